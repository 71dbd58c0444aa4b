#pragma once
// Pipelines and their layouts. Every pipeline uses one push-descriptor set (no pools, and no
// binding can be left unwritten, which lavapipe punishes) plus a push-constant block.
// Variants are specialization constants named at the call site: {{/* TECHNIQUE= */ 0, id}}.
#include "vk/context.h"
#include "vk/handles.h"

#include <array>
#include <initializer_list>
#include <span>
#include <string_view>
#include <vector>

namespace penumbra::vk {

struct Binding {
    uint32_t binding;
    VkDescriptorType type;
    uint32_t count = 1; // an array of this many (a shader's `sampler2DArray maps[N]`)
    // What its shaders do with what is bound there, read from their SPIR-V (vk/spirv_bindings.h;
    // a storage image or buffer's `readonly` and `writeonly`): set by reflection and the layouts
    // made from it, left false in a layout listed by hand.
    bool read = false, written = false;
    // A storage image's format as its shaders declare it (`layout(rg32f)`), which the view bound
    // there must have; VK_FORMAT_UNDEFINED for none declared and for other kinds.
    VkFormat format = VK_FORMAT_UNDEFINED;
    // The stages of the shaders that declare it (createLayoutOf, from each shader's name: .vert,
    // .frag, .comp); 0 where unknown (reflection alone, a layout listed by hand).
    VkShaderStageFlags usedBy = 0;
};

// Why `bindings`, seen by one shader stage through one push descriptor set, exceed the device's
// limits (its maxPushDescriptors and per-stage limits of each descriptor kind); empty when they
// do not. createPipelineLayout refuses such a layout, naming the limit.
std::string bindingLimitProblem(std::span<const Binding> bindings,
                                const VkPhysicalDeviceLimits& limits, uint32_t maxPushDescriptors);

struct PipelineLayout {
    DescriptorSetLayoutHandle set;
    PipelineLayoutHandle layout;
    // What it was made with: a pipeline's shaders are checked against them
    // (vk/spirv_bindings.h).
    std::vector<Binding> bindings;
    VkShaderStageFlags stages = 0;
    VkPipelineLayout get() const { return layout.get(); }
};

PipelineLayout createPipelineLayout(const Context& ctx, std::initializer_list<Binding> bindings,
                                    VkShaderStageFlags stages, uint32_t pushConstantBytes);
PipelineLayout createPipelineLayout(const Context& ctx, std::span<const Binding> bindings,
                                    VkShaderStageFlags stages, uint32_t pushConstantBytes);

// The layout of a pass whose shaders alone say what it binds: the bindings its shaders use
// (vk/spirv_bindings.h), one kind per binding across them. Passes whose layout is a contract
// several shaders meet (the visibility pass's TECH_*, the layers' LAYER_*, the post passes')
// list theirs by hand.
PipelineLayout createLayoutOf(const Context& ctx, std::initializer_list<std::string_view> shaders,
                              VkShaderStageFlags stages, uint32_t pushConstantBytes);

struct SpecConstant {
    uint32_t id;
    uint32_t value;
};

PipelineHandle createComputePipeline(const Context& ctx, const PipelineLayout& layout,
                                     std::string_view shader,
                                     std::span<const SpecConstant> constants = {});

// How a colour attachment combines what a fragment writes with what it holds: replaced, or
// multiplied or added in (the translucent layer's maps: order-independent).
enum class Blend { None, Multiply, Add };

struct GraphicsPipelineDesc {
    std::string_view vertexShader;
    std::string_view fragmentShader; // empty: depth-only
    uint32_t vertexStride = 0;
    std::vector<VkVertexInputAttributeDescription> attributes;
    std::vector<VkFormat> colorFormats;
    VkFormat depthFormat = VK_FORMAT_D32_SFLOAT; // VK_FORMAT_UNDEFINED: no depth test
    VkCompareOp depthCompare = VK_COMPARE_OP_LESS_OR_EQUAL;
    Blend blend = Blend::None; // every colour attachment's
    bool depthClamp = false;
    bool depthBias = false;              // values set per draw with vkCmdSetDepthBias
    bool dynamicCullMode = false;        // set per draw with vkCmdSetCullMode (default none)
    std::vector<SpecConstant> constants; // for both stages (their ids apart)
};

PipelineHandle createGraphicsPipeline(const Context& ctx, const PipelineLayout& layout,
                                      const GraphicsPipelineDesc& desc);

// Collects descriptor writes for one vkCmdPushDescriptorSetKHR call.
class PushDescriptors {
public:
    PushDescriptors& sampled(uint32_t binding, VkImageView view, VkSampler sampler);
    // An array binding whole, element by element, in one write (lavapipe 22.3 drops a push
    // descriptor write's dstArrayElement: writes of single elements all land on the first).
    PushDescriptors& sampled(uint32_t binding, std::span<const VkImageView> views,
                             VkSampler sampler);
    PushDescriptors& storageImage(uint32_t binding, VkImageView view);
    // The whole buffer, or `range` bytes from `offset` (a multiple of the device's
    // minUniformBufferOffsetAlignment, at most 256 by the specification).
    PushDescriptors& uniformBuffer(uint32_t binding, VkBuffer buffer, VkDeviceSize offset = 0,
                                   VkDeviceSize range = VK_WHOLE_SIZE);
    PushDescriptors& storageBuffer(uint32_t binding, VkBuffer buffer);
    void push(const Context& ctx, VkCommandBuffer cmd, VkPipelineBindPoint point,
              const PipelineLayout& layout);
    // The writes gathered so far (what tests of a pass's bindings read).
    std::span<const VkWriteDescriptorSet> writes() const { return mWrites; }

private:
    // Descriptors of each kind one push holds: the least maxPushDescriptors a device may report
    // (createPipelineLayout checks each layout against the device's own limit).
    static constexpr size_t kMax = 32;
    std::array<VkDescriptorImageInfo, kMax> mImages{};
    std::array<VkDescriptorBufferInfo, kMax> mBuffers{};
    std::vector<VkWriteDescriptorSet> mWrites;
    size_t mImageCount = 0, mBufferCount = 0;
};

} // namespace penumbra::vk
