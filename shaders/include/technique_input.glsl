// What a pass that evaluates a technique (visibility.comp, filter_probe.comp) hands it: its entry
// point `vec4 evaluate<Name>(TechniqueInput at)` (technique_list.h, techniques.glsl) returns x
// the visibility and yzw its intermediate results (what the parity tests and the viewer read).
// The maps, table and field a technique may read are declared here, at the same bindings in both
// passes (TECH_*, bindings.h); each technique declares its own parameter block
// (technique_block.h) and specialization constants.
#ifndef PENUMBRA_TECHNIQUE_INPUT_GLSL
#define PENUMBRA_TECHNIQUE_INPUT_GLSL
#include "bindings.h"
#include "light_geometry.h"
#include "receiver.glsl"

// The maps its module lists (visibilityMaps): float ones in shadowMaps, integer ones in
// shadowTables, each kind in the order listed; shadowMap and shadowTable are the first of each.
layout(set = 0, binding = TECH_MAP) uniform sampler2DArray shadowMaps[TECH_MAX_MAPS];
layout(set = 0, binding = TECH_COMPARE) uniform sampler2DArrayShadow shadowMapCmp;
layout(set = 0, binding = TECH_TABLE) uniform usampler2DArray shadowTables[TECH_MAX_MAPS];
#define shadowMap shadowMaps[0]
#define shadowTable shadowTables[0]
layout(set = 0, binding = TECH_FIELD) uniform sampler3D distanceField;

// What a technique with a blocker search (SPEC_BLOCKER_SEARCH) is asked for: the whole filter, the
// search alone (x blocking texels found, y their average depth in this view), or the filter alone
// after a search in another view (a sun's cascade whose texels hold the search).
#define STAGE_WHOLE 0u
#define STAGE_SEARCH 1u
#define STAGE_FILTER 2u

struct TechniqueInput {
    Receiver r;          // where the receiver falls in the view's maps
    ShadowViewData view; // the shadow view it is read through
    uint mapSize;        // texels a side
    uvec2 pixel;         // the pixel (per-pixel rotations)
    uint stage;          // STAGE_*
    vec2 blockers;       // STAGE_FILTER: the search's result ...
    float zBlocker;      // ... and its blockers' light view distance
    // A technique that traces the scene's distance field (SPEC_TRACES_FIELD) reads these instead:
    LightData light;
    vec3 world, face;    // the receiver and its triangle's normal
    float sinRadius;     // the light's angular radius seen from it
    bool horizon;        // bias.horizon applies: the tracer clips the light at the surface
};

#endif
