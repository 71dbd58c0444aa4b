#pragma once
// Ground truth: the fraction of each light's solid angle that no geometry blocks, seen from
// every pixel of a rendered G-buffer, by ray tracing the scene's triangles with Embree.
//  - Spot and point lights of radius R are spheres of uniform radiance: directions are sampled
//    uniformly over the cone the sphere subtends; a ray ends where it reaches the sphere.
//  - A directional light of angular diameter A is the cone of that full angle around the
//    direction the light comes from.
//  - R = 0 or A = 0: one exact ray per pixel, the truth for hard shadows.
#include "penumbra/renderer.h"
#include "penumbra/scene.h"

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

namespace penumbra {

struct ReferenceOptions {
    uint32_t samples = 256;   // rays per pixel and light for lights with a size (1 .. 65536)
    std::string embreeConfig; // rtcNewDevice configuration, e.g. "threads=2"
    bool progress = false;    // a progress bar on stderr when the work runs past a second
    // For a caller tracing in the background (the viewer): rows done so far are added to
    // `rowsDone`; once `cancel` is true the remaining rows are skipped (left NaN).
    std::atomic<uint32_t>* rowsDone = nullptr;
    const std::atomic<bool>* cancel = nullptr;
};

struct ReferenceResult {
    uint32_t width = 0, height = 0;
    std::vector<std::vector<float>> visibility; // per shadow-casting light, as RenderResult
    // Where the scene has translucent casters, per shadow-casting light: the light that arrives
    // through them per channel (linear RGB, 3 floats a pixel, the rays' mean transmittance), and
    // `visibility` is its luminance. Empty without translucent casters.
    std::vector<std::vector<float>> transmittance;
    // Per shadow-casting light: how far along the ray to the light's centre the nearest occluder
    // lies (world units; infinity: none; NaN: background), what tells a contact shadow, whose
    // caster is near, from a long one.
    std::vector<std::vector<float>> occluderDistance;
    uint64_t rays = 0;
    double seconds = 0.0;      // everything: scene build and tracing
    double traceSeconds = 0.0; // tracing alone: rays / traceSeconds is the ray rate
    size_t triangles = 0;      // what Embree was given (the rasterizer draws the same)
};

// Rec. 709's luminance of linear RGB: what one channel of visibility is for a coloured one.
inline double luminance(double r, double g, double b) {
    return 0.2126 * r + 0.7152 * g + 0.0722 * b;
}

// Throws InputError("--samples", ...) outside 1..65536.
void validate(const ReferenceOptions& options);

// Traces from the world positions of `gbuffer` (its position and normal images). The scene
// must be the one the G-buffer was rendered from, with the same light-size overrides applied.
// Throws std::runtime_error("embree: ...") on an Embree failure.
ReferenceResult computeReference(const Scene& scene, const RenderResult& gbuffer,
                                 const ReferenceOptions& options);

// The Embree version this build links, e.g. "3.13.5".
std::string embreeVersion();

} // namespace penumbra
