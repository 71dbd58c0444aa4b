#include "render/pass_bindings.h"

#include "penumbra/error.h"
#include "render/frame_graph.h"
#include "vk/spirv_bindings.h"

#include <algorithm>
#include <fmt/format.h>

namespace penumbra::render {
namespace {

[[noreturn]] void refuse(std::string_view pass, const std::string& why) {
    fatal(__FILE__, __LINE__, fmt::format("pass \"{}\": {}", pass, why));
}

const vk::Binding& heldAt(const vk::PipelineLayout& layout, uint32_t binding,
                          std::string_view pass) {
    const auto it = std::find_if(layout.bindings.begin(), layout.bindings.end(),
                                 [&](const vk::Binding& b) { return b.binding == binding; });
    if (it == layout.bindings.end())
        refuse(pass, fmt::format("binds binding {}, which its layout does not hold", binding));
    return *it;
}

} // namespace

Access accessOf(const vk::Binding& binding, VkShaderStageFlags stages, std::string_view pass) {
    if (!binding.read && !binding.written)
        refuse(pass, fmt::format("binding {} ({}) is neither read nor written by its shaders "
                                 "(a layout listed by hand?)",
                                 binding.binding, vk::descriptorKind(binding.type)));
    const bool compute = (stages & VK_SHADER_STAGE_COMPUTE_BIT) != 0;
    switch (binding.type) {
    case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
        return compute ? Access::ComputeSampled : Access::FragmentSampled;
    case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
        return Access::UniformRead;
    case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
    case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
        // A buffer only a vertex shader reads (the G-buffer's previous positions).
        if (binding.type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER && !binding.written &&
            binding.usedBy == VK_SHADER_STAGE_VERTEX_BIT)
            return Access::VertexStorageRead;
        if (!compute)
            refuse(pass,
                   fmt::format("binding {}: storage outside a compute shader", binding.binding));
        return binding.written ? (binding.read ? Access::ComputeReadWrite : Access::ComputeWrite)
                               : Access::ComputeRead;
    default:
        refuse(pass, fmt::format("binding {}: a {} is not bound through PassBindings",
                                 binding.binding, vk::descriptorKind(binding.type)));
    }
}

std::vector<Use> usesOf(const PassBindings& bindings, std::string_view pass) {
    if (!bindings.layout)
        return {};
    const vk::PipelineLayout& layout = *bindings.layout;
    std::vector<Use> uses;
    for (const Bound& b : bindings.bound) {
        const vk::Binding& held = heldAt(layout, b.binding, pass);
        if (held.count != 1)
            refuse(pass, fmt::format("binding {} is an array of {}; PassBindings binds one "
                                     "resource",
                                     b.binding, held.count));
        if (std::count_if(bindings.bound.begin(), bindings.bound.end(),
                          [&](const Bound& o) { return o.binding == b.binding; }) != 1)
            refuse(pass, fmt::format("binds binding {} twice", b.binding));
        const bool sampled = held.type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
        if (sampled != (b.sampler != VK_NULL_HANDLE))
            refuse(pass, fmt::format("binding {} ({}) {}", b.binding, vk::descriptorKind(held.type),
                                     sampled ? "needs a sampler" : "takes no sampler"));
        uses.push_back({b.resource, accessOf(held, layout.stages, pass)});
    }
    for (const vk::Binding& held : layout.bindings)
        if (std::none_of(bindings.bound.begin(), bindings.bound.end(),
                         [&](const Bound& b) { return b.binding == held.binding; }))
            refuse(pass, fmt::format("leaves binding {} ({}) unbound", held.binding,
                                     vk::descriptorKind(held.type)));
    return uses;
}

void checkStorageFormats(const PassBindings& bindings, std::string_view pass,
                         const std::function<VkFormat(ResourceId)>& formatOf) {
    if (!bindings.layout)
        return;
    for (const Bound& b : bindings.bound) {
        const vk::Binding& held = heldAt(*bindings.layout, b.binding, pass);
        if (held.type != VK_DESCRIPTOR_TYPE_STORAGE_IMAGE)
            continue;
        const std::string why = vk::storageFormatMismatch(held.format, formatOf(b.resource));
        if (!why.empty())
            refuse(pass, fmt::format("binding {}: {}", b.binding, why));
    }
}

void pushBindings(const PassBindings& bindings, const PassContext& c, const vk::Context& ctx) {
    if (!bindings.layout)
        return;
    const vk::PipelineLayout& layout = *bindings.layout;
    vk::PushDescriptors writes;
    for (const Bound& b : bindings.bound) {
        switch (heldAt(layout, b.binding, "").type) {
        case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
            writes.sampled(b.binding, c.image(b.resource).view(), b.sampler);
            break;
        case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
            writes.storageImage(b.binding, c.image(b.resource).view());
            break;
        case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
            writes.uniformBuffer(b.binding, c.buffer(b.resource));
            break;
        default: // usesOf let no other kind through
            writes.storageBuffer(b.binding, c.buffer(b.resource));
            break;
        }
    }
    const bool compute = (layout.stages & VK_SHADER_STAGE_COMPUTE_BIT) != 0;
    writes.push(ctx, c.cmd,
                compute ? VK_PIPELINE_BIND_POINT_COMPUTE : VK_PIPELINE_BIND_POINT_GRAPHICS, layout);
}

} // namespace penumbra::render
