#pragma once
// The `contact` layer's CPU reference (src/shadows/contact.cpp): shaders/contact.comp's march,
// operation for operation, over an exported G-buffer.
#include "contact_march.h"
#include "frame_block.h"
#include "penumbra/scene.h"
#include "penumbra/settings.h"

#include <span>
#include <vector>

namespace penumbra::shadows {

// The G-buffer as the host reads it back (RenderResult::position, faceNormal): xyz per pixel,
// rows top to bottom, NaN where there is no geometry.
struct ScreenGBuffer {
    uint32_t width = 0, height = 0;
    std::span<const float> position, faceNormal;
};

// What a compare row "<row>+contact" marches, as a fraction of the scene's bounding radius
// (where the caller leaves contact.length off); also the band within which metrics count a
// shadow as a contact shadow (leak_near_contact).
inline constexpr double kContactRowFraction = 0.02;

// The layer's block for these parameters (contact.thickness 0: half the march's length).
gpu::ContactParams contactParams(const ParameterValues& params);

// Per pixel: 1 where no G-buffer surface within the march hides `light`, 0 where one does, NaN
// on the background. `frame`: the frame block the layer read (its camera matrices and size).
std::vector<float> contactReference(const ScreenGBuffer& gbuffer, const gpu::FrameData& frame,
                                    const Light& light, const gpu::ContactParams& params);

} // namespace penumbra::shadows
