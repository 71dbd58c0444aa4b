#pragma once
// Base-colour textures on the GPU: one sRGB image with a full mip chain per scene image, one
// sampler per texture (its glTF wrap modes and magnification filter), and a white placeholder
// for materials without a texture, so every draw binds a texture.
#include "penumbra/scene.h"
#include "vk/resources.h"

#include <vector>

namespace penumbra::render {

struct GpuTextures {
    std::vector<vk::Image> images;           // per Scene::images, then the white placeholder
    std::vector<vk::SamplerHandle> samplers; // per Scene::textures, then the placeholder's
    struct Binding {
        VkImageView view;
        VkSampler sampler;
    };
    // The texture material `m` samples (the placeholder when it has none).
    Binding of(const Scene& scene, uint32_t material) const;
    Binding placeholder() const { return {images.back().view.get(), samplers.back().get()}; }
};

GpuTextures uploadTextures(const vk::Context& ctx, const Scene& scene);

} // namespace penumbra::render
