// The filter maths the shaders and the CPU reference share (shaders/include: kernels.h, bias.h,
// moments.h, light_geometry.h, gbuffer_encoding.h),
// against answers derived independently: a plane's gradient from the inverse Jacobian and from
// finite differences, weights that sum to one, rotations that keep lengths, the depth mappings'
// end points.
#include "bias.h"
#include "core/light_space.h"
#include "core/projection.h"
#include "gbuffer_encoding.h"
#include "kernels.h"
#include "light_geometry.h"
#include "moments.h"

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include <cmath>

using namespace penumbra;

namespace {

// (u, v, depth) of a world point under the projective map S.
glm::dvec3 project(const glm::mat4& S, const glm::dvec3& p) {
    const glm::dvec4 s = glm::dmat4(S) * glm::dvec4(p, 1.0);
    return glm::dvec3(s) / s.w;
}

// The plane through p with normal n as it appears in (u, v, depth): the gradient of depth over
// (u, v), by finite differences along two tangents and a 2x2 solve in double.
glm::dvec2 gradientByDifferences(const glm::mat4& S, const glm::dvec3& p, const glm::dvec3& n) {
    const glm::dvec3 t1 = glm::normalize(
        glm::cross(n, std::abs(n.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0)));
    const glm::dvec3 t2 = glm::cross(n, t1);
    const double h = 1e-4;
    const glm::dvec3 a = (project(S, p + h * t1) - project(S, p - h * t1)) / (2 * h);
    const glm::dvec3 b = (project(S, p + h * t2) - project(S, p - h * t2)) / (2 * h);
    // Along each tangent, d depth = g.u du + g.v dv: rows (du_a, dv_a) and (du_b, dv_b).
    const glm::dmat2 rows(a.x, b.x, a.y, b.y); // glm is column-major: columns (du), (dv)
    return glm::inverse(rows) * glm::dvec2(a.z, b.z);
}

} // namespace

TEST(FilterMath, ReceiverPlaneGradientsFromTheNormalAndFromNeighboursAreThePlanes) {
    const Bounds scene = [] {
        Bounds b;
        b.grow({-10, 0, -10});
        b.grow({10, 4, 10});
        return b;
    }();
    const Light sun{.type = LightType::Directional,
                    .direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.4f))};
    const Light spot{.type = LightType::Spot,
                     .position = {-4, 9, -3},
                     .direction = glm::normalize(glm::vec3(0.4f, -1.0f, 0.3f)),
                     .outerConeAngle = 0.6f};
    for (const Light& light : {sun, spot}) {
        const glm::mat4 S =
            textureMatrix() * fitLightViews(light, scene, 1024, {}).front().viewProj;
        for (const glm::dvec3 n :
             {glm::dvec3(0, 1, 0), glm::normalize(glm::dvec3(0.5, 1, -0.2)),
              glm::normalize(glm::dvec3(-0.3, 0.8, 0.6)), glm::normalize(glm::dvec3(1, 0.2, 0))}) {
            const glm::dvec3 p(1.5, 0.7, -2.0);
            const glm::dvec2 want = gradientByDifferences(S, p, n);
            const glm::vec2 fromNormal =
                gpu::receiverGradientFromNormal(S, glm::vec3(p), glm::vec3(n));
            // The screen-space variant sees two neighbours' offsets along any two tangents.
            const glm::dvec3 t1 = glm::normalize(glm::cross(n, glm::dvec3(0.2, 0.3, 1.0)));
            const glm::dvec3 t2 = glm::cross(n, t1);
            const glm::vec3 alongX(project(S, p + 0.01 * t1) - project(S, p));
            const glm::vec3 alongY(project(S, p - 0.01 * t2) - project(S, p));
            const glm::vec2 fromOffsets = gpu::receiverGradientFromOffsets(alongX, alongY);
            const double scale = std::max(1.0, glm::length(want));
            const std::string what = std::string(lightTypeName(light.type)) + ", normal " +
                                     std::to_string(n.x) + " " + std::to_string(n.y) + " " +
                                     std::to_string(n.z);
            EXPECT_NEAR(fromNormal.x, want.x, 2e-3 * scale) << what;
            EXPECT_NEAR(fromNormal.y, want.y, 2e-3 * scale) << what;
            // Perspective maps bend over the 0.01 step the offsets take.
            const double tolerance = light.type == LightType::Spot ? 2e-2 : 2e-3;
            EXPECT_NEAR(fromOffsets.x, want.x, tolerance * scale) << what;
            EXPECT_NEAR(fromOffsets.y, want.y, tolerance * scale) << what;
        }
    }
    // Edge-on to the light: no plane to speak of.
    const glm::mat4 S = textureMatrix() * fitDirectional(sun, scene, 1024).viewProj;
    const glm::vec3 edgeOn = glm::normalize(glm::cross(sun.direction, glm::vec3(1, 0, 0)));
    EXPECT_EQ(gpu::receiverGradientFromNormal(S, {0, 1, 0}, edgeOn), glm::vec2(0.0f));
    EXPECT_EQ(gpu::receiverGradientFromOffsets({1, 2, 3}, {2, 4, 6}), glm::vec2(0.0f));
}

TEST(FilterMath, KernelWeightsSumToOneAndFollowTheBilinearFraction) {
    for (const uint32_t kind : {FILTER_BOX, FILTER_GAUSSIAN})
        for (int n = 1; n <= PCF_MAX_SIZE; n += 2)
            for (const float f : {0.0f, 0.25f, 0.5f, 0.9f}) {
                float c[PCF_MAX_SIZE + 1];
                gpu::footprintWeights(kind, n, 0.3f * float(n), f, c);
                double sum = 0;
                for (int k = 0; k <= n; ++k) {
                    EXPECT_GE(c[k], 0.0f);
                    sum += c[k];
                }
                EXPECT_NEAR(sum, 1.0, 1e-5) << "kind " << kind << " n " << n << " f " << f;
                if (kind == FILTER_BOX) { // (1 - f)/n, then 1/n, ..., then f/n
                    EXPECT_NEAR(c[0], (1.0f - f) / float(n), 1e-6f);
                    EXPECT_NEAR(c[n], f / float(n), 1e-6f);
                    for (int k = 1; k < n; ++k)
                        EXPECT_NEAR(c[k], 1.0f / float(n), 1e-6f);
                } else if (f == 0.5f) { // symmetric about the footprint's centre
                    for (int k = 0; k <= n; ++k)
                        EXPECT_NEAR(c[k], c[n - k], 1e-6f);
                    if (n >= 3) {
                        EXPECT_GT(c[n / 2], c[0]);
                    }
                }
            }
    // The bilinear mix of textureGather's (x (i, j+1), y (i+1, j+1), z (i+1, j), w (i, j)).
    const glm::vec4 tests(0.0f, 1.0f, 1.0f, 0.0f); // the right column passes
    EXPECT_FLOAT_EQ(gpu::bilinearMix(tests, {0.3f, 0.8f}), 0.3f);
    EXPECT_FLOAT_EQ(gpu::bilinearMix(glm::vec4(1, 1, 0, 0), {0.7f, 0.4f}), 0.4f); // top row
}

TEST(FilterMath, RotationsKeepLengthsAndTurnTheRightWay) {
    const glm::vec2 d(0.6f, -0.3f);
    for (const float turns : {0.0f, 0.1f, 0.25f, 0.5f, 0.9f}) {
        const glm::vec2 r = gpu::rotatedOffset(d, turns, 2.5f);
        EXPECT_NEAR(glm::length(r), 2.5f * glm::length(d), 1e-5f);
        const double angle = std::atan2(r.y, r.x) - std::atan2(d.y, d.x);
        EXPECT_NEAR(std::remainder(angle - 2 * M_PI * turns, 2 * M_PI), 0.0, 1e-5);
    }
    EXPECT_NEAR(gpu::rotatedOffset({1, 0}, 0.25f, 1.0f).y, 1.0f, 1e-6f); // counter-clockwise
    for (uint32_t x = 0; x < 64; ++x)
        for (const uint32_t rotation : {ROTATION_RANDOM, ROTATION_IGN}) {
            const float t = gpu::rotationTurns(rotation, {x * 37, x * 11 + 5});
            EXPECT_GE(t, 0.0f);
            EXPECT_LT(t, 1.0f);
        }
    EXPECT_EQ(gpu::rotationTurns(ROTATION_NONE, {17, 3}), 0.0f);
    EXPECT_NE(gpu::hashU32(1), gpu::hashU32(2));
}

TEST(FilterMath, TheRotationsCosineAndSineFromAddsAndMultipliesAreAccurate) {
    // Every quadrant and both ends of each: within 1e-6 of the double-precision functions (the
    // series' error is under 6e-8, float rounding adds a few ulps).
    double worst = 0.0;
    for (int i = 0; i <= 4096; ++i) {
        const float turns = static_cast<float>(i) / 4096.0f * 0.999999f;
        const glm::vec2 cs = gpu::turnCosSin(turns);
        const double angle = 2.0 * M_PI * static_cast<double>(turns);
        worst =
            std::max({worst, std::abs(cs.x - std::cos(angle)), std::abs(cs.y - std::sin(angle))});
    }
    EXPECT_LT(worst, 1e-6);
    // Quarter turns land exactly; the turn's whole part does not count.
    EXPECT_EQ(gpu::turnCosSin(0.25f), glm::vec2(0.0f, 1.0f));
    EXPECT_EQ(gpu::turnCosSin(0.5f), glm::vec2(-1.0f, 0.0f));
    EXPECT_EQ(gpu::turnCosSin(0.75f), glm::vec2(0.0f, -1.0f));
    EXPECT_EQ(gpu::turnCosSin(1.25f), gpu::turnCosSin(0.25f));
}

TEST(FilterMath, PcssGeometryMeetsItsEndPoints) {
    for (const float perspective : {0.0f, 1.0f}) {
        const gpu::ShadowViewData view{.frustum = {2.0f, 30.0f, 1.5f, 1.5f},
                                       .texel = {0.0f, perspective, 0.0f, 0.4f}};
        EXPECT_NEAR(gpu::viewDistance(view, 0.0f), 2.0f, 1e-5f);  // depth 0: the near plane
        EXPECT_NEAR(gpu::viewDistance(view, 1.0f), 30.0f, 1e-4f); // depth 1: the far plane
        // A receiver on the near plane has nothing to search; a blocker at the receiver casts
        // no penumbra.
        EXPECT_NEAR(gpu::blockerSearchRadius(view, 2.0f, 1024), 0.0f, 1e-5f);
        EXPECT_NEAR(gpu::penumbraRadius(view, 9.0f, 9.0f, 1024), 0.0f, 1e-5f);
        // Texels per world unit: the map's texels over what one uv unit spans there.
        const float z = 6.0f, spans = perspective > 0.5f ? 1.5f * z : 1.5f;
        EXPECT_NEAR(gpu::texelsPerWorld(view, z, 1024), 1024.0f / spans, 1e-3f);
    }
    EXPECT_EQ(gpu::snapToExtremes(0.999995f), 1.0f);
    EXPECT_EQ(gpu::snapToExtremes(0.99f), 0.99f);
    EXPECT_EQ(gpu::snapToExtremes(0.000005f), 0.0f);
}

TEST(FilterMath, CascadeBlendRisesAcrossTheBandFromNothingToTheNextCascade) {
    // A cascade whose slice ends at 10 and starts blending at 8.
    EXPECT_EQ(gpu::cascadeBlendWeight(5.0f, 8.0f, 10.0f), 0.0f); // before the band: this one
    EXPECT_EQ(gpu::cascadeBlendWeight(8.0f, 8.0f, 10.0f), 0.0f); // the band's start: no seam
    EXPECT_FLOAT_EQ(gpu::cascadeBlendWeight(8.5f, 8.0f, 10.0f), 0.25f);
    EXPECT_FLOAT_EQ(gpu::cascadeBlendWeight(9.0f, 8.0f, 10.0f), 0.5f);
    EXPECT_EQ(gpu::cascadeBlendWeight(10.0f, 8.0f, 10.0f), 1.0f); // the split: the next alone
    EXPECT_EQ(gpu::cascadeBlendWeight(12.0f, 8.0f, 10.0f), 1.0f);
    // csm.blend 0: no band, a switch at the split.
    EXPECT_EQ(gpu::cascadeBlendWeight(9.99f, 10.0f, 10.0f), 0.0f);
    EXPECT_EQ(gpu::cascadeBlendWeight(10.01f, 10.0f, 10.0f), 1.0f);
}

TEST(FilterMath, VarianceShadowMapsMathMeetsItsDefinitions) {
    // Moment depth: linear in the view distance, 0 at the near plane, 1 at the far one.
    gpu::ShadowViewData perspective{};
    perspective.frustum = {0.5f, 20.0f, 1.0f, 1.0f};
    perspective.texel = {0.0f, 1.0f, 0.0f, 0.0f};
    for (float z : {0.5f, 1.0f, 7.0f, 20.0f}) {
        const float n = 0.5f, f = 20.0f;
        const float depth = (f / (f - n)) * (1.0f - n / z); // the perspective depth of z
        EXPECT_NEAR(gpu::momentDepth(perspective, depth), (z - n) / (f - n), 1e-5f) << z;
    }
    gpu::ShadowViewData orthographic = perspective;
    orthographic.texel.y = 0.0f;
    EXPECT_EQ(gpu::momentDepth(orthographic, 0.37f), 0.37f);
    // Chebyshev's one-tailed bound: 1 up to the mean, then sigma^2 / (sigma^2 + d^2).
    EXPECT_EQ(gpu::chebyshevUpperBound({0.4f, 0.17f}, 0.4f, 0.0f), 1.0f);
    EXPECT_EQ(gpu::chebyshevUpperBound({0.4f, 0.17f}, 0.2f, 0.0f), 1.0f);
    EXPECT_NEAR(gpu::chebyshevUpperBound({0.4f, 0.17f}, 0.6f, 0.0f), 0.01f / (0.01f + 0.04f),
                1e-5f);
    // The minimum variance takes over when the moments' own is smaller.
    EXPECT_NEAR(gpu::chebyshevUpperBound({0.4f, 0.16f}, 0.5f, 0.001f), 0.001f / 0.011f, 1e-5f);
    // Bleeding reduction: amount -> 0, 1 -> 1, linear between, 0 leaves p alone.
    EXPECT_EQ(gpu::reduceLightBleeding(0.3f, 0.3f), 0.0f);
    EXPECT_EQ(gpu::reduceLightBleeding(0.2f, 0.3f), 0.0f);
    EXPECT_EQ(gpu::reduceLightBleeding(1.0f, 0.3f), 1.0f);
    EXPECT_NEAR(gpu::reduceLightBleeding(0.65f, 0.3f), 0.5f, 1e-6f);
    EXPECT_EQ(gpu::reduceLightBleeding(0.42f, 0.0f), 0.42f);
    // Gaussian taps: symmetric, falling, sigma = n / 6 (tap 3 sigma out of the centre of 19).
    EXPECT_EQ(gpu::gaussianTap(0, 7), 1.0f);
    EXPECT_EQ(gpu::gaussianTap(-2, 7), gpu::gaussianTap(2, 7));
    EXPECT_GT(gpu::gaussianTap(1, 7), gpu::gaussianTap(2, 7));
    EXPECT_NEAR(gpu::gaussianTap(9, 18), std::exp(-0.5f * 9.0f), 1e-6f);
}

// Two depths a (weight w) and b: VSSM's estimate recovers both exactly, as Yang et al. derive.
TEST(FilterMath, ChebyshevBlockersRecoverTwoDepths) {
    for (float w : {0.1f, 0.5f, 0.9f}) {
        const float a = 0.2f, t = 0.7f; // blockers at a, the receiver (and the rest) at t
        const glm::vec2 moments(w * a + (1 - w) * t, w * a * a + (1 - w) * t * t);
        const glm::vec2 b = gpu::chebyshevBlockers(moments, t, 0.0f);
        EXPECT_NEAR(b.x, w, 1e-5f) << w;
        EXPECT_NEAR(b.y / b.x, a, 1e-5f) << w;
    }
    // A receiver not beyond the mean has no blockers.
    EXPECT_EQ(gpu::chebyshevBlockers({0.5f, 0.3f}, 0.5f, 1e-5f), glm::vec2(0.0f));
    // momentDepthDistance inverts momentDepth in both projections.
    gpu::ShadowViewData view{};
    view.frustum = {0.5f, 20.0f, 1.0f, 1.0f};
    view.texel = {0.0f, 1.0f, 0.0f, 0.0f};
    EXPECT_NEAR(gpu::momentDepthDistance(view, 0.0f), 0.5f, 1e-6f);
    EXPECT_NEAR(gpu::momentDepthDistance(view, 1.0f), 20.0f, 1e-5f);
    EXPECT_NEAR(gpu::momentDepthDistance(view, (7.0f - 0.5f) / 19.5f), 7.0f, 1e-5f);
}

TEST(FilterMath, MomentDepthSpreadsTheReceiversRangeAndInvertsOverIt) {
    // A cascade's receivers from 20% to 70% of the way from the near plane to the far one
    // (moments = the parts cut off in front and behind): that slice becomes [0, 1], casters in
    // front read 0, and momentDepthDistance walks back to the same distance, in both projections.
    for (const float perspective : {0.0f, 1.0f}) {
        gpu::ShadowViewData view{};
        view.frustum = {0.5f, 20.0f, 1.0f, 1.0f};
        view.texel = {0.0f, perspective, 0.0f, 0.0f};
        view.moments = {0.2f, 0.3f, 0.0f, 0.0f};
        const float n = 0.5f, f = 20.0f;
        auto depthOf = [&](float z) { // the map's depth of view distance z
            return perspective > 0.5f ? (f / (f - n)) * (1.0f - n / z) : (z - n) / (f - n);
        };
        for (const float share : {0.0f, 0.25f, 0.5f, 1.0f}) {
            const float z = n + (0.2f + 0.5f * share) * (f - n);
            EXPECT_NEAR(gpu::momentDepth(view, depthOf(z)), share, 2e-5f)
                << z << " " << perspective;
            EXPECT_NEAR(gpu::momentDepthDistance(view, share), z, 1e-4f * z) << perspective;
        }
        EXPECT_EQ(gpu::momentDepth(view, depthOf(n + 0.1f * (f - n))), 0.0f); // a caster in front
        EXPECT_EQ(gpu::momentDepth(view, depthOf(n + 0.9f * (f - n))), 1.0f); // beyond the slice
    }
}

// Moment soft shadows' blockers on two and three atoms: with four moments the reconstruction
// of a two-atom distribution is exact, blockers and their depth included.
TEST(FilterMath, MomentBlockersRecoverTheAtomsInFront) {
    auto momentsOf = [](std::initializer_list<std::pair<float, float>> atoms) {
        glm::vec4 m(0.0f);
        for (auto [z, w] : atoms)
            m += w * glm::vec4(z, z * z, z * z * z, z * z * z * z);
        return m;
    };
    const glm::vec4 two = momentsOf({{-0.6f, 0.3f}, {0.4f, 0.7f}});
    glm::vec2 b = gpu::momentBlockers(two, 0.1f, 0.0f); // between: the atom at -0.6 blocks
    EXPECT_NEAR(b.x, 0.3f, 2e-3f);
    EXPECT_NEAR(b.y / b.x, -0.6f, 5e-3f);
    EXPECT_NEAR(gpu::momentOcclusion(two, 0.1f, 0.0f), 0.3f, 2e-3f);
    b = gpu::momentBlockers(two, 0.8f, 0.0f); // behind both: everything blocks, at the mean
    EXPECT_NEAR(b.x, 1.0f, 2e-3f);
    EXPECT_NEAR(b.y / b.x, 0.3f * -0.6f + 0.7f * 0.4f, 5e-3f);
    EXPECT_EQ(gpu::momentBlockers(two, -0.8f, 0.0f), glm::vec2(0.0f)); // in front of both
    // Three atoms: the reconstruction is a bound, the blockers' weight at most the truth's.
    const glm::vec4 three = momentsOf({{-0.7f, 0.2f}, {-0.1f, 0.3f}, {0.6f, 0.5f}});
    b = gpu::momentBlockers(three, 0.3f, 0.0f);
    EXPECT_LE(b.x, 0.5f + 1e-4f);
    EXPECT_NEAR(b.x, gpu::momentOcclusion(three, 0.3f, 0.0f), 1e-5f);
    EXPECT_GT(b.y / b.x, -0.7f);
    EXPECT_LT(b.y / b.x, 0.3f);
}

// bias.horizon: the part of a disc above a line at distance h from its centre.
TEST(FilterMath, HorizonVisibilityIsTheDiscAboveTheTangentPlane) {
    const float s = std::sin(0.1f); // a light of angular radius 0.1
    EXPECT_EQ(gpu::horizonVisibility(std::sin(0.1f), s), 1.0f);
    EXPECT_EQ(gpu::horizonVisibility(0.5f, s), 1.0f);
    EXPECT_EQ(gpu::horizonVisibility(-0.5f, s), 0.0f);
    EXPECT_NEAR(gpu::horizonVisibility(0.0f, s), 0.5f, 1e-6f);
    // Centre at half the radius above: the segment's area over the disc's,
    // 1/2 + (x sqrt(1 - x^2) + asin x) / pi at x = 1/2.
    const double x = 0.5, expected = 0.5 + (x * std::sqrt(1 - x * x) + std::asin(x)) / M_PI;
    EXPECT_NEAR(gpu::horizonVisibility(std::sin(0.05f), s), expected, 1e-4);
    EXPECT_NEAR(gpu::horizonVisibility(-std::sin(0.05f), s), 1.0 - expected, 1e-4);
    EXPECT_EQ(gpu::horizonVisibility(0.01f, 0.0f), 1.0f); // a point light: no change
}

// The G-buffer's normals: every octant, the poles, the equator and the unfolded seams come back
// as they went in, so a sign slip in either direction's fold shows.
TEST(FilterMath, OctahedralNormalsRoundTrip) {
    for (int i = -4; i <= 4; ++i)
        for (int j = -4; j <= 4; ++j)
            for (int k = -4; k <= 4; ++k) {
                if (i == 0 && j == 0 && k == 0)
                    continue;
                const glm::vec3 n = glm::normalize(glm::vec3(i, j, k));
                const glm::vec2 e = gpu::octahedralEncode(n);
                // The upper half inside the diamond |x| + |y| <= 1, the lower half outside it,
                // both within the unit square.
                EXPECT_LE(std::max(std::abs(e.x), std::abs(e.y)), 1.0f + 1e-6f);
                if (k > 0) {
                    EXPECT_LE(std::abs(e.x) + std::abs(e.y), 1.0f + 1e-6f);
                } else if (k < 0) {
                    EXPECT_GE(std::abs(e.x) + std::abs(e.y), 1.0f - 1e-6f);
                }
                // Either half keeps its quadrant: the fold goes to the corner beyond the edge
                // facing the point (a fold that is its own inverse the other way round would
                // still round-trip).
                if (i != 0) {
                    EXPECT_EQ(e.x > 0.0f, i > 0) << i << ", " << j << ", " << k;
                }
                if (j != 0) {
                    EXPECT_EQ(e.y > 0.0f, j > 0) << i << ", " << j << ", " << k;
                }
                const glm::vec3 back = gpu::octahedralDecode(e);
                EXPECT_NEAR(back.x, n.x, 1e-6f) << i << ", " << j << ", " << k;
                EXPECT_NEAR(back.y, n.y, 1e-6f) << i << ", " << j << ", " << k;
                EXPECT_NEAR(back.z, n.z, 1e-6f) << i << ", " << j << ", " << k;
            }
    // Stored as half floats: the direction stays within 1e-3 radians.
    const glm::vec3 n = glm::normalize(glm::vec3(0.3f, -0.8f, -0.52f));
    const glm::vec2 half = glm::unpackHalf2x16(glm::packHalf2x16(gpu::octahedralEncode(n)));
    EXPECT_GT(glm::dot(gpu::octahedralDecode(half), n), std::cos(1e-3f));
}

// vsm.filter=mip's footprint: a square footprint of 4 texels is level 2 with one tap; one 8 texels
// long and 2 wide spreads 4 taps of 2 texels (level 1) along its long axis, or, with fewer taps
// allowed, wider ones; a magnified footprint stays on level 0 with one tap, a huge one on the
// last level.
TEST(FilterMath, MipFootprintPicksTheLevelAndTapsOfThePixelsFootprint) {
    const float size = 256.0f, maxLevel = 8.0f;
    const float texel = 1.0f / size;
    glm::vec4 f = gpu::mipFootprint({4 * texel, 0}, {0, 4 * texel}, size, 16, maxLevel);
    EXPECT_NEAR(f.x, 2.0f, 1e-5f);
    EXPECT_EQ(f.y, 1.0f);
    f = gpu::mipFootprint({0, 2 * texel}, {8 * texel, 0}, size, 16, maxLevel);
    EXPECT_NEAR(f.x, 1.0f, 1e-5f);
    EXPECT_EQ(f.y, 4.0f);
    EXPECT_NEAR(f.z, 8 * texel, 1e-9f); // the axis: the longer of the two
    EXPECT_NEAR(f.w, 0.0f, 1e-9f);
    f = gpu::mipFootprint({0, 2 * texel}, {8 * texel, 0}, size, 2, maxLevel);
    EXPECT_NEAR(f.x, 2.0f, 1e-5f);
    EXPECT_EQ(f.y, 2.0f);
    // Rotated 45 degrees: lengths, not components, decide.
    const float d = 8 * texel / std::sqrt(2.0f), e = 2 * texel / std::sqrt(2.0f);
    f = gpu::mipFootprint({d, d}, {-e, e}, size, 16, maxLevel);
    EXPECT_NEAR(f.x, 1.0f, 1e-5f);
    EXPECT_EQ(f.y, 4.0f);
    EXPECT_NEAR(f.z, d, 1e-9f);
    // Half-way between levels blends them.
    f = gpu::mipFootprint({3 * texel, 0}, {0, 3 * texel}, size, 16, maxLevel);
    EXPECT_NEAR(f.x, std::log2(3.0f), 1e-5f);
    f = gpu::mipFootprint({0.3f * texel, 0}, {0, 0.1f * texel}, size, 16, maxLevel);
    EXPECT_EQ(f.x, 0.0f);
    EXPECT_EQ(f.y, 1.0f); // magnified: one bilinear tap, however thin
    f = gpu::mipFootprint({1.5f * texel, 0}, {0, 0.5f * texel}, size, 16, maxLevel);
    EXPECT_EQ(f.x, 0.0f);
    EXPECT_EQ(f.y, 3.0f);
    f = gpu::mipFootprint({4.0f, 0}, {0, 4.0f}, size, 16, maxLevel);
    EXPECT_EQ(f.x, maxLevel);
    f = gpu::mipFootprint({0, 0}, {0, 0}, size, 16, maxLevel); // no footprint: level 0, one tap
    EXPECT_EQ(f.x, 0.0f);
    EXPECT_EQ(f.y, 1.0f);
    EXPECT_EQ(gpu::mipLevelCount(1u), 1u);
    EXPECT_EQ(gpu::mipLevelCount(256u), 9u);
    EXPECT_EQ(gpu::mipLevelCount(300u), 9u);
    EXPECT_EQ(gpu::mipLevelCount(511u), 9u);
    EXPECT_EQ(gpu::mipLevelCount(512u), 10u);
    EXPECT_EQ(gpu::mipTapOffset(0, 1), 0.0f);
    EXPECT_EQ(gpu::mipTapOffset(0, 4), -0.375f);
    EXPECT_EQ(gpu::mipTapOffset(3, 4), 0.375f);
}

// The fixed-point tables: quantising and its inverse, and a backwards box read signed.
TEST(FilterMath, FixedPointTablesRoundTripTheirMoments) {
    const float scale = 100000.0f;
    for (float z : {0.0f, 0.3f, 0.77f, 1.0f}) {
        const glm::vec4 vsm =
            gpu::tableMean(MOMENTS_VSM, glm::vec4(gpu::tableMoments(MOMENTS_VSM, z, scale)), scale);
        EXPECT_NEAR(vsm.x, z - 0.5f, 1e-5f) << z;
        EXPECT_NEAR(vsm.y, (z - 0.5f) * (z - 0.5f), 1e-5f) << z;
        const glm::vec4 msm =
            gpu::tableMean(MOMENTS_MSM, glm::vec4(gpu::tableMoments(MOMENTS_MSM, z, scale)), scale);
        const float d = 2 * z - 1;
        EXPECT_NEAR(msm.x, d, 2e-5f) << z;
        EXPECT_NEAR(msm.w, d * d * d * d, 2e-5f) << z;
    }
    // Corners whose box runs backwards (a wrapped negative sum) read as negative.
    const glm::uvec4 small(5u), large(9u);
    EXPECT_EQ(gpu::boxFromCorners(glm::uvec4(0u), small, glm::uvec4(0u), large).x, 4.0f);
    EXPECT_EQ(gpu::boxFromCorners(glm::uvec4(0u), large, glm::uvec4(0u), small).x, -4.0f);
    // Sums wrap past 2^32 and still difference exactly.
    const glm::uvec4 wrapped = glm::uvec4(4294967290u) + glm::uvec4(10u);
    EXPECT_EQ(
        gpu::boxFromCorners(glm::uvec4(0u), glm::uvec4(4294967290u), glm::uvec4(0u), wrapped).x,
        10.0f);
}

// msm.precision=16: the paper's affine map takes the moments of every depth in [0, 1] into the
// unit cube (what a unorm texel holds), the stored values are whole 16-bit steps, and the inverse
// gives back the moments of d = 2z - 1 to the quantisation's precision.
TEST(FilterMath, OptimisedMomentQuantisationRoundTrips) {
    for (int k = 0; k <= 100; ++k) {
        const float z = static_cast<float>(k) / 100.0f;
        const glm::vec4 d = gpu::warpedMoments(MOMENTS_MSM, z, glm::vec2(0.0f));
        const glm::vec4 stored = gpu::msmStore16(d);
        for (int c = 0; c < 4; ++c) {
            EXPECT_GE(stored[c], 0.0f) << z;
            EXPECT_LE(stored[c], 1.0f) << z;
            const float steps = stored[c] * 65535.0f;
            EXPECT_NEAR(steps, std::round(steps), 1e-2f) << z;
        }
        const glm::vec4 back = gpu::msmLoad16(stored);
        for (int c = 0; c < 4; ++c)
            EXPECT_NEAR(back[c], d[c], 5e-4f) << "z " << z << ", moment " << c + 1;
    }
    // A mixture: the map is affine, so a filtered (averaged) texel round-trips as well.
    const glm::vec4 mix = 0.3f * gpu::warpedMoments(MOMENTS_MSM, 0.2f, glm::vec2(0.0f)) +
                          0.7f * gpu::warpedMoments(MOMENTS_MSM, 0.9f, glm::vec2(0.0f));
    const glm::vec4 back = gpu::msmLoad16(gpu::msmStore16(mix));
    for (int c = 0; c < 4; ++c)
        EXPECT_NEAR(back[c], mix[c], 5e-4f) << c;
}
