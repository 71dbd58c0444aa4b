// The binding contract of every pass: descriptor bindings (set 0, push descriptors; the shaders
// declare `layout(binding = X)`, src/render/pipelines.cpp builds each pass's layout from the
// same names, the passes in src/render write them), specialization-constant ids, and workgroup
// sizes. Compiled as GLSL and as C++.
// clang-format off
#ifndef PENUMBRA_BINDINGS_H
#define PENUMBRA_BINDINGS_H

// Specialization-constant ids of visibility.comp and filter_probe.comp (the pipeline key is the
// list of (id, value) pairs: src/shadows/technique.h).
#define SPEC_TECHNIQUE 0         // the technique's id (shaders/include/technique_list.h)
#define SPEC_FILTER 1            // pcf.filter (pcf's own, shadow_pcf.glsl)
#define SPEC_RECEIVER 2
#define SPEC_HORIZON 3           // 1: the visibility pass applies bias.horizon
#define SPEC_LIGHT_TYPE 4        // the visibility dispatch's light: LIGHT_*
#define SPEC_LIGHT_VIEWS 5       // ... and how many shadow views it has
#define SPEC_SCENE_LIGHTS 6      // shading.glsl: the scene's lights (0: more than
                                 // MAX_SPECIALIZED_LIGHTS, counted at run time)
#define SPEC_SCENE_LIGHT_TYPES 7 // ... their LIGHT_* kinds, two bits each
#define SPEC_FUSED_COMPOSITE 8   // 1: this visibility dispatch (the last light's) also shades
#define MAX_SPECIALIZED_LIGHTS 16u
#define SPEC_CASCADE_BLEND 9     // 1: csm.blend > 0 (the blend band evaluates two cascades)
#define SPEC_MATERIAL_TEXTURE 10 // gbuffer.frag: MaterialPush::hasTexture ...
#define SPEC_MATERIAL_ALPHA_TEST 11 // ... and alphaTest, fixed per pipeline
#define SPEC_MATERIAL_VERTEX_COLOR 12 // 0: the batch's vertex colours are all opaque white
#define SPEC_ADAPTIVE_BIAS 13    // 1: bias.mode=adaptive (the visibility pass's receiver terms)
#define SPEC_FOOTPRINT 14        // 1: the technique reads the pixel's footprint in the map
                                 // (TechniqueModule::readsFootprint: vsm.filter=mip)
#define SPEC_INTERMEDIATES 15    // 1: the visibility pass also writes VIS_INTERMEDIATES (viewer)
#define SPEC_BLOCKER_SEARCH 16   // 1: the technique searches blockers, in a sun's cascades as its
                                 // kernel follows the light's size (TechniqueModule::searchCap)
#define SPEC_TRACES_FIELD 17     // 1: the technique traces the scene's distance field, not a map
                                 // (TechniqueModule::tracedField)
#define SPEC_VIRTUAL 18          // 1: the maps are virtual (virtual.enabled): TECH_MAP is the
                                 // page pool, read through the page table (virtual_pages.h)
#define SPEC_FILTER_RADIUS 19    // visibility_filter.comp: its radius in pixels,
#define SPEC_FILTER_TOLERANCE 20 // ... its range tolerance (a float's bits)
#define SPEC_FILTER_AXIS 21      // ... and its pass: 0 along rows, 1 along columns
#define SPEC_SMRT_HIDDEN 22     // smrt.hidden (smrt's own, shadow_smrt.glsl)
#define SPEC_FILTER_WIDE 23     // visibility_filter.comp: its radius inside wide penumbrae
#define SPEC_CHECKERBOARD 24    // visibility.comp: which pixels it traces (CHECKERBOARD_*,
                                // checkerboard.h)
#define SPEC_PROBE_SLOTS 26      // filter_probe.comp: 1 returns shadowMaps[0..3] at the receiver's
                                 // texel, 2 shadowTables[0..3] (as float bits), 3 all four
                                 // channels of shadowTables[0] (as float bits), not the technique
#define SPEC_FILL_RANGE 25      // visibility_fill.comp: the range of the neighbours it fills from
                                // (a float's bits)
#define SPEC_GBUFFER_MOTION 28  // gbuffer.vert, gbuffer.frag: 1 writes the motion vectors
#define SPEC_TRANSLUCENT_METHOD 30 // translucent.comp: TRANSLUCENT_COLOURED or _MOMENTS
#define SPEC_COMPOSITE_COLOURED 31 // composite.comp: 1 reads COMPOSITE_TRANSMITTANCE (a light's
                                   // tint from the translucent layer)
#define SPEC_HISTORY_RESOLVE 29 // a layer that keeps a history (temporal.comp): 0 writes this
                                // frame's history, 1 then copies it into the visibility

// Descriptor bindings, pass by pass.
#define BIND_FRAME 0             // FrameData, in every pass that reads it
// What a technique reads, at the same bindings in every pass that evaluates one (visibility.comp,
// filter_probe.comp; shaders/include/technique_input.glsl declares them) and, for its parameter
// block, in its post passes.
#define TECH_MAX_MAPS 4          // maps of each kind (float, integer) its visibility pass reads
#define TECH_MAP 4               // the technique's float maps, every view (nearest): an array of
                                 // TECH_MAX_MAPS in the order its module lists them
                                 // (visibilityMaps); slots it leaves hold the depth map
#define TECH_COMPARE 5           // the depth map, every view (comparison sampler)
#define TECH_TABLE 8             // its integer maps likewise (usampler2DArray[TECH_MAX_MAPS]);
                                 // slots it leaves hold a placeholder
#define TECH_FIELD 9             // the scene's distance field (a 1x1x2 placeholder when the
                                 // technique traces none), trilinear
#define TECH_PARAMS 18           // the technique's parameter block (technique_block.h)
#define TECH_PAGE_TABLE 19       // virtual maps' page table: uint[], an entry per page
#define MARK_LIGHTS 1            // page_marking.comp: LightData[], uniform
#define MARK_GBUFFER_DEPTH 2
#define MARK_VIEWS 3             // ShadowViewData[], uniform
#define MARK_REQUESTS 4          // uint[], an entry per page (page-table layout): 1 requested
#define MARK_GBUFFER_NORMAL 5
#define MARK_BLOCK 4u            // the page marking reads one pixel of MARK_BLOCK^2
#define VIS_LIGHTS 1             // visibility.comp: LightData[], uniform
#define VIS_GBUFFER_DEPTH 2
#define VIS_GBUFFER_NORMAL 3
#define VIS_OUT 6                // R32F array, a layer per shadow-casting light
#define VIS_VIEWS 7              // ShadowViewData[], uniform
#define VIS_INTERMEDIATES 10     // RGBA32F array, a layer per shadow-casting light: the
                                 // technique's intermediate results (evaluateTechnique's yzw),
                                 // written with SPEC_INTERMEDIATES (a 1x1 placeholder otherwise)
#define VIS_GBUFFER_ALBEDO 11    // read and ...
#define VIS_COLOR 12             // ... written by a dispatch with SPEC_FUSED_COMPOSITE (RGBA8)
#define VIS_TRACE_LIST 13        // checkerboard.h's trace list, read with CHECKERBOARD_LIST (a
                                 // placeholder of one head otherwise)
#define COMPOSITE_LIGHTS 1       // composite.comp: LightData[], uniform
#define COMPOSITE_GBUFFER_DEPTH 2
#define COMPOSITE_GBUFFER_NORMAL 3
#define COMPOSITE_GBUFFER_ALBEDO 4
#define COMPOSITE_VISIBILITY 5
#define COMPOSITE_OUT 6
#define COMPOSITE_TRANSMITTANCE 7 // RGBA32F array, the translucent layer's light per channel, read
                                  // with SPEC_COMPOSITE_COLOURED (the visibility otherwise)
// A layer's pass (src/shadows/layer.h; contact.comp): per shadow-casting light, multiplies what
// it finds into the light's visibility layer. Push constants: VisibilityPush.
#define LAYER_LIGHTS 1           // LightData[], uniform
#define LAYER_GBUFFER_DEPTH 2
#define LAYER_GBUFFER_NORMAL 3
#define LAYER_VISIBILITY 4       // R32F array, a layer per shadow-casting light, read and written
#define LAYER_PARAMS 5           // the layer's parameter block (uniform)
#define LAYER_RESULTS 6          // R32F array: the layer's own factor, with SPEC_INTERMEDIATES (a
                                 // 1x1 placeholder otherwise; the viewer's debug view)
#define LAYER_TRACE_LIST 7       // checkerboard.h's trace list: visibility_fill.comp appends to it
// A layer that keeps a history (LayerModule::history; temporal.comp), on a layout of its own:
#define LAYER_MOTION 8           // the G-buffer's motion vectors (gbuffer.motion)
#define LAYER_HISTORY_PREVIOUS 9 // its history as last frame wrote it (zeros where none), and
#define LAYER_HISTORY 10         // this frame's, written: a layer per shadow-casting light
// The translucent layer (src/shadows/translucent.cpp): its caster draws (translucent_*.frag) ...
#define TRANSLUCENT_TEXTURE_BINDING 0 // the caster's base colour texture (sRGB view)
#define TRANSLUCENT_OPAQUE_DEPTH 1    // the light's depth map, every view a layer (nearest)
#define TRANSLUCENT_VIEWS 2           // ShadowViewData[], uniform
#define TRANSLUCENT_NEAREST_DEPTH 3   // the coloured map's nearest depths (its second's peel; the
                                      // light's depth map, unread, in the other draws)
#define TRANSLUCENT_TRANSMISSION_TEXTURE 4 // the caster's transmission texture (UNORM view: its
                                           // bytes stored linear; white when it has none)
// ... and its pass (translucent.comp) on a layout of its own, beside the LAYER_* bindings:
#define TRANSLUCENT_LAYER_VIEWS 11    // ShadowViewData[], uniform
#define TRANSLUCENT_LAYER_NEAREST 12  // the coloured map's nearest depths and its second nearest
#define TRANSLUCENT_LAYER_SECOND 14   // (the first moment map stands in for both with the moments)
#define TRANSLUCENT_LAYER_MAPS 13     // TRANSLUCENT_MAPS maps: the nearest's transmittance and the
                                      // product (the product again in the last two slots), or
                                      // the absorbance and the three channels' moments
#define TRANSLUCENT_LAYER_COLOUR 15   // RGBA32F array, a layer per light: the light per channel
#define TRANSLUCENT_MAPS 4
#define EXPORT_GBUFFER_DEPTH 1   // export.comp
#define EXPORT_GBUFFER_NORMAL 2
#define EXPORT_POSITION 3
#define EXPORT_NORMAL 4
#define EXPORT_FACE_NORMAL 5     // the triangle's own normal (the contact layer's CPU reference)
#define PROBE_RECEIVERS 1        // filter_probe.comp (and the TECH_* bindings)
#define PROBE_RESULTS 2
#define PROBE_VIEW 3
#define GBUFFER_TEXTURE 1        // gbuffer.frag: the material's base colour
#define GBUFFER_PREVIOUS_POSITIONS 2 // gbuffer.vert: each vertex's position in the last frame
                                 // (floats, three a vertex; FrameData::motion.x)
#define MASK_TEXTURE 0           // shadow_mask.frag: the alpha-tested caster's texture
#define READ_MAP 0               // a technique's extra depth pass (shadow_peel.frag): the map
#define READ_TEXTURE 1           // it reads, and the caster's texture
#define FIELD_TRIANGLES 0        // the distance field's build passes (sdf_seed, sdf_flood,
#define FIELD_BRICK_STARTS 1     // sdf_resolve): FieldTriangle[], each brick's first entry in
#define FIELD_BRICK_LIST 2       // the brick list (one past the last brick: its end), the list
#define FIELD_IDS_IN 3           // of triangle indices; nearest-triangle ids (R32UI, 3D) read
#define FIELD_IDS_OUT 4          // and written; the field (R32F, 3D) written; each brick's
#define FIELD_OUT 5              // candidates for its far voxels
#define FIELD_FAR_CANDIDATES 6
#define SKIN_BIND_VERTICES 0     // skin.comp: SkinVertex[] (skinning.h), SkinInfluence[], the
#define SKIN_INFLUENCES 1        // joint matrices (mat4[]), read; the vertex buffer (as floats)
#define SKIN_JOINTS 2            // and the positions buffer, written
#define SKIN_VERTICES 3
#define SKIN_POSITIONS 4

// A shadow-map post pass samples its inputs at bindings POST_INPUT_BINDING + i and writes its
// outputs at POST_OUTPUT_BINDING + i (src/shadows/technique.h, PostPassDecl); its technique's
// parameter block is at TECH_PARAMS.
#define POST_INPUT_BINDING 0
#define POST_OUTPUT_BINDING 8
#define POST_MAX_MAPS 8
#define POST_VIEWS_BINDING 17   // ShadowViewData[], uniform; PostPassPush.size.z: the view

#define GROUP_SIZE 8u           // screen-space and per-texel passes: GROUP_SIZE^2 invocations
#define LINE_GROUP_SIZE 64u     // post passes dispatched one invocation per row or column

#endif
// clang-format on
