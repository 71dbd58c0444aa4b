#pragma once
// Textures on the GPU: one sRGB image with a full mip chain per scene image (with a UNORM view too
// where a transmission texture reads its bytes as they are), one
// sampler per texture (its glTF wrap modes and magnification filter), and a 1x1 white texture
// that materials without one bind: every draw writes its texture binding (lavapipe crashes on
// an unwritten one) and multiplying by white changes nothing.
#include "penumbra/scene.h"
#include "vk/resources.h"

#include <vector>

namespace penumbra::render {

struct GpuTextures {
    std::vector<vk::Image> images;           // per Scene::images, then the white texture
    std::vector<vk::SamplerHandle> samplers; // per Scene::textures, then the white one's
    // Per image, where a material reads it stored linear (KHR_materials_transmission's texture):
    // a UNORM view of its bytes as they are; else none.
    std::vector<vk::ImageViewHandle> linearViews;
    struct Binding {
        VkImageView view;
        VkSampler sampler;
    };
    // The base-colour texture `material` of `scene` samples (white when it has none).
    Binding of(const Scene& scene, const Material& material) const;
    // Its transmission texture, through the linear view (white when it has none).
    Binding transmissionOf(const Scene& scene, const Material& material) const;
    Binding white() const { return {images.back().view.get(), samplers.back().get()}; }
};

GpuTextures uploadTextures(const vk::Context& ctx, const Scene& scene);

} // namespace penumbra::render
