#pragma once
// GPU tests share one Renderer with the Khronos validation layer (and synchronization
// validation) on and a persistent debug messenger; every test fails if it caused any validation
// message at all, warnings and performance warnings included. There is no allow-list.
#include "penumbra/renderer.h"
#include "scene/builtin_scenes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace penumbra::test {

inline Renderer& sharedRenderer() {
    static Renderer renderer({.deviceIndex = -1, .validation = true});
    return renderer;
}

class GpuTest : public ::testing::Test {
protected:
    void SetUp() override { mMessagesBefore = sharedRenderer().validationMessages(); }
    void TearDown() override {
        EXPECT_EQ(sharedRenderer().validationMessages(), mMessagesBefore)
            << "Vulkan validation messages during this test (on stderr)";
    }
    RenderResult render(const Scene& scene, RenderOptions options) {
        options.frames = 1;
        return sharedRenderer().render(scene, options);
    }

private:
    uint32_t mMessagesBefore = 0;
};

// The suite name is the test's area: tests/CMakeLists.txt gives each area a ctest label, which
// `make mutation-test` uses to run only the tests that can see a change.
using FilterTest = GpuTest;   // filters on synthetic maps: CPU/GPU parity, closed forms
using ShadowTest = GpuTest;   // where shadows land, what the frame outputs
using BiasTest = GpuTest;     // acne and peter-panning for each bias and light type
using LightingTest = GpuTest; // the lit image: composite, attenuation, shadow intensity
using QualityTest = GpuTest;  // every technique against the ray-traced ground truth
using MaterialTest = GpuTest; // textures, alpha-tested casters, culling
using FieldTest = GpuTest;    // the sdf technique's distance field: build, sign, cache
using FrameTest = GpuTest;    // the frame graph: order, barriers, the resource pool
using LayerTest = GpuTest;    // layers on a light's evaluation (contact shadows)
using VirtualTest = GpuTest;  // virtual shadow maps: pages, their cache, against the truth

inline glm::vec3 pixelVec(const std::vector<float>& v, size_t i) {
    return {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
}

// How far a hardware-filtered 2x2 comparison tap may read from the exact bilinear mix: the texture
// unit keeps subTexelPrecisionBits of each axis's fraction, and Vulkan does not say whether it
// rounds or truncates, so each fraction may be up to one step 2^-bits off; the mix moves by at
// most its fraction's change along each axis (its slope is at most 1 there): 2 x 2^-bits.
inline double hardwareFilterTolerance() {
    const DeviceInfo& device = sharedRenderer().device();
    return device.depthLinearFilter ? std::ldexp(2.0, -int(device.subTexelPrecisionBits)) : 0.0;
}

// Pixels of the ground plane y = 0 facing up.
inline bool onGround(const RenderResult& r, size_t i) {
    const glm::vec3 p = pixelVec(r.position, i), n = pixelVec(r.normal, i);
    return std::isfinite(p.x) && std::abs(p.y) < 1e-3f && n.y > 0.999f;
}

// Distance from `center` to the ray origin + t dir, t >= 0 (dir unit length).
inline float rayPointDistance(const glm::vec3& origin, const glm::vec3& dir,
                              const glm::vec3& center) {
    const float t = std::max(glm::dot(center - origin, dir), 0.0f);
    return glm::length(origin + t * dir - center);
}

// Whether the ray origin + t dir (t > 0) hits the axis-aligned box [lo, hi] (slab test).
inline bool rayHitsBox(const glm::vec3& origin, const glm::vec3& dir, const glm::vec3& lo,
                       const glm::vec3& hi) {
    float tNear = 0.0f, tFar = 1e30f;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(dir[a]) < 1e-12f) {
            if (origin[a] < lo[a] || origin[a] > hi[a])
                return false;
            continue;
        }
        float t0 = (lo[a] - origin[a]) / dir[a], t1 = (hi[a] - origin[a]) / dir[a];
        if (t0 > t1)
            std::swap(t0, t1);
        tNear = std::max(tNear, t0), tFar = std::min(tFar, t1);
        if (tNear > tFar)
            return false;
    }
    return true;
}

// Fraction of builtin:grazing's plane pixels that nothing can shadow, yet have visibility < 1:
// acne. "Nothing can shadow": the ray toward the light misses the box grown by `margin` (beyond
// a filter's reach, and past hard-shadow aliasing at the true boundary).
inline double grazingAcneFraction(const RenderResult& r, const Scene& scene, float margin,
                                  size_t* counted) {
    const glm::vec3 toLight = -glm::normalize(scene.lights[0].direction);
    const glm::vec3 lo = builtin::kGrazingBoxCenter - 0.5f * builtin::kGrazingBoxSize - margin;
    const glm::vec3 hi = builtin::kGrazingBoxCenter + 0.5f * builtin::kGrazingBoxSize + margin;
    size_t lit = 0, acne = 0;
    for (size_t i = 0; i < size_t{r.width} * r.height; ++i) {
        if (!onGround(r, i) || rayHitsBox(pixelVec(r.position, i), toLight, lo, hi))
            continue;
        ++lit;
        acne += r.visibility[0][i] < 1.0f;
    }
    *counted = lit;
    return lit ? static_cast<double>(acne) / static_cast<double>(lit) : 1.0;
}

} // namespace penumbra::test
