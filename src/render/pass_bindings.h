#pragma once
// A pass's descriptor bindings, declared once (issue 58's "one source of bindings"): which
// resource each binding of its layout holds. The layout is read from the pass's shaders
// (vk::createLayoutOf: each binding's kind, and whether the shaders read or write it, from their
// SPIR-V), so the graph's uses follow from it (usesOf) and so do the descriptor writes the graph
// pushes before the pass records (pushBindings). GLSL says once what a binding is and whether it
// is read or written (`readonly`, `writeonly`); C++ says once what is bound there.
#include "render/resource_pool.h"
#include "vk/pipelines.h"

#include <functional>
#include <string_view>
#include <vector>

namespace penumbra::render {

struct Use;
struct PassContext;

// What one binding holds: an image (sampled through `sampler` where the binding is a sampler),
// or a buffer, whole.
struct Bound {
    uint32_t binding;
    ResourceId resource;
    VkSampler sampler = VK_NULL_HANDLE;
};

struct PassBindings {
    const vk::PipelineLayout* layout = nullptr; // none: the pass writes its own descriptors
    std::vector<Bound> bound;                   // every binding of the layout, once
};

// The access a binding's use needs, from its kind, its layout's stages and what the shaders do
// with it: a sampled image is sampled in the stage that reads it (fragment in a graphics layout),
// a uniform buffer read, a storage image or buffer read, written or both in a compute shader.
// Fatal for a binding the shaders neither read nor write (a layout listed by hand: its pass
// declares its uses itself) and for storage outside compute.
Access accessOf(const vk::Binding& binding, VkShaderStageFlags stages, std::string_view pass);

// The uses `bindings` make, after checking that they bind each binding of the layout once and
// nothing else (fatal, naming `pass` and the binding).
std::vector<Use> usesOf(const PassBindings& bindings, std::string_view pass);

// Checks that each storage image bound has the format its shaders declare for the binding
// (`layout(rg32f)`; none declared: any): fatal, naming `pass`, the binding and both formats, for
// one that does not, which a device would read or write as the wrong format without a word.
// `formatOf` gives a resource's format.
void checkStorageFormats(const PassBindings& bindings, std::string_view pass,
                         const std::function<VkFormat(ResourceId)>& formatOf);

// Pushes the descriptors of `bindings` for the pass about to record in `c`.
void pushBindings(const PassBindings& bindings, const PassContext& c, const vk::Context& ctx);

} // namespace penumbra::render
