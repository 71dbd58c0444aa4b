#pragma once
// Every pipeline of the frame (docs/architecture.md), created once per Renderer. What depends on
// the technique is made on first use from what its module declares: the visibility pass per list of
// specialization constants, extra depth passes per fragment shader, post passes per shader.
#include "bindings.h"
#include "penumbra/settings.h"
#include "shadows/technique.h"
#include "vk/pipelines.h"

#include <array>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace penumbra::render {

// The `skin` pass (shaders/skin.comp).
struct SkinPipeline {
    vk::PipelineLayout layout;
    vk::PipelineHandle pipeline;
};

// The distance field's build passes (src/render/distance_field.h), one layout for the three.
struct FieldPipelines {
    vk::PipelineLayout layout;
    vk::PipelineHandle seed, flood, resolve;
};

class FramePipelines {
public:
    explicit FramePipelines(const vk::Context& ctx);

    const vk::Context& ctx;
    vk::PipelineLayout shadowLayout, gbufferLayout, visibilityLayout, compositeLayout, exportLayout,
        probeLayout;
    vk::PipelineLayout readingDepthLayout; // extra depth passes that read a map (depth peels)
    vk::PipelineLayout layerLayout;        // the layers' passes (LAYER_* bindings)
    vk::PipelineLayout markingLayout;      // virtual maps' page marking (MARK_* bindings)
    vk::PipelineLayout shadowMaskLayout;   // alpha-tested casters
    vk::PipelineHandle shadowOrtho;        // depth clamp on: casters before the near plane clamp
    vk::PipelineHandle shadowPerspective;  // depth clamp off
    vk::PipelineHandle shadowMaskOrtho, shadowMaskPerspective; // alpha-tested casters
    vk::PipelineHandle exportGBuffer;

    // The G-buffer pass for a batch: its material's flags (MaterialPush::hasTexture, alphaTest)
    // and whether its vertices are coloured (DrawBatch::vertexColors); `motion`: the frame
    // writes motion vectors too (a third target, kMotionFormat).
    struct GBufferVariant {
        bool texture, alphaTest, vertexColors, motion = false;
    };
    VkPipeline gbuffer(GBufferVariant variant);

    // The visibility pass (and the parity tests' probe) for one list of specialization
    // constants (shadows::visibilityConstants), made on first use.
    VkPipeline visibility(const std::vector<shadows::SpecConstant>& constants);
    VkPipeline probe(const std::vector<shadows::SpecConstant>& constants);
    // Virtual maps' page marking for one light kind (SPEC_LIGHT_TYPE).
    VkPipeline marking(const std::vector<shadows::SpecConstant>& constants);
    // The composite on its own, for the scene's lights (sceneLightConstants).
    VkPipeline composite(const std::vector<shadows::SpecConstant>& constants);
    // A layer's pass (src/shadows/layer.h) for one list of specialization constants.
    VkPipeline layer(std::string_view shader, const std::vector<shadows::SpecConstant>& constants);
    // A layer that keeps a history (shadows::LayerModule::history): its own layout, read from
    // its shader (bindings.h, LAYER_*), and its pipeline.
    struct HistoryLayerPipeline {
        vk::PipelineLayout layout;
        vk::PipelineHandle blend, resolve; // SPEC_HISTORY_RESOLVE 0 and 1
    };
    const HistoryLayerPipeline& historyLayer(std::string_view shader);
    // A technique's extra depth pass: the shadow pass's vertex stage and state with
    // `fragmentShader`, which reads a map at binding 0 (readingDepthLayout).
    VkPipeline readingDepthPass(std::string_view fragmentShader, bool perspective);
    // A technique's post pass and its layout: `inputs` sampled maps, a storage image of each
    // format of `outputs`. Fatal where the shader declares an output's format (`layout(rg32f)`)
    // other than its map's: a device would write the map as the wrong format without a word.
    VkPipeline postPass(std::string_view shader, uint32_t inputs,
                        std::span<const VkFormat> outputs);
    const vk::PipelineLayout& postPassLayout(uint32_t inputs, uint32_t outputs);
    // The translucent layer's caster draws into its maps (TRANSLUCENT_DRAW_*: the nearest
    // depth, the product, the moments), made on first use, and its pass for one list of
    // specialization constants (light type and views, SPEC_TRANSLUCENT_METHOD).
    VkPipeline translucentCaster(uint32_t draw, bool perspective);
    VkPipeline translucentLayer(const std::vector<shadows::SpecConstant>& constants);
    const vk::PipelineLayout& translucentCasterLayout();
    const vk::PipelineLayout& translucentLayerLayout();
    // Made on first use: only the sdf technique builds a field.
    const FieldPipelines& field();
    // Made on first use: only a skinned scene has a `skin` pass.
    const SkinPipeline& skin();

private:
    using Constants = std::vector<shadows::SpecConstant>;
    VkPipeline specialized(std::map<Constants, vk::PipelineHandle>& cache,
                           const vk::PipelineLayout& layout, std::string_view shader,
                           const Constants& constants);
    std::map<Constants, vk::PipelineHandle> mVisibility, mProbe, mComposite, mMarking;
    std::map<std::pair<std::string, Constants>, vk::PipelineHandle, std::less<>> mLayers;
    std::map<std::pair<std::string, bool>, vk::PipelineHandle> mReadingDepth;
    std::map<std::pair<uint32_t, uint32_t>, vk::PipelineLayout> mPostLayouts;
    struct PostPipeline {
        vk::PipelineHandle pipeline;
        uint32_t inputs = 0, outputs = 0;               // its layout's
        std::array<VkFormat, POST_MAX_MAPS> declared{}; // its outputs' formats, as the shader says
    };
    std::map<std::string, PostPipeline, std::less<>> mPost;
    std::unique_ptr<FieldPipelines> mField;
    std::unique_ptr<SkinPipeline> mSkin;
    std::map<std::string, HistoryLayerPipeline, std::less<>> mHistoryLayers;
    vk::PipelineLayout mTranslucentCasterLayout, mTranslucentLayerLayout;
    std::map<std::pair<uint32_t, bool>, vk::PipelineHandle> mTranslucentCasters;
    std::map<Constants, vk::PipelineHandle> mTranslucentLayer;
    std::array<vk::PipelineHandle, 16> mGbuffer;
};

inline constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
inline constexpr VkFormat kNormalFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kAlbedoFormat = VK_FORMAT_R8G8B8A8_UNORM;
// Motion vectors: x, y in pixels and the last frame's depth; float32, so that a test's tolerance
// is the projection's rounding alone and a reprojected depth keeps a far surface apart.
inline constexpr VkFormat kMotionFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
// The translucent layer's maps: the coloured map's product (half floats: every device blends
// them) and the moments (32-bit floats, which Muenstermann et al.'s bias assumes; a device must
// blend them: Renderer::check).
inline constexpr VkFormat kTranslucentProductFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kTranslucentMomentsFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

} // namespace penumbra::render
