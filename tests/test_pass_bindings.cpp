// A pass's bindings declared once (src/render/pass_bindings.cpp): whether a shader reads or
// writes each binding, read from its SPIR-V (`readonly`, `writeonly`; the expectations below are
// written from each shader's GLSL), the graph's uses that follow from a layout made from the
// shaders, and the declarations refused before anything is recorded.
#include "bindings.h"
#include "gpu_fixture.h"
#include "render/frame_graph.h"
#include "render/pass_bindings.h"
#include "render/pipelines.h"
#include "viewer_types.h"
#include "vk/context.h"
#include "vk/spirv_bindings.h"

#include <algorithm>
#include <array>

namespace penumbra::shaders {
std::span<const uint32_t> spirv(std::string_view name); // cmake/Shaders.cmake's table
}

using namespace penumbra;
using namespace penumbra::render;
using namespace penumbra::test;

namespace {

// {read, written} of `binding` in `shader`; {false, false} where the shader does not use it.
std::pair<bool, bool> accessIn(std::string_view shader, uint32_t binding) {
    for (const vk::Binding& b : vk::reflectBindings(shaders::spirv(shader)))
        if (b.binding == binding)
            return {b.read, b.written};
    return {false, false};
}

VkSampler fakeSampler() { // never dereferenced: usesOf only asks whether one is given
    return reinterpret_cast<VkSampler>(uintptr_t{1});
}

} // namespace

TEST(SpirvBindings, ReadsWhetherTheShaderReadsOrWritesEachBinding) {
    using RW = std::pair<bool, bool>;
    // Sampled images and uniform blocks are read.
    EXPECT_EQ(accessIn("second_depth_mid.comp", POST_INPUT_BINDING), RW(true, false));
    EXPECT_EQ(accessIn("visibility_fill.comp", BIND_FRAME), RW(true, false));
    // A storage image: `writeonly`, or neither qualifier (both).
    EXPECT_EQ(accessIn("second_depth_mid.comp", POST_OUTPUT_BINDING), RW(false, true));
    EXPECT_EQ(accessIn("visibility_fill.comp", LAYER_VISIBILITY), RW(true, true));
    // A storage buffer's block: `readonly`, `writeonly` (decorated member by member), neither.
    EXPECT_EQ(accessIn("filter_probe.comp#1", PROBE_RECEIVERS), RW(true, false));
    EXPECT_EQ(accessIn("filter_probe.comp#1", PROBE_RESULTS), RW(false, true));
    EXPECT_EQ(accessIn("page_marking.comp", MARK_REQUESTS), RW(false, true));
    EXPECT_EQ(accessIn("visibility_fill.comp", LAYER_TRACE_LIST), RW(true, true));
    // A `readonly` image, and a `readonly` block of two members (every member decorated).
    EXPECT_EQ(accessIn("viewer_display.comp", DISPLAY_COLOR), RW(true, false));
    EXPECT_EQ(accessIn("visibility.comp#12", VIS_TRACE_LIST), RW(true, false));
}

// A layout made from several shaders holds what any of them does with a binding: the filter
// reads and writes the layers' scratch, contact only writes it.
TEST_F(FrameTest, ALayoutOfSeveralShadersReadsAndWritesWhatAnyOfThemDoes) {
    const vk::PipelineLayout layout =
        vk::createLayoutOf(sharedRenderer().context(), {"visibility_filter.comp", "contact.comp"},
                           VK_SHADER_STAGE_COMPUTE_BIT, 0);
    const auto results =
        std::find_if(layout.bindings.begin(), layout.bindings.end(),
                     [](const vk::Binding& b) { return b.binding == LAYER_RESULTS; });
    ASSERT_NE(results, layout.bindings.end());
    EXPECT_TRUE(results->read);
    EXPECT_TRUE(results->written);
    const vk::PipelineLayout reversed =
        vk::createLayoutOf(sharedRenderer().context(), {"contact.comp", "visibility_filter.comp"},
                           VK_SHADER_STAGE_COMPUTE_BIT, 0);
    for (const vk::Binding& b : reversed.bindings)
        if (b.binding == LAYER_RESULTS) {
            EXPECT_TRUE(b.read && b.written) << "in either order";
        }
}

// A layout made from its shaders gives each binding's use: the composite pass's.
TEST_F(FrameTest, APassBindingsUsesFollowFromItsShaders) {
    const vk::Context& ctx = sharedRenderer().context();
    const vk::PipelineLayout layout =
        vk::createLayoutOf(ctx, {"composite.comp"}, VK_SHADER_STAGE_COMPUTE_BIT, 0);
    const PassBindings bindings{.layout = &layout,
                                .bound = {{BIND_FRAME, 10},
                                          {COMPOSITE_LIGHTS, 11},
                                          {COMPOSITE_GBUFFER_DEPTH, 12, fakeSampler()},
                                          {COMPOSITE_GBUFFER_NORMAL, 13, fakeSampler()},
                                          {COMPOSITE_GBUFFER_ALBEDO, 14, fakeSampler()},
                                          {COMPOSITE_VISIBILITY, 15, fakeSampler()},
                                          {COMPOSITE_OUT, 16},
                                          {COMPOSITE_TRANSMITTANCE, 17, fakeSampler()}}};
    const std::vector<Use> uses = usesOf(bindings, "composite");
    ASSERT_EQ(uses.size(), 8u);
    const std::vector<Access> expected{Access::UniformRead,    Access::UniformRead,
                                       Access::ComputeSampled, Access::ComputeSampled,
                                       Access::ComputeSampled, Access::ComputeSampled,
                                       Access::ComputeWrite,   Access::ComputeSampled};
    for (size_t i = 0; i < uses.size(); ++i) {
        EXPECT_EQ(uses[i].resource, 10 + i) << i;
        EXPECT_EQ(uses[i].access, expected[i]) << i;
    }
    // A graphics layout samples in the fragment stage.
    const vk::PipelineLayout gbuffer =
        vk::createLayoutOf(ctx, {"gbuffer.vert", "gbuffer.frag"},
                           VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0);
    const std::vector<Use> drawn = usesOf({.layout = &gbuffer,
                                           .bound = {{BIND_FRAME, 1},
                                                     {GBUFFER_TEXTURE, 2, fakeSampler()},
                                                     {GBUFFER_PREVIOUS_POSITIONS, 3}}},
                                          "gbuffer");
    ASSERT_EQ(drawn.size(), 3u);
    EXPECT_EQ(drawn[1].access, Access::FragmentSampled);
    // A storage buffer only its vertex shader reads (the previous positions).
    EXPECT_EQ(drawn[2].access, Access::VertexStorageRead);
    // Storage read and written, and read only.
    const vk::PipelineLayout fill =
        vk::createLayoutOf(ctx, {"visibility_fill.comp"}, VK_SHADER_STAGE_COMPUTE_BIT, 0);
    const vk::Binding* visibility = nullptr;
    for (const vk::Binding& b : fill.bindings)
        if (b.binding == LAYER_VISIBILITY)
            visibility = &b;
    ASSERT_NE(visibility, nullptr);
    EXPECT_EQ(accessOf(*visibility, fill.stages, "fill"), Access::ComputeReadWrite);
    vk::Binding readOnly = *visibility;
    readOnly.written = false;
    EXPECT_EQ(accessOf(readOnly, fill.stages, "fill"), Access::ComputeRead);
    // Storage outside compute, and a kind PassBindings does not bind, are refused by name.
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(accessOf(*visibility, VK_SHADER_STAGE_FRAGMENT_BIT, "draw"),
                 "pass \"draw\": binding [0-9]+: storage outside a compute shader");
    const vk::Binding sampler{.binding = 3, .type = VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, .read = true};
    EXPECT_DEATH(accessOf(sampler, fill.stages, "fill"),
                 "pass \"fill\": binding 3: a sampled image is not bound through PassBindings");
}

// A storage image's format as its GLSL declares it, read from the SPIR-V; one bound with another
// format is refused, naming both as GLSL writes them (a device would write it as the wrong format
// without a word, validation or not).
TEST_F(FrameTest, AStorageImageOfAnotherFormatThanItsShaderDeclaresIsRefused) {
    const auto formatIn = [](std::string_view shader, uint32_t binding) {
        for (const vk::Binding& b : vk::reflectBindings(shaders::spirv(shader)))
            if (b.binding == binding)
                return b.format;
        return VK_FORMAT_MAX_ENUM;
    };
    EXPECT_EQ(formatIn("second_depth_mid.comp", POST_OUTPUT_BINDING), VK_FORMAT_R32_SFLOAT);
    EXPECT_EQ(formatIn("vsm_mip.comp", POST_OUTPUT_BINDING), VK_FORMAT_R32G32_SFLOAT);
    EXPECT_EQ(formatIn("vsm_mip.comp", POST_INPUT_BINDING), VK_FORMAT_UNDEFINED) << "sampled";
    const vk::Context& ctx = sharedRenderer().context();
    const vk::PipelineLayout layout =
        vk::createLayoutOf(ctx, {"vsm_mip.comp"}, VK_SHADER_STAGE_COMPUTE_BIT, 16);
    const PassBindings bindings{
        .layout = &layout,
        .bound = {{POST_INPUT_BINDING, 1, fakeSampler()}, {POST_OUTPUT_BINDING, 2}}};
    const auto formats = [](VkFormat input, VkFormat output) {
        return [=](ResourceId id) { return id == 1 ? input : output; };
    };
    // The input is sampled: its format is the sampler's business.
    checkStorageFormats(bindings, "mip", formats(VK_FORMAT_R32_SFLOAT, VK_FORMAT_R32G32_SFLOAT));
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(
        checkStorageFormats(bindings, "mip", formats(VK_FORMAT_R32G32_SFLOAT, VK_FORMAT_R32_UINT)),
        "pass \"mip\": binding 8: declared rg32f in its shaders, the image is r32ui");
    // Through the graph: the pass is refused when it is added.
    const auto addThroughTheGraph = [&] {
        ResourcePool pool(ctx);
        FrameGraph graph(pool, {.width = 4, .height = 4});
        const auto image = [](std::string name, VkFormat format) {
            return ImageDecl{.name = std::move(name),
                             .size = SizeClass::Screen,
                             .format = format,
                             .usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT};
        };
        const ResourceId in = graph.declare(image("in", VK_FORMAT_R32G32_SFLOAT));
        const ResourceId out = graph.declare(image("out", VK_FORMAT_R32G32B32A32_SFLOAT));
        graph.addPass({.phase = Phase::LightSpace,
                       .bindings = {.layout = &layout,
                                    .bound = {{POST_INPUT_BINDING, in, fakeSampler()},
                                              {POST_OUTPUT_BINDING, out}}},
                       .record = [](PassContext&) {}});
    };
    EXPECT_DEATH(addThroughTheGraph(),
                 "binding 8: declared rg32f in its shaders, the image is rgba32f");
    // Two shaders that declare one binding's format differently make no layout.
    EXPECT_DEATH(vk::createLayoutOf(ctx, {"vsm_mip.comp", "second_depth_mid.comp"},
                                    VK_SHADER_STAGE_COMPUTE_BIT, 16),
                 "shader second_depth_mid.comp: binding 8 differs from another stage's");
    // A post pass's outputs, which it writes itself, are checked when its pipeline is bound:
    // vsm_mip.comp writes rg32f.
    FramePipelines pipelines(ctx);
    EXPECT_NE(pipelines.postPass("vsm_mip.comp", 1, std::array{VK_FORMAT_R32G32_SFLOAT}),
              VK_NULL_HANDLE);
    EXPECT_DEATH(pipelines.postPass("vsm_mip.comp", 1, std::array{VK_FORMAT_R32_SFLOAT}),
                 "post pass vsm_mip.comp: output 0 \\(binding 8\\): declared rg32f in its "
                 "shaders, the image is r32f");
    EXPECT_DEATH(pipelines.postPass("vsm_mip.comp", 2, std::array{VK_FORMAT_R32G32_SFLOAT}),
                 "post pass vsm_mip.comp: declared with 2 inputs and 1 outputs, and before with 1 "
                 "and 1");
    // Every map format a technique may declare, as its GLSL qualifier (docs/architecture.md).
    for (const auto& [format, glsl] :
         std::vector<std::pair<VkFormat, std::string>>{{VK_FORMAT_R32_SFLOAT, "r32f"},
                                                       {VK_FORMAT_R32G32_SFLOAT, "rg32f"},
                                                       {VK_FORMAT_R32G32B32A32_SFLOAT, "rgba32f"},
                                                       {VK_FORMAT_R16G16B16A16_UNORM, "rgba16"},
                                                       {VK_FORMAT_R32_UINT, "r32ui"},
                                                       {VK_FORMAT_R32G32_UINT, "rg32ui"},
                                                       {VK_FORMAT_R32G32B32A32_UINT, "rgba32ui"}})
        EXPECT_EQ(vk::storageFormatName(format), glsl);
    EXPECT_EQ(vk::storageFormatName(VK_FORMAT_R16G16_SFLOAT), "rg16f");
    // The rule both ask: a declared format must be the image's; none declared takes any.
    EXPECT_EQ(vk::storageFormatMismatch(VK_FORMAT_UNDEFINED, VK_FORMAT_R32_SFLOAT), "");
    EXPECT_EQ(vk::storageFormatMismatch(VK_FORMAT_R32_SFLOAT, VK_FORMAT_R32_SFLOAT), "");
    EXPECT_EQ(vk::storageFormatMismatch(VK_FORMAT_R32_UINT, VK_FORMAT_R32_SFLOAT),
              "declared r32ui in its shaders, the image is r32f");
    EXPECT_EQ(vk::storageFormatName(VK_FORMAT_D32_SFLOAT), "VkFormat 126");
}

// What cannot be bound as declared is refused by name when the pass is added.
TEST_F(FrameTest, PassBindingsThatDoNotMatchTheLayoutAreRefused) {
    const vk::Context& ctx = sharedRenderer().context();
    const vk::PipelineLayout layout =
        vk::createLayoutOf(ctx, {"second_depth_mid.comp"}, VK_SHADER_STAGE_COMPUTE_BIT, 16);
    const Bound first{POST_INPUT_BINDING, 1, fakeSampler()};
    const Bound second{POST_INPUT_BINDING + 1, 2, fakeSampler()};
    const Bound out{POST_OUTPUT_BINDING, 3};
    EXPECT_EQ(usesOf({.layout = &layout, .bound = {first, second, out}}, "mid").size(), 3u);
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(usesOf({.layout = &layout, .bound = {first, out}}, "mid"),
                 "pass \"mid\": leaves binding 1 \\(combined image sampler\\) unbound");
    EXPECT_DEATH(usesOf({.layout = &layout, .bound = {first, second, out, {5, 4}}}, "mid"),
                 "pass \"mid\": binds binding 5, which its layout does not hold");
    EXPECT_DEATH(usesOf({.layout = &layout, .bound = {first, second, out, out}}, "mid"),
                 "pass \"mid\": binds binding 8 twice");
    EXPECT_DEATH(
        usesOf({.layout = &layout, .bound = {{POST_INPUT_BINDING, 1}, second, out}}, "mid"),
        "pass \"mid\": binding 0 \\(combined image sampler\\) needs a sampler");
    EXPECT_DEATH(usesOf({.layout = &layout,
                         .bound = {first, second, {POST_OUTPUT_BINDING, 3, fakeSampler()}}},
                        "mid"),
                 "pass \"mid\": binding 8 \\(storage image\\) takes no sampler");
    // An array binding (a technique's map slots) takes several views: PassBindings binds one.
    const vk::PipelineLayout arrays = vk::createPipelineLayout(
        ctx, {{POST_INPUT_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 4, true, false}},
        VK_SHADER_STAGE_COMPUTE_BIT, 16);
    EXPECT_DEATH(usesOf({.layout = &arrays, .bound = {first}}, "mid"),
                 "pass \"mid\": binding 0 is an array of 4; PassBindings binds one resource");
    // A layout listed by hand says nothing of what its shaders do: its pass declares its uses.
    const vk::PipelineLayout byHand =
        vk::createPipelineLayout(ctx,
                                 {{POST_INPUT_BINDING, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
                                  {POST_OUTPUT_BINDING, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}},
                                 VK_SHADER_STAGE_COMPUTE_BIT, 16);
    EXPECT_DEATH(usesOf({.layout = &byHand, .bound = {first, out}}, "mid"),
                 "pass \"mid\": binding 0 \\(combined image sampler\\) is neither read nor "
                 "written by its shaders");
}
