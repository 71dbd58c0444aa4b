#include "render/pipelines.h"

#include "bindings.h"
#include "pass_types.h"
#include "penumbra/error.h"
#include "penumbra/scene.h"
#include "skinning.h"
#include "translucent.h"
#include "vk/spirv_bindings.h"

#include <cstddef>
#include <fmt/format.h>

namespace penumbra::render {
namespace {

// The module of a pass that evaluates techniques, for the technique its constants name:
// `<shader>#<id>` holds that technique's code alone (cmake/Shaders.cmake, PER_TECHNIQUE).
std::string techniqueModule(std::string_view shader,
                            const std::vector<shadows::SpecConstant>& constants) {
    for (const shadows::SpecConstant& c : constants)
        if (c.id == SPEC_TECHNIQUE)
            return std::string(shader) + "#" + std::to_string(c.value);
    PENUMBRA_CHECK(false, std::string(shader) + ": no technique among its constants");
    return {};
}

constexpr VkDescriptorType kUniform = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
constexpr VkDescriptorType kStorage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
constexpr VkDescriptorType kImage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;

constexpr VkShaderStageFlags kGraphicsStages =
    VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;

VkVertexInputAttributeDescription attribute(uint32_t location, VkFormat format, uint32_t offset) {
    return {.location = location, .binding = 0, .format = format, .offset = offset};
}

vk::GraphicsPipelineDesc shadowDesc(bool depthClamp, std::string_view fragment = {}) {
    return {.vertexShader = "shadow_depth.vert",
            .fragmentShader = fragment,
            .vertexStride = sizeof(Vertex),
            .attributes = {attribute(0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)),
                           attribute(1, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)),
                           attribute(2, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, color))},
            .depthFormat = kDepthFormat,
            .depthCompare = VK_COMPARE_OP_LESS_OR_EQUAL,
            .depthClamp = depthClamp,
            .depthBias = true};
}

// The opaque casters' pipeline: positions only (GpuScene::positions), no fragment stage.
vk::GraphicsPipelineDesc positionOnlyDesc(bool depthClamp) {
    return {.vertexShader = "shadow_position.vert",
            .vertexStride = sizeof(glm::vec3),
            .attributes = {attribute(0, VK_FORMAT_R32G32B32_SFLOAT, 0)},
            .depthFormat = kDepthFormat,
            .depthCompare = VK_COMPARE_OP_LESS_OR_EQUAL,
            .depthClamp = depthClamp,
            .depthBias = true};
}

} // namespace

FramePipelines::FramePipelines(const vk::Context& context) : ctx(context) {
    shadowLayout =
        vk::createPipelineLayout(ctx, {}, VK_SHADER_STAGE_VERTEX_BIT, sizeof(gpu::ShadowPush));
    // Binding numbers: bindings.h, shared with the shaders.
    // Passes whose shaders alone say what they bind: their layouts read from the SPIR-V.
    shadowMaskLayout =
        vk::createLayoutOf(ctx, {"shadow_depth.vert", "shadow_mask.frag"}, kGraphicsStages,
                           sizeof(gpu::ShadowPush) + sizeof(gpu::MaterialPush));
    gbufferLayout = vk::createLayoutOf(ctx, {"gbuffer.vert", "gbuffer.frag"}, kGraphicsStages,
                                       sizeof(gpu::MaterialPush));
    visibilityLayout =
        vk::createPipelineLayout(ctx,
                                 {{BIND_FRAME, kUniform},
                                  {VIS_LIGHTS, kUniform},
                                  {VIS_GBUFFER_DEPTH, kSampled},
                                  {VIS_GBUFFER_NORMAL, kSampled},
                                  {TECH_MAP, kSampled, TECH_MAX_MAPS},
                                  {TECH_COMPARE, kSampled},
                                  {VIS_OUT, kImage},
                                  {VIS_VIEWS, kUniform},
                                  {TECH_TABLE, kSampled, TECH_MAX_MAPS},
                                  {TECH_FIELD, kSampled},
                                  {TECH_PARAMS, kUniform},
                                  {VIS_INTERMEDIATES, kImage},
                                  {VIS_GBUFFER_ALBEDO, kSampled},
                                  {VIS_COLOR, kImage},
                                  {TECH_PAGE_TABLE, kStorage},
                                  {VIS_TRACE_LIST, kStorage}},
                                 VK_SHADER_STAGE_COMPUTE_BIT, sizeof(gpu::VisibilityPush));
    markingLayout = vk::createLayoutOf(ctx, {"page_marking.comp"}, VK_SHADER_STAGE_COMPUTE_BIT,
                                       sizeof(gpu::VisibilityPush));
    compositeLayout = vk::createLayoutOf(ctx, {"composite.comp"}, VK_SHADER_STAGE_COMPUTE_BIT, 0);
    exportLayout = vk::createLayoutOf(ctx, {"export.comp"}, VK_SHADER_STAGE_COMPUTE_BIT, 0);
    probeLayout = vk::createPipelineLayout(ctx,
                                           {{BIND_FRAME, kUniform},
                                            {PROBE_RECEIVERS, kStorage},
                                            {PROBE_RESULTS, kStorage},
                                            {PROBE_VIEW, kStorage},
                                            {TECH_MAP, kSampled, TECH_MAX_MAPS},
                                            {TECH_COMPARE, kSampled},
                                            {TECH_TABLE, kSampled, TECH_MAX_MAPS},
                                            {TECH_FIELD, kSampled},
                                            {TECH_PARAMS, kUniform},
                                            {TECH_PAGE_TABLE, kStorage}},
                                           VK_SHADER_STAGE_COMPUTE_BIT, sizeof(gpu::ProbePush));
    layerLayout =
        vk::createPipelineLayout(ctx,
                                 {{BIND_FRAME, kUniform},
                                  {LAYER_LIGHTS, kUniform},
                                  {LAYER_GBUFFER_DEPTH, kSampled},
                                  {LAYER_GBUFFER_NORMAL, kSampled},
                                  {LAYER_VISIBILITY, kImage},
                                  {LAYER_PARAMS, kUniform},
                                  {LAYER_RESULTS, kImage},
                                  {LAYER_TRACE_LIST, kStorage}},
                                 VK_SHADER_STAGE_COMPUTE_BIT, sizeof(gpu::VisibilityPush));
    readingDepthLayout = vk::createPipelineLayout(
        ctx, {{READ_MAP, kSampled}, {READ_TEXTURE, kSampled}}, kGraphicsStages,
        sizeof(gpu::ShadowPush) + sizeof(gpu::MaterialPush));
    shadowOrtho = vk::createGraphicsPipeline(ctx, shadowLayout, positionOnlyDesc(true));
    shadowPerspective = vk::createGraphicsPipeline(ctx, shadowLayout, positionOnlyDesc(false));
    shadowMaskOrtho =
        vk::createGraphicsPipeline(ctx, shadowMaskLayout, shadowDesc(true, "shadow_mask.frag"));
    shadowMaskPerspective =
        vk::createGraphicsPipeline(ctx, shadowMaskLayout, shadowDesc(false, "shadow_mask.frag"));
    exportGBuffer = vk::createComputePipeline(ctx, exportLayout, "export.comp");
}

VkPipeline FramePipelines::specialized(std::map<Constants, vk::PipelineHandle>& cache,
                                       const vk::PipelineLayout& layout, std::string_view shader,
                                       const Constants& constants) {
    auto it = cache.find(constants);
    if (it == cache.end()) {
        std::vector<vk::SpecConstant> values;
        for (const shadows::SpecConstant& c : constants)
            values.push_back({.id = c.id, .value = c.value});
        it = cache.emplace(constants, vk::createComputePipeline(ctx, layout, shader, values)).first;
    }
    return it->second.get();
}

VkPipeline FramePipelines::marking(const Constants& constants) {
    return specialized(mMarking, markingLayout, "page_marking.comp", constants);
}

VkPipeline FramePipelines::visibility(const Constants& constants) {
    return specialized(mVisibility, visibilityLayout, techniqueModule("visibility.comp", constants),
                       constants);
}

VkPipeline FramePipelines::gbuffer(GBufferVariant v) {
    vk::PipelineHandle& pipeline = mGbuffer[(v.motion ? 8 : 0) + (v.texture ? 4 : 0) +
                                            (v.alphaTest ? 2 : 0) + (v.vertexColors ? 1 : 0)];
    if (!pipeline)
        pipeline = vk::createGraphicsPipeline(
            ctx, gbufferLayout,
            {.vertexShader = "gbuffer.vert",
             .fragmentShader = "gbuffer.frag",
             .vertexStride = sizeof(Vertex),
             .attributes = {attribute(0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)),
                            attribute(1, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)),
                            attribute(2, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)),
                            attribute(3, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, color))},
             .colorFormats = v.motion ? std::vector{kNormalFormat, kAlbedoFormat, kMotionFormat}
                                      : std::vector{kNormalFormat, kAlbedoFormat},
             .depthFormat = kDepthFormat,
             .depthCompare = VK_COMPARE_OP_GREATER_OR_EQUAL, // reverse-Z
             .dynamicCullMode = true,
             .constants = {{SPEC_MATERIAL_TEXTURE, v.texture ? 1u : 0u},
                           {SPEC_MATERIAL_ALPHA_TEST, v.alphaTest ? 1u : 0u},
                           {SPEC_MATERIAL_VERTEX_COLOR, v.vertexColors ? 1u : 0u},
                           {SPEC_GBUFFER_MOTION, v.motion ? 1u : 0u}}});
    return pipeline.get();
}

VkPipeline FramePipelines::composite(const Constants& constants) {
    return specialized(mComposite, compositeLayout, "composite.comp", constants);
}

const FramePipelines::HistoryLayerPipeline& FramePipelines::historyLayer(std::string_view shader) {
    auto it = mHistoryLayers.find(shader);
    if (it == mHistoryLayers.end()) {
        HistoryLayerPipeline made{.layout =
                                      vk::createLayoutOf(ctx, {shader}, VK_SHADER_STAGE_COMPUTE_BIT,
                                                         sizeof(gpu::VisibilityPush))};
        const vk::SpecConstant blend{.id = SPEC_HISTORY_RESOLVE, .value = 0u},
            resolve{.id = SPEC_HISTORY_RESOLVE, .value = 1u};
        made.blend = vk::createComputePipeline(ctx, made.layout, shader, std::span(&blend, 1));
        made.resolve = vk::createComputePipeline(ctx, made.layout, shader, std::span(&resolve, 1));
        it = mHistoryLayers.emplace(std::string(shader), std::move(made)).first;
    }
    return it->second;
}

VkPipeline FramePipelines::layer(std::string_view shader, const Constants& constants) {
    const auto key = std::make_pair(std::string(shader), constants);
    auto it = mLayers.find(key);
    if (it == mLayers.end()) {
        std::vector<vk::SpecConstant> values;
        for (const shadows::SpecConstant& c : constants)
            values.push_back({.id = c.id, .value = c.value});
        it =
            mLayers.emplace(key, vk::createComputePipeline(ctx, layerLayout, shader, values)).first;
    }
    return it->second.get();
}

VkPipeline FramePipelines::probe(const Constants& constants) {
    return specialized(mProbe, probeLayout, techniqueModule("filter_probe.comp", constants),
                       constants);
}

VkPipeline FramePipelines::readingDepthPass(std::string_view fragmentShader, bool perspective) {
    const auto key = std::make_pair(std::string(fragmentShader), perspective);
    auto it = mReadingDepth.find(key);
    if (it == mReadingDepth.end())
        it = mReadingDepth
                 .emplace(key, vk::createGraphicsPipeline(ctx, readingDepthLayout,
                                                          shadowDesc(!perspective, fragmentShader)))
                 .first;
    return it->second.get();
}

const vk::PipelineLayout& FramePipelines::postPassLayout(uint32_t inputs, uint32_t outputs) {
    PENUMBRA_CHECK(inputs <= POST_MAX_MAPS && outputs <= POST_MAX_MAPS, "post pass maps");
    auto it = mPostLayouts.find({inputs, outputs});
    if (it == mPostLayouts.end()) {
        std::vector<vk::Binding> bindings;
        for (uint32_t i = 0; i < inputs; ++i)
            bindings.push_back({POST_INPUT_BINDING + i, kSampled});
        for (uint32_t i = 0; i < outputs; ++i)
            bindings.push_back({POST_OUTPUT_BINDING + i, kImage});
        bindings.push_back({TECH_PARAMS, kUniform});
        bindings.push_back({POST_VIEWS_BINDING, kUniform});
        it = mPostLayouts
                 .emplace(std::make_pair(inputs, outputs),
                          vk::createPipelineLayout(ctx, bindings, VK_SHADER_STAGE_COMPUTE_BIT,
                                                   sizeof(gpu::PostPassPush)))
                 .first;
    }
    return it->second;
}

VkPipeline FramePipelines::postPass(std::string_view shader, uint32_t inputs,
                                    std::span<const VkFormat> outputs) {
    const auto count = static_cast<uint32_t>(outputs.size());
    auto it = mPost.find(shader);
    if (it == mPost.end()) {
        PostPipeline made{.pipeline =
                              vk::createComputePipeline(ctx, postPassLayout(inputs, count), shader),
                          .inputs = inputs,
                          .outputs = count};
        for (const vk::Binding& b : vk::reflectEmbedded(shader))
            if (b.binding >= POST_OUTPUT_BINDING && b.binding < POST_OUTPUT_BINDING + POST_MAX_MAPS)
                made.declared[b.binding - POST_OUTPUT_BINDING] = b.format;
        it = mPost.emplace(std::string(shader), std::move(made)).first;
    }
    // Made once per shader: a second declaration with other counts would bind the first's layout.
    PENUMBRA_CHECK(it->second.inputs == inputs && it->second.outputs == count,
                   fmt::format("post pass {}: declared with {} inputs and {} outputs, and before "
                               "with {} and {}",
                               shader, inputs, count, it->second.inputs, it->second.outputs));
    for (uint32_t i = 0; i < count; ++i) {
        const std::string why = vk::storageFormatMismatch(it->second.declared[i], outputs[i]);
        PENUMBRA_CHECK(why.empty(), fmt::format("post pass {}: output {} (binding {}): {}", shader,
                                                i, POST_OUTPUT_BINDING + i, why));
    }
    return it->second.pipeline.get();
}

const vk::PipelineLayout& FramePipelines::translucentCasterLayout() {
    if (!mTranslucentCasterLayout
             .layout) // the moments' and the peel's draws bind all the others do
        mTranslucentCasterLayout = vk::createLayoutOf(
            ctx, {"translucent_caster.vert", "translucent_moments.frag", "translucent_second.frag"},
            kGraphicsStages, sizeof(gpu::TranslucentCasterPush));
    return mTranslucentCasterLayout;
}

const vk::PipelineLayout& FramePipelines::translucentLayerLayout() {
    if (!mTranslucentLayerLayout.layout)
        mTranslucentLayerLayout = vk::createLayoutOf(
            ctx, {"translucent.comp"}, VK_SHADER_STAGE_COMPUTE_BIT, sizeof(gpu::VisibilityPush));
    return mTranslucentLayerLayout;
}

VkPipeline FramePipelines::translucentCaster(uint32_t draw, bool perspective) {
    const auto key = std::make_pair(draw, perspective);
    auto it = mTranslucentCasters.find(key);
    if (it == mTranslucentCasters.end()) {
        vk::GraphicsPipelineDesc desc = shadowDesc(!perspective);
        desc.vertexShader = "translucent_caster.vert";
        desc.depthBias = false; // the constant bias alone: the moments' depth reads it too
        // The depth tests keep the first drawn of surfaces at one depth (as colouredTexel does).
        desc.depthCompare = VK_COMPARE_OP_LESS;
        if (draw == TRANSLUCENT_DRAW_NEAREST) {
            desc.fragmentShader = "translucent_nearest.frag";
            desc.colorFormats = {kTranslucentProductFormat};
        } else if (draw == TRANSLUCENT_DRAW_SECOND) {
            desc.fragmentShader = "translucent_second.frag";
        } else {
            desc.depthFormat = VK_FORMAT_UNDEFINED; // every surface counts, in any order
            desc.fragmentShader = draw == TRANSLUCENT_DRAW_PRODUCT ? "translucent_product.frag"
                                                                   : "translucent_moments.frag";
            desc.colorFormats =
                draw == TRANSLUCENT_DRAW_PRODUCT
                    ? std::vector{kTranslucentProductFormat}
                    : std::vector<VkFormat>(TRANSLUCENT_MAPS, kTranslucentMomentsFormat);
            desc.blend = draw == TRANSLUCENT_DRAW_PRODUCT ? vk::Blend::Multiply : vk::Blend::Add;
        }
        it = mTranslucentCasters
                 .emplace(key, vk::createGraphicsPipeline(ctx, translucentCasterLayout(), desc))
                 .first;
    }
    return it->second.get();
}

VkPipeline FramePipelines::translucentLayer(const Constants& constants) {
    return specialized(mTranslucentLayer, translucentLayerLayout(), "translucent.comp", constants);
}

const FieldPipelines& FramePipelines::field() {
    if (!mField) {
        auto f = std::make_unique<FieldPipelines>();
        f->layout = vk::createLayoutOf(ctx, {"sdf_seed.comp", "sdf_flood.comp", "sdf_resolve.comp"},
                                       VK_SHADER_STAGE_COMPUTE_BIT, sizeof(gpu::FieldPush));
        f->seed = vk::createComputePipeline(ctx, f->layout, "sdf_seed.comp");
        f->flood = vk::createComputePipeline(ctx, f->layout, "sdf_flood.comp");
        f->resolve = vk::createComputePipeline(ctx, f->layout, "sdf_resolve.comp");
        mField = std::move(f);
    }
    return *mField;
}

const SkinPipeline& FramePipelines::skin() {
    if (!mSkin) {
        auto s = std::make_unique<SkinPipeline>();
        s->layout = vk::createLayoutOf(ctx, {"skin.comp"}, VK_SHADER_STAGE_COMPUTE_BIT,
                                       sizeof(gpu::SkinPush));
        s->pipeline = vk::createComputePipeline(ctx, s->layout, "skin.comp");
        mSkin = std::move(s);
    }
    return *mSkin;
}

} // namespace penumbra::render
