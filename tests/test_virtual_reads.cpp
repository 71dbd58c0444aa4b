// Virtual shadow maps where a filter's taps leave the receiver's page: taps on pages the pool
// could not hold (they read as lit, never as an occluder), and taps across a point light's cube
// seams (the neighbouring face's pages are asked for too), against the ray-traced truth.
#include "analytic_scenes.h"
#include "truth_fixture.h"

#include <algorithm>

using namespace penumbra;
using namespace penumbra::test;

namespace {

using Sets = std::vector<std::pair<std::string, std::string>>;

Sets with(Sets a, const Sets& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

// Low over spheres that float above the plane: the cube's seams cross their shadows on it
// (|x - 0.2| = 2 and |z + 0.4| = 2), and no shadow touches its caster.
Light lowPoint() {
    return {.name = "point",
            .type = LightType::Point,
            .position = {0.2f, 2.0f, -0.4f},
            .intensity = 6.0f};
}
Light sun() {
    return {.name = "sun",
            .type = LightType::Directional,
            .direction = glm::normalize(glm::vec3(0.5f, -0.7f, -0.4f))};
}

// Pixels whose direction from the point light lies within `band` (in a face's uv, -1..1) of a
// cube face's edge: where a kernel's taps fall in the neighbouring face.
std::vector<uint8_t> seamBand(const Truth& t, const glm::vec3& light, float band) {
    const std::vector<float>& p = t.gbuffer.position;
    std::vector<uint8_t> mask(t.mask.size(), 0);
    for (size_t i = 0; i < mask.size(); ++i) {
        const glm::vec3 d = glm::abs(glm::vec3(p[3 * i], p[3 * i + 1], p[3 * i + 2]) - light);
        if (!t.mask[i] || !std::isfinite(d.x))
            continue;
        const float major = std::max({d.x, d.y, d.z});
        const float second = d.x + d.y + d.z - major - std::min({d.x, d.y, d.z});
        mask[i] = major > 0.0f && 1.0f - second / major <= band;
    }
    return mask;
}

ErrorMetrics errorIn(const Truth& t, const RenderResult& r, const std::vector<uint8_t>& mask) {
    const MetricLayer layer{r.visibility[0], t.reference.visibility[0], mask};
    return computeMetrics(r.width, r.height, std::span(&layer, 1));
}

// The fraction of the pixels `mask` holds (and the truth counts) where two renders disagree on
// which side of a shadow's edge they lie (|a - b| > 1/2).
double disagreement(const Truth& t, const RenderResult& a, const RenderResult& b,
                    const std::vector<uint8_t>& mask) {
    size_t pixels = 0, differ = 0;
    for (size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i] || !t.mask[i] || std::isnan(a.visibility[0][i]))
            continue;
        ++pixels;
        differ += std::abs(a.visibility[0][i] - b.visibility[0][i]) > 0.5f;
    }

    return pixels ? double(differ) / double(pixels) : 0.0;
}

// Lit pixels farther than `radius` pixels from every pixel the truth shadows.
std::vector<uint8_t> farFromShadow(const Truth& t, int radius) {
    const int w = int(t.setup.width), h = int(t.setup.height);
    const std::vector<float>& truth = t.reference.visibility[0];
    std::vector<uint8_t> mask(t.mask.size(), 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            if (!t.mask[i] || !(truth[i] >= 1.0f))
                continue;
            bool far = true;
            for (int dy = -radius; dy <= radius && far; ++dy)
                for (int dx = -radius; dx <= radius && far; ++dx) {
                    const int u = x + dx, v = y + dy;
                    if (u >= 0 && v >= 0 && u < w && v < h)
                        far = !(truth[size_t(v) * size_t(w) + size_t(u)] < 1.0f);
                }
            mask[i] = far;
        }
    return mask;
}

} // namespace

// A pool too small for the view drops pages, and a pixel reads the finest level whose page at its
// receiver is resident; its kernel's taps may still land on neighbouring pages that are not.
// Those read as the far plane: a shadow loses detail, but a lit pixel far from every shadow (16
// pixels, more than any kernel here reaches at the levels the pool keeps) stays lit. Floating
// spheres: no shadow touches its caster, so nothing else darkens such a pixel.
TEST_F(VirtualTest, TapsOnMissingPagesReadLitUnderEveryLightType) {
    const Sets cramped = {
        {"virtual.enabled", "1"}, {"virtual.pageSize", "32"}, {"virtual.poolSize", "256"}};
    for (const Light& light : {sun(), lowPoint()}) {
        const Truth t =
            groundTruth(spheresOverPlane(light),
                        {.width = 240, .height = 180, .shadowMapSize = 1024, .samples = 1});
        const std::vector<uint8_t> far = farFromShadow(t, 16);
        for (const Sets& kernel : {Sets{{"pcf.filter", "box"}, {"pcf.size", "3"}},
                                   Sets{{"pcf.filter", "box"}, {"pcf.size", "5"}}}) {
            const RenderResult r = renderRow(t, Technique::Pcf, with(kernel, cramped));
            ASSERT_TRUE(r.virtualMaps);
            const ErrorMetrics e = errorIn(t, r, far);
            std::printf("%s, box %s: %u of %u pages dropped; %llu lit pixels far from shadows, "
                        "%.4f%% dark\n",
                        light.name.c_str(), kernel[1].second.c_str(), r.virtualMaps->dropped,
                        r.virtualMaps->requested, static_cast<unsigned long long>(e.truthLit),
                        100.0 * e.acne);
            EXPECT_GT(r.virtualMaps->dropped, 0u) << light.name << ": the test needs drops";
            EXPECT_GE(e.truthLit, 5000u) << light.name;
            EXPECT_LE(e.acnePixels, e.truthLit / 2000) << light.name << " box " << kernel[1].second;
        }
    }
}

// A kernel centred by a cube seam reads its face's guard band, which holds the neighbouring
// face's geometry: through pages as through a cube. By the seams (a band of 0.04 in a face's
// tangent either side) the pages lose or add no shadow away from the truth's edges, and disagree
// with the cube no more often than they do elsewhere, for narrow and wide kernels.
TEST_F(VirtualTest, KernelsBySeamsReadAsTheCubeReads) {
    const Light light = lowPoint();
    const Truth t = groundTruth(spheresOverPlane(light),
                                {.width = 320, .height = 240, .shadowMapSize = 512, .samples = 1});
    const std::vector<uint8_t> band = seamBand(t, light.position, 0.04f);
    std::vector<uint8_t> elsewhere(band.size());
    for (size_t i = 0; i < band.size(); ++i)
        elsewhere[i] = !band[i];
    for (const char* size : {"3", "7", "11"}) {
        const Sets kernel{{"pcf.filter", "box"}, {"pcf.size", size}};
        const RenderResult cubeRow = renderRow(t, Technique::Pcf, kernel);
        const RenderResult pagesRow =
            renderRow(t, Technique::Pcf, with(kernel, {{"virtual.enabled", "1"}}));
        const ErrorMetrics cube = errorIn(t, cubeRow, band), pages = errorIn(t, pagesRow, band);
        const double bySeams = disagreement(t, cubeRow, pagesRow, band),
                     away = disagreement(t, cubeRow, pagesRow, elsewhere);
        std::printf("box %s by the seams (%llu pixels, %llu shadowed): misclassified away from "
                    "edges %.3f%% -> %.3f%%; pages and cube disagree on %.3f%% (%.3f%% "
                    "elsewhere)\n",
                    size, static_cast<unsigned long long>(cube.pixels),
                    static_cast<unsigned long long>(cube.truthShadowed),
                    100 * cube.misclassifiedOutsideEdges, 100 * pages.misclassifiedOutsideEdges,
                    100 * bySeams, 100 * away);
        EXPECT_GE(cube.truthShadowed, 500u) << "the seams must cross shadows";
        EXPECT_LE(pages.misclassifiedOutsideEdges, cube.misclassifiedOutsideEdges + 0.001) << size;
        EXPECT_LE(bySeams, 2.0 * away + 0.002) << size;
    }
}
