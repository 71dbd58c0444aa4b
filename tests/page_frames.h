#pragma once
// Random frames of virtual-map page decisions (tests/test_page_decisions.cpp, the CPU reference
// against the host cache; tests/test_page_decision_passes.cpp, the device against the reference):
// three lights' levels (a sun's window moving with the camera, a spot, a bulb that comes and
// goes), random requests, lights re-keyed and casters moved, in a pool too small for them.
#include "core/virtual_maps.h"
#include "virtual_field.h"

#include <random>
#include <vector>

namespace penumbra::test {
using namespace penumbra::virtual_field;

struct Frame {
    std::vector<VirtualLevel> levels;
    std::vector<uint32_t> requests; // one word per entry
    std::vector<uint32_t> rekeyed;
    std::vector<Bounds> moved;
};

// Frame `n` of a random sequence: the camera walks, the bulb is there two frames of three, each
// light's contents change now and then, boxes move. `s`: the virtual maps' sizes.
inline Frame randomFrame(std::mt19937& rng, glm::vec3& camera, const VirtualSettings& s = small()) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), step(-60.0f, 60.0f);
    camera += glm::vec3(step(rng), 0.0f, step(rng));
    Frame f;
    uint32_t offset = 0;
    const Light lights[] = {kSun, kSpot, kPoint};
    for (uint32_t light = 0; light < 3; ++light) {
        if (light == 2 && unit(rng) < 0.33f)
            continue;
        for (const VirtualLevel& l : virtualLevels(lights[light], light, kField, camera, s,
                                                   {.nearestSurface = 5.0f}, offset))
            f.levels.push_back(l);
        if (unit(rng) < 0.15f)
            f.rekeyed.push_back(light);
    }
    f.requests.assign(offset, 0u);
    // Patches of pages in random levels: sometimes more than the pool holds.
    const int patches = std::uniform_int_distribution<int>(0, 12)(rng);
    for (int k = 0; k < patches; ++k) {
        const VirtualLevel& l =
            f.levels[std::uniform_int_distribution<size_t>(0, f.levels.size() - 1)(rng)];
        const int n = int(l.pagesPerSide);
        std::uniform_int_distribution<int> at(0, n - 1), extent(0, std::min(n - 1, 7));
        const int x0 = at(rng), y0 = at(rng), w = extent(rng), h = extent(rng);
        for (int y = y0; y <= std::min(n - 1, y0 + h); ++y)
            for (int x = x0; x <= std::min(n - 1, x0 + w); ++x)
                f.requests[l.tableOffset + uint32_t(y) * l.pagesPerSide + uint32_t(x)] = 1u;
    }
    if (unit(rng) < 0.4f)
        for (int k = std::uniform_int_distribution<int>(1, 4)(rng); k > 0; --k) {
            const glm::vec3 at =
                glm::vec3(camera.x + step(rng), 10.0f * unit(rng), camera.z + step(rng));
            f.moved.push_back({.min = at, .max = at + 8.0f * unit(rng)});
        }
    return f;
}

} // namespace penumbra::test
