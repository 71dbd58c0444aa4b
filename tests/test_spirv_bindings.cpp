// The bindings a shader uses, read from its SPIR-V (src/vk/spirv_bindings.cpp), and the check
// every pipeline's shaders pass against their layout when the pipeline is made: the expected
// sets below are written from the GLSL (layout(binding = ...)) of each shader.
#include "bindings.h"
#include "gpu_fixture.h"
#include "vk/context.h"
#include "vk/pipelines.h"
#include "vk/spirv_bindings.h"

#include <algorithm>

namespace penumbra::shaders {
std::span<const uint32_t> spirv(std::string_view name); // cmake/Shaders.cmake's table
}

using namespace penumbra;
using namespace penumbra::test;
using penumbra::vk::Binding;

namespace {

constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
constexpr VkDescriptorType kStorageImage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
constexpr VkDescriptorType kUniform = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
constexpr VkDescriptorType kStorageBuffer = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;

std::vector<Binding> usedBy(std::string_view shader) {
    return vk::reflectBindings(shaders::spirv(shader));
}

const Binding* at(const std::vector<Binding>& bindings, uint32_t binding) {
    const auto it = std::find_if(bindings.begin(), bindings.end(),
                                 [&](const Binding& b) { return b.binding == binding; });
    return it == bindings.end() ? nullptr : &*it;
}

bool same(const Binding& a, const Binding& b) {
    return a.binding == b.binding && a.type == b.type && a.count == b.count;
}

} // namespace

TEST(SpirvBindings, ReadsTheBindingsEachShaderUses) {
    // A post pass: two inputs sampled, one output written; its push block is no binding.
    const std::vector<Binding> mid = usedBy("second_depth_mid.comp");
    ASSERT_EQ(mid.size(), 3u);
    EXPECT_TRUE(same(mid[0], {POST_INPUT_BINDING, kSampled, 1}));
    EXPECT_TRUE(same(mid[1], {POST_INPUT_BINDING + 1, kSampled, 1}));
    EXPECT_TRUE(same(mid[2], {POST_OUTPUT_BINDING, kStorageImage, 1}));
    // The checkerboard fill: a uniform block, images, and a storage buffer (std430 `buffer`).
    const std::vector<Binding> fill = usedBy("visibility_fill.comp");
    ASSERT_NE(at(fill, LAYER_TRACE_LIST), nullptr);
    EXPECT_EQ(at(fill, LAYER_TRACE_LIST)->type, kStorageBuffer);
    ASSERT_NE(at(fill, LAYER_VISIBILITY), nullptr);
    EXPECT_EQ(at(fill, LAYER_VISIBILITY)->type, kStorageImage);
    ASSERT_NE(at(fill, LAYER_GBUFFER_DEPTH), nullptr);
    EXPECT_EQ(at(fill, LAYER_GBUFFER_DEPTH)->type, kSampled);
    ASSERT_NE(at(fill, BIND_FRAME), nullptr);
    EXPECT_EQ(at(fill, BIND_FRAME)->type, kUniform);
    // pcf's visibility pass: the technique's arrays of maps, counted whole.
    const std::vector<Binding> vis = usedBy("visibility.comp#1");
    ASSERT_NE(at(vis, TECH_MAP), nullptr);
    EXPECT_TRUE(same(*at(vis, TECH_MAP), {TECH_MAP, kSampled, TECH_MAX_MAPS}));
    ASSERT_NE(at(vis, TECH_PARAMS), nullptr);
    EXPECT_EQ(at(vis, TECH_PARAMS)->type, kUniform);
    EXPECT_TRUE(std::is_sorted(vis.begin(), vis.end(), [](const Binding& a, const Binding& b) {
        return a.binding < b.binding;
    }));
    // Every embedded shader reads (none malformed, none outside set 0).
    for (const char* shader : {"composite.comp", "contact.comp", "export.comp", "page_marking.comp",
                               "shadow_mask.frag", "gbuffer.frag"})
        EXPECT_FALSE(usedBy(shader).empty()) << shader;
}

// A uniform whose struct lost its Block decoration is malformed, not taken for a uniform buffer:
// the fill's SPIR-V with each `OpDecorate %struct Block` overwritten by OpNops (a random mutant
// that read every Uniform-class struct as a uniform buffer went unseen).
TEST(SpirvBindings, AUniformWithoutItsBlockDecorationIsMalformed) {
    const std::span<const uint32_t> original = shaders::spirv("visibility_fill.comp");
    std::vector<uint32_t> words(original.begin(), original.end());
    constexpr uint32_t kOpDecorate = 71, kDecorationBlock = 2, kOpNop = 1u << 16;
    size_t removed = 0;
    for (size_t i = 5; i < words.size();) { // after the header, one instruction at a time
        const uint32_t count = std::max(words[i] >> 16, 1u);
        if ((words[i] & 0xffffu) == kOpDecorate && count >= 3 && words[i + 2] == kDecorationBlock) {
            std::fill_n(words.begin() + static_cast<std::ptrdiff_t>(i), count, kOpNop);
            ++removed;
        }
        i += count;
    }
    ASSERT_GT(removed, 0u);
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(vk::reflectBindings(words), "neither a Block nor a BufferBlock");
}

// The same bindings whatever the entry point's name and the order of its interface: the name is
// a literal string of any length (its last word padded with zeros), so a scan that misjudges where
// it ends takes an interface id for a character and drops that variable.
TEST(SpirvBindings, TheEntryPointsNameAndInterfaceOrderChangeNothing) {
    const std::span<const uint32_t> original = shaders::spirv("visibility_fill.comp");
    const std::vector<Binding> expected = vk::reflectBindings(original);
    ASSERT_GE(expected.size(), 4u);
    constexpr uint32_t kOpEntryPoint = 15;
    size_t at = 5;
    while (at < original.size() && (original[at] & 0xffffu) != kOpEntryPoint)
        at += std::max(original[at] >> 16, 1u);
    ASSERT_LT(at, original.size());
    const size_t count = original[at] >> 16;
    size_t name = at + 3; // model, id, then the name's words up to one with a zero byte
    const auto ends = [](uint32_t w) {
        return (w & 0xffu) == 0 || (w & 0xff00u) == 0 || (w & 0xff0000u) == 0 ||
               (w & 0xff000000u) == 0;
    };
    while (!ends(original[name]))
        ++name;
    const std::vector<uint32_t> interface(original.begin() + static_cast<std::ptrdiff_t>(name + 1),
                                          original.begin() +
                                              static_cast<std::ptrdiff_t>(at + count));
    ASSERT_GE(interface.size(), expected.size());
    const auto same = [](const std::vector<Binding>& a, const std::vector<Binding>& b) {
        return std::equal(
            a.begin(), a.end(), b.begin(), b.end(), [](const Binding& x, const Binding& y) {
                return x.binding == y.binding && x.type == y.type && x.count == y.count &&
                       x.read == y.read && x.written == y.written && x.format == y.format;
            });
    };
    for (size_t length = 1; length <= 9; ++length)
        for (size_t rotation = 0; rotation < interface.size(); ++rotation) {
            std::vector<uint32_t> entry{0, original[at + 1], original[at + 2]};
            std::string text(length, 'e'); // whole words of characters, then one of zeros
            text.resize((length / 4 + 1) * 4, '\0');
            for (size_t i = 0; i < text.size(); i += 4)
                entry.push_back(uint32_t(uint8_t(text[i])) | uint32_t(uint8_t(text[i + 1])) << 8 |
                                uint32_t(uint8_t(text[i + 2])) << 16 |
                                uint32_t(uint8_t(text[i + 3])) << 24);
            for (size_t i = 0; i < interface.size(); ++i)
                entry.push_back(interface[(i + rotation) % interface.size()]);
            entry[0] = static_cast<uint32_t>(entry.size()) << 16 | kOpEntryPoint;
            std::vector<uint32_t> words(original.begin(),
                                        original.begin() + static_cast<std::ptrdiff_t>(at));
            words.insert(words.end(), entry.begin(), entry.end());
            words.insert(words.end(), original.begin() + static_cast<std::ptrdiff_t>(at + count),
                         original.end());
            EXPECT_TRUE(same(vk::reflectBindings(words), expected))
                << "a name of " << length << " characters, interface rotated by " << rotation;
        }
}

// An array's length may be a specialization constant (OpSpecConstant, its default value): the
// count is the same as the plain constant's.
TEST(SpirvBindings, AnArrayWhoseLengthIsASpecializationConstantCountsItsDefault) {
    const std::span<const uint32_t> original = shaders::spirv("visibility.comp#1");
    std::vector<uint32_t> words(original.begin(), original.end());
    constexpr uint32_t kOpTypeArray = 28, kOpConstant = 43, kOpSpecConstant = 50;
    std::vector<uint32_t> lengths;
    for (size_t i = 5; i < words.size(); i += std::max(words[i] >> 16, 1u))
        if ((words[i] & 0xffffu) == kOpTypeArray)
            lengths.push_back(words[i + 3]);
    size_t changed = 0;
    for (size_t i = 5; i < words.size(); i += std::max(words[i] >> 16, 1u))
        if ((words[i] & 0xffffu) == kOpConstant &&
            std::find(lengths.begin(), lengths.end(), words[i + 2]) != lengths.end()) {
            words[i] = (words[i] & 0xffff0000u) | kOpSpecConstant;
            ++changed;
        }
    ASSERT_GT(changed, 0u);
    const std::vector<Binding> vis = vk::reflectBindings(words);
    ASSERT_NE(at(vis, TECH_MAP), nullptr);
    EXPECT_EQ(at(vis, TECH_MAP)->count, uint32_t{TECH_MAX_MAPS});
}

// Two variables on one binding (the fill's second binding moved onto its first) are refused by
// name, not handed on as two descriptors of one binding.
TEST(SpirvBindings, TwoVariablesOnOneBindingAreRefused) {
    const std::span<const uint32_t> original = shaders::spirv("visibility_fill.comp");
    const std::vector<Binding> used = vk::reflectBindings(original);
    ASSERT_GE(used.size(), 2u);
    std::vector<uint32_t> words(original.begin(), original.end());
    constexpr uint32_t kOpDecorate = 71, kDecorationBinding = 33;
    size_t moved = 0;
    for (size_t i = 5; i < words.size(); i += std::max(words[i] >> 16, 1u))
        if ((words[i] & 0xffffu) == kOpDecorate && words[i + 2] == kDecorationBinding &&
            words[i + 3] == used[1].binding) {
            words[i + 3] = used[0].binding;
            ++moved;
        }
    ASSERT_GT(moved, 0u);
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(vk::reflectBindings(words),
                 "binding " + std::to_string(used[0].binding) + " is declared by two variables");
}

// An image of dimension Buffer is a texel buffer, not an image: the mid pass's storage image
// with its OpTypeImage's Dim set to Buffer (5) reads as a storage texel buffer.
TEST(SpirvBindings, AnImageOfDimensionBufferIsATexelBuffer) {
    const std::span<const uint32_t> original = shaders::spirv("second_depth_mid.comp");
    std::vector<uint32_t> words(original.begin(), original.end());
    constexpr uint32_t kOpTypeImage = 25, kDimBuffer = 5, kStorage = 2;
    size_t changed = 0;
    for (size_t i = 5; i < words.size(); i += std::max(words[i] >> 16, 1u))
        if ((words[i] & 0xffffu) == kOpTypeImage && (words[i] >> 16) >= 9 &&
            words[i + 7] == kStorage) { // op, id, sampled type, dim, depth, arrayed, MS, sampled
            words[i + 3] = kDimBuffer;
            ++changed;
        }
    ASSERT_EQ(changed, 1u);
    const std::vector<Binding> mid = vk::reflectBindings(words);
    ASSERT_NE(at(mid, POST_OUTPUT_BINDING), nullptr);
    EXPECT_EQ(at(mid, POST_OUTPUT_BINDING)->type, VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER);
    ASSERT_NE(at(mid, POST_INPUT_BINDING), nullptr);
    EXPECT_EQ(at(mid, POST_INPUT_BINDING)->type, kSampled) << "the sampled inputs unchanged";
}

TEST(SpirvBindings, AMismatchNamesTheBindingAndBothKinds) {
    const std::vector<Binding> used{{0, kSampled, 1}, {8, kStorageImage, 4}};
    EXPECT_EQ(vk::bindingMismatch(used, used), "");
    const std::vector<Binding> wider{{0, kSampled, 1}, {3, kUniform, 1}, {8, kStorageImage, 5}};
    EXPECT_EQ(vk::bindingMismatch(used, wider), "") << "a layout may hold more";
    EXPECT_EQ(vk::bindingMismatch(used, std::vector<Binding>{{8, kStorageImage, 4}}),
              "binding 0 (combined image sampler) is not in the layout");
    EXPECT_EQ(vk::bindingMismatch(used, std::vector<Binding>{{0, kSampled, 1}, {8, kSampled, 4}}),
              "binding 8 is a storage image in the shader, a combined image sampler in the layout");
    EXPECT_EQ(
        vk::bindingMismatch(used, std::vector<Binding>{{0, kSampled, 1}, {8, kStorageImage, 3}}),
        "binding 8 is an array of 4 in the shader, of 3 in the layout");
}

// Made with a layout that lacks what the shader uses: refused by name before any device sees it.
TEST_F(FrameTest, APipelineWhoseShaderUsesABindingItsLayoutLacksIsRefused) {
    const vk::Context& ctx = sharedRenderer().context();
    const vk::PipelineLayout right =
        vk::createPipelineLayout(ctx,
                                 {{POST_INPUT_BINDING, kSampled},
                                  {POST_INPUT_BINDING + 1, kSampled},
                                  {POST_OUTPUT_BINDING, kStorageImage}},
                                 VK_SHADER_STAGE_COMPUTE_BIT, 16);
    EXPECT_NE(vk::createComputePipeline(ctx, right, "second_depth_mid.comp").get(), VK_NULL_HANDLE);
    const vk::PipelineLayout lacking = vk::createPipelineLayout(
        ctx, {{POST_INPUT_BINDING, kSampled}, {POST_INPUT_BINDING + 1, kSampled}},
        VK_SHADER_STAGE_COMPUTE_BIT, 16);
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(vk::createComputePipeline(ctx, lacking, "second_depth_mid.comp"),
                 "shader second_depth_mid.comp: binding 8 \\(storage image\\) is not in the "
                 "layout");
}

// A pass's descriptor writes against its layout, checked before they reach the device: a write
// the layout does not hold as that kind, and a binding left unwritten, are refused by name.
TEST_F(FrameTest, DescriptorWritesTheLayoutDoesNotHoldAreRefused) {
    const vk::Context& ctx = sharedRenderer().context();
    const vk::PipelineLayout layout =
        vk::createLayoutOf(ctx, {"second_depth_mid.comp"}, VK_SHADER_STAGE_COMPUTE_BIT, 16);
    ASSERT_EQ(layout.bindings.size(), 3u) << "what the shader uses, read from it";
    EXPECT_TRUE(same(layout.bindings[2], {POST_OUTPUT_BINDING, kStorageImage, 1}));
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    vk::PushDescriptors wrongKind; // never recorded: refused before any command
    wrongKind.sampled(POST_INPUT_BINDING, VK_NULL_HANDLE, VK_NULL_HANDLE)
        .sampled(POST_INPUT_BINDING + 1, VK_NULL_HANDLE, VK_NULL_HANDLE)
        .sampled(POST_OUTPUT_BINDING, VK_NULL_HANDLE, VK_NULL_HANDLE);
    EXPECT_DEATH(wrongKind.push(ctx, VK_NULL_HANDLE, VK_PIPELINE_BIND_POINT_COMPUTE, layout),
                 "a descriptor write of 1 combined image sampler at binding 8 that its layout "
                 "does not hold so");
    vk::PushDescriptors missing;
    missing.sampled(POST_INPUT_BINDING, VK_NULL_HANDLE, VK_NULL_HANDLE)
        .storageImage(POST_OUTPUT_BINDING, VK_NULL_HANDLE);
    EXPECT_DEATH(missing.push(ctx, VK_NULL_HANDLE, VK_PIPELINE_BIND_POINT_COMPUTE, layout),
                 "binding 1 \\(combined image sampler\\) left unwritten");
}
