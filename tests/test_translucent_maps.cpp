// The translucent techniques' texels (src/shadows/translucent_maps.h, shaders/include/
// translucent.h): what each keeps of a texel's translucent surfaces and the transmittance a
// receiver reads back, on generated stacks and on builtin:sheets' ideal (deep) maps, whose
// surfaces Embree lists along each light ray (EmbreeScene::surfacesAlong). CPU only.
#include "penumbra/reference.h"
#include "reference/embree_scene.h"
#include "reference/sampling.h"
#include "scene/builtin_scenes.h"
#include "shadows/translucent_maps.h"
#include "translucent.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

using namespace penumbra;
using namespace penumbra::shadows;

namespace {

// The moment bias for 32-bit floats (Muenstermann et al. 2018 use 5e-7 for four power moments):
constexpr float kBias = 5e-7f;
// moments.overestimation's default: on ideal maps every share of the upper bound costs
// (IdealMapsOfTheStackedSheets).
constexpr float kOverestimation = 0.0f;

float luma(glm::vec3 c) {
    return static_cast<float>(luminance(c.x, c.y, c.z));
}

// `count` surfaces at depths in [0.05, 0.95], at least `gap` apart, each letting through
// between 5% and all of each channel.
std::vector<TranslucentLayer> generatedStack(std::mt19937& rng, int count, float gap) {
    std::uniform_real_distribution<float> depth(0.05f, 0.95f), through(0.05f, 1.0f);
    std::vector<TranslucentLayer> layers;
    while (static_cast<int>(layers.size()) < count) {
        const float z = depth(rng);
        if (std::any_of(layers.begin(), layers.end(),
                        [&](const TranslucentLayer& l) { return std::abs(l.depth - z) < gap; }))
            continue;
        layers.push_back({z, {through(rng), through(rng), through(rng)}});
    }
    return layers;
}

// Receiver depths at least `gap` from every surface.
std::vector<float> receiversBetween(const std::vector<TranslucentLayer>& layers, float gap) {
    std::vector<float> out;
    for (float z = 0.01f; z < 1.0f; z += 0.01f)
        if (std::none_of(layers.begin(), layers.end(),
                         [&](const TranslucentLayer& l) { return std::abs(l.depth - z) < gap; }))
            out.push_back(z);
    return out;
}

} // namespace

// A single surface's absorbance is -ln T, clamped where T is 0; its moments the powers of
// 2 z - 1 times it.
TEST(TranslucentTexels, OneSurfaceAddsItsAbsorbanceAndItsMoments) {
    const glm::vec3 a = gpu::layerAbsorbance({0.5f, 1.0f, 0.0f});
    EXPECT_FLOAT_EQ(a.x, std::log(2.0f));
    EXPECT_FLOAT_EQ(a.y, 0.0f);
    EXPECT_NEAR(a.z, 9.2103404f, 1e-5f);                // -ln 1e-4: at most this much a surface
    const glm::vec4 m = gpu::layerMoments(2.0f, 0.75f); // x = 0.5
    EXPECT_FLOAT_EQ(m.x, 1.0f);
    EXPECT_FLOAT_EQ(m.y, 0.5f);
    EXPECT_FLOAT_EQ(m.z, 0.25f);
    EXPECT_FLOAT_EQ(m.w, 0.125f);
    const ColouredTexel none = colouredTexel({});
    EXPECT_EQ(none.nearest, 1.0f);
    EXPECT_EQ(none.product, glm::vec3(1.0f));
    EXPECT_EQ(momentTransmittance(momentTexel({}), 0.5f, kBias, 0.0f), glm::vec3(1.0f));
}

// The coloured map keeps the nearest depth and transmittance, the second nearest depth and the
// product: exact in front of the second surface and behind them all, the product of all between
// (its documented error).
TEST(TranslucentTexels, TheColouredMapIsExactOutsideTheStack) {
    std::mt19937 rng(61062u);
    for (int trial = 0; trial < 200; ++trial) {
        const auto layers = generatedStack(rng, 1 + trial % 4, 0.02f);
        const ColouredTexel texel = colouredTexel(layers);
        std::vector<float> depths;
        for (const TranslucentLayer& l : layers)
            depths.push_back(l.depth);
        std::sort(depths.begin(), depths.end());
        const float nearest = depths.front(), farthest = depths.back();
        const float second = depths.size() > 1 ? depths[1] : 1.0f;
        EXPECT_EQ(texel.nearest, nearest);
        EXPECT_EQ(texel.second, second);
        for (float z : receiversBetween(layers, 0.005f)) {
            const glm::vec3 got = colouredTransmittance(texel, z);
            const glm::vec3 want = z > second    ? exactTransmittance(layers, 1.0f)
                                   : z > nearest ? exactTransmittance(layers, second)
                                                 : glm::vec3(1.0f);
            for (int c = 0; c < 3; ++c)
                EXPECT_FLOAT_EQ(got[c], want[c]) << "trial " << trial << ", z " << z;
            if (z > farthest || z < second) {
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(got[c], exactTransmittance(layers, z)[c], 1e-6f);
            }
        }
    }
}

// Four moments hold one or two surfaces exactly: every receiver between, in front and behind
// reads what the surfaces in front of it let through, up to the bias's pull, in every channel.
// (The pull is on the normalised moments: a faint surface beside a dark one in a channel takes
// its largest share, 0.008 here; at msm's bias of 3e-5 it would be 0.18.)
TEST(TranslucentTexels, MomentsHoldOneOrTwoSurfacesExactly) {
    std::mt19937 rng(20181u);
    double worst = 0.0;
    for (int trial = 0; trial < 400; ++trial) {
        const auto layers = generatedStack(rng, 1 + trial % 2, 0.1f);
        const MomentTexel texel = momentTexel(layers);
        for (float z : receiversBetween(layers, 0.05f)) {
            const glm::vec3 got = momentTransmittance(texel, z, kBias, 0.0f);
            const glm::vec3 want = exactTransmittance(layers, z);
            for (int c = 0; c < 3; ++c)
                worst = std::max(worst, static_cast<double>(std::abs(got[c] - want[c])));
        }
    }
    std::printf("two surfaces: worst %.2e\n", worst);
    EXPECT_LT(worst, 1e-2);
}

// Whatever the stack: a receiver deeper down keeps no more light in any channel (the bounds are
// monotone; up to float rounding in the reconstruction, 1e-4), in [0, 1], 1 in front of
// everything from the lower bound; the order the surfaces arrive in changes nothing but
// rounding.
TEST(TranslucentTexels, MomentTransmittanceFallsWithDepthWhateverTheStack) {
    std::mt19937 rng(7u);
    for (int trial = 0; trial < 300; ++trial) {
        auto layers = generatedStack(rng, 1 + trial % 6, 0.02f);
        const float overestimation = static_cast<float>(trial % 3) * 0.25f;
        const MomentTexel texel = momentTexel(layers);
        std::shuffle(layers.begin(), layers.end(), rng);
        const MomentTexel shuffled = momentTexel(layers);
        glm::vec3 last(1.0f);
        for (float z = 0.0f; z <= 1.0f; z += 0.005f) {
            const glm::vec3 t = momentTransmittance(texel, z, kBias, overestimation);
            const glm::vec3 u = momentTransmittance(shuffled, z, kBias, overestimation);
            for (int c = 0; c < 3; ++c) {
                EXPECT_GE(t[c], 0.0f);
                EXPECT_LE(t[c], last[c] + 1e-4f) << "trial " << trial << ", z " << z;
                EXPECT_NEAR(t[c], u[c], 1e-3f);
            }
            if (z < 0.04f && overestimation == 0.0f) {
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(t[c], 1.0f, 1e-3f) << "in front, trial " << trial;
            }
            last = t;
        }
    }
}

namespace {

// A texel's ray on builtin:sheets' ideal map: from the light (a sun's from a plane beyond the
// scene, `radius` before its centre) through the receiver p, the depths over [0, far].
struct IdealRay {
    glm::vec3 origin, dir;
    float receiver, far; // p's distance along it; the depth range
};

IdealRay idealRay(const Light& light, const Bounds& bounds, glm::vec3 p) {
    const glm::vec3 c = bounds.center();
    const float r = bounds.radius();
    if (light.type == LightType::Directional) {
        const glm::vec3 d = glm::normalize(light.direction);
        const float before = glm::dot(p - c, d) + r;
        return {p - d * before, d, before, 2.0f * r};
    }
    const glm::vec3 d = glm::normalize(p - light.position);
    return {light.position, d, glm::length(p - light.position),
            glm::length(c - light.position) + r};
}

struct ModelErrors {
    size_t receivers = 0, between = 0;     // compared; with a surface of their stack behind them
    size_t grazing = 0;                    // left out: the list and the truth's ray disagree
    double colouredGround = 0;             // the coloured map's worst channel error on the ground
    double coloured = 0, moments = 0;      // luminance: sums of squares
    std::array<double, 5> overestimated{}; // moments.overestimation 0, 0.1, ... 0.4
    double colouredChannel = 0, momentsChannel = 0; // worst channel error
    double colouredRmse() const { return std::sqrt(coloured / count()); }
    double momentsRmse() const { return std::sqrt(moments / count()); }
    double overestimatedRmse(size_t k) const { return std::sqrt(overestimated[k] / count()); }
    double count() const { return static_cast<double>(receivers); }
};

// The receivers: a grid on the ground under the sheets and one on each sheet's upper face.
std::vector<glm::vec3> sheetReceivers() {
    // Cell centres of n cells over [-1, 1].
    const auto cell = [](int i, int n) {
        return 2.0f * (static_cast<float>(i) + 0.5f) / static_cast<float>(n) - 1.0f;
    };
    std::vector<glm::vec3> out;
    for (int i = 0; i < 64; ++i)
        for (int j = 0; j < 64; ++j)
            out.push_back({1.0f + 3.0f * cell(i, 64), 0.0f, 0.5f + 3.0f * cell(j, 64)});
    for (const builtin::SheetSpec& sheet : builtin::kSheets)
        for (int i = 0; i < 24; ++i)
            for (int j = 0; j < 24; ++j)
                out.push_back({sheet.centre.x + sheet.halfSize.x * cell(i, 24), sheet.height,
                               sheet.centre.y + sheet.halfSize.y * cell(j, 24)});
    return out;
}

ModelErrors idealMapErrors(const Scene& scene, const EmbreeScene& embree, const Light& light) {
    const Bounds bounds = scene.bounds();
    ModelErrors e;
    constexpr float kLift = 1e-3f; // world units: the receiver's bias towards the light
    for (const glm::vec3& p : sheetReceivers()) {
        const IdealRay ray = idealRay(light, bounds, p);
        const EmbreeScene::SurfacesAlong along =
            embree.surfacesAlong(ray.origin, ray.dir, 0.0f, std::numeric_limits<float>::infinity());
        if (along.opaque < ray.receiver - kLift)
            continue; // an opaque caster's shadow: the base technique's
        const float towardsLight = light.type == LightType::Directional ? 1e30f : ray.receiver;
        const glm::vec3 truth = embree.transmittance(p, -ray.dir, kLift, towardsLight);
        std::vector<TranslucentLayer> layers;
        for (const EmbreeScene::CrossedSurface& s : along.translucent)
            layers.push_back({s.distance / ray.far, s.transmittance});
        const float z = (ray.receiver - kLift) / ray.far;
        // The ideal map's surfaces in front of the receiver are what the truth's ray crosses,
        // but where the two rays, from either end, graze a sheet's edge.
        const glm::vec3 exact = exactTransmittance(layers, z);
        if (glm::any(glm::greaterThan(glm::abs(exact - truth), glm::vec3(1e-6f)))) {
            ++e.grazing;
            continue;
        }
        const auto square = [](float x) { return static_cast<double>(x) * x; };
        const glm::vec3 coloured = colouredTransmittance(colouredTexel(layers), z);
        const MomentTexel texel = momentTexel(layers);
        const glm::vec3 moments = momentTransmittance(texel, z, kBias, kOverestimation);
        for (size_t k = 0; k < e.overestimated.size(); ++k) {
            const float beta = 0.1f * static_cast<float>(k);
            e.overestimated[k] +=
                square(luma(momentTransmittance(texel, z, kBias, beta)) - luma(truth));
        }
        ++e.receivers;
        e.between += std::any_of(layers.begin(), layers.end(),
                                 [&](const TranslucentLayer& l) { return l.depth > z; });
        e.coloured += square(luma(coloured) - luma(truth));
        e.moments += square(luma(moments) - luma(truth));
        if (p.y == 0.0f) // under the whole stack
            e.colouredGround = std::max(e.colouredGround, double{glm::length(coloured - truth)});
        for (int c = 0; c < 3; ++c) {
            e.colouredChannel =
                std::max(e.colouredChannel, double{std::abs(coloured[c] - truth[c])});
            e.momentsChannel = std::max(e.momentsChannel, double{std::abs(moments[c] - truth[c])});
        }
    }
    return e;
}

} // namespace

// builtin:sheets' ideal maps under a sun and from a light's position (a spot's and a point
// light's rays alike; their maps differ in resolution, which this leaves out): each technique's
// own error against the truth at the same receivers, on the ground and on the sheets (where a
// receiver lies between surfaces of its texel's stack). The list Embree gives matches the
// truth's ray; the moments meet the bound of 0.03 on their own; the coloured map, exact
// under the whole stack, errs on the sheets.
TEST(TranslucentTexels, IdealMapsOfTheStackedSheets) {
    const Scene scene = builtin::sheets();
    const EmbreeScene embree(scene, "threads=1");
    const Light lights[] = {
        {.name = "sun",
         .type = LightType::Directional,
         .direction = glm::normalize(builtin::kSheetsSunDirection)},
        {.name = "point", .type = LightType::Point, .position = {-1.5f, 6.0f, 0.5f}},
        {.name = "spot",
         .type = LightType::Spot,
         .position = {-2.5f, 7.0f, -1.0f},
         .direction = glm::normalize(glm::vec3(3.0f, -7.0f, 1.5f)),
         .outerConeAngle = 1.2f},
    };
    for (const Light& light : lights) {
        const ModelErrors e = idealMapErrors(scene, embree, light);
        std::printf("%s: %zu receivers (%zu grazing an edge), %zu between surfaces; luminance "
                    "RMSE coloured %.4f, moments %.4f; worst channel coloured %.3f, moments "
                    "%.3f\n",
                    light.name.c_str(), e.receivers, e.grazing, e.between, e.colouredRmse(),
                    e.momentsRmse(), e.colouredChannel, e.momentsChannel);
        std::printf("  moments with overestimation 0, 0.1, 0.2, 0.3, 0.4:");
        for (size_t k = 0; k < e.overestimated.size(); ++k) {
            std::printf(" %.4f", e.overestimatedRmse(k));
            if (k > 0) { // the upper bound's share only darkens what the lower bound got right
                EXPECT_GT(e.overestimatedRmse(k), e.overestimatedRmse(k - 1)) << light.name;
            }
        }
        std::printf("\n");
        EXPECT_GT(e.receivers, 4000u) << light.name;
        EXPECT_LT(e.grazing, e.receivers / 200) << light.name;
        EXPECT_GT(e.between, 300u) << light.name;
        EXPECT_LT(e.momentsRmse(), 0.03) << light.name;
        EXPECT_GT(e.colouredRmse(), e.momentsRmse()) << light.name;
        EXPECT_LT(e.colouredGround, 1e-6) << light.name;
    }
}
