// smrt.skipLit's ceiling (smrtCeilingOf, smrtLitCeiling, shaders/include/smrt_march.h) against the
// march itself: every point of every ray a receiver traces towards the light, a given number of
// texels from the receiver in the map, must lie no farther from the light (less its slack) than the
// ceiling there. The shader and its CPU mirror share the ceiling, so only a check like this one
// (and the frame with and without the proof, tests/test_smrt.cpp) sees a mistake in it. The ceiling
// must also stay near the widest ray's own path, or it proves nothing.
#include "smrt_march.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

using namespace penumbra;

namespace {

constexpr uint32_t kMapSize = 1024;
constexpr float kSlope = 8.0f;

gpu::ShadowViewData view(float kind, float nearPlane, float farPlane, glm::vec2 worldPerUv,
                         float lightSize) {
    gpu::ShadowViewData v{};
    v.frustum = {nearPlane, farPlane, worldPerUv.x, worldPerUv.y};
    v.texel = {0.0f, kind, 0.0f, lightSize};
    return v;
}

// Each point of a ray's march, z - slack(z), against the ceiling at its distance in texels.
struct Check {
    int points = 0, above = 0;
    float tightest = 1e30f; // smallest (ceiling - z') / (p.z - ceiling) over points past 4 texels
};

void march(const gpu::ShadowViewData& v, glm::vec3 p, glm::vec3 d, Check& check) {
    const float rate = v.texel.y > 0.5f ? gpu::smrtPerspectiveRate(v, p, d, kMapSize) : 0.0f;
    const float extent = gpu::smrtMarchLength(v, p, d, 256.0f, kMapSize, rate);
    const gpu::SmrtScale scale = gpu::smrtScaleOf(v, kMapSize);
    const glm::vec2 home = gpu::smrtProject(v, scale, p) * float(kMapSize);
    for (int i = 1; i <= 200; ++i) {
        const float s = extent * float(i) / 200.0f;
        const glm::vec3 q = p + s * d;
        const float r = glm::length(gpu::smrtProject(v, scale, q) * float(kMapSize) - home);
        const float slack = gpu::smrtSlack(v, scale, q.z, kSlope);
        const float ceiling = gpu::smrtLitCeiling(gpu::smrtCeilingOf(v, p, kMapSize, kSlope), r);
        ++check.points;
        check.above += q.z - slack > ceiling;
        if (q.z - slack > ceiling && check.above < 6)
            std::printf("p %g %g %g d %g %g %g s %g ext %g r %g z' %.7g ceil %.7g slack %g\n", p.x,
                        p.y, p.z, d.x, d.y, d.z, s, extent, r, q.z - slack, ceiling, slack);
        if (r > 4.0f)
            check.tightest = std::min(check.tightest,
                                      (ceiling - (q.z - slack)) / std::max(p.z - ceiling, 1e-6f));
    }
}

// Receivers across the view (off its axis too), each with rays over the whole cone, the rim's
// densely.
Check sweep(const gpu::ShadowViewData& v, float zLow, float zHigh) {
    std::mt19937 engine(11);
    auto unit = [&] { return float(engine() >> 8) / 16777216.0f; };
    Check check;
    for (int receiver = 0; receiver < 60; ++receiver) {
        const glm::vec2 uv(0.05f + 0.9f * unit(), 0.05f + 0.9f * unit());
        const glm::vec3 p = gpu::smrtViewPoint(v, uv, zLow + (zHigh - zLow) * unit());
        for (uint32_t k = 0; k < 64; ++k)
            march(v, p, gpu::smrtRayDirection(v, p, k, 64, unit()), check);
        // The rim itself: the last stratum's jitter at its end, at every azimuth.
        // The jitter is frac(turns * 1.618034 + 0.5): 0.999 at turns = 1.499 / 1.618034, and the
        // same at turns + m / 1.618034, which turns the azimuth by m / 1.618034 (mod 1).
        for (int m = 0; m < 32; ++m) {
            const float turns = (1.499f + float(m)) / 1.618034f;
            march(v, p, gpu::smrtRayDirection(v, p, 63, 64, turns), check);
        }
    }
    return check;
}

} // namespace

TEST(SmrtLitCeiling, BoundsEveryRayPointUnderEveryLight) {
    struct Setup {
        const char* name;
        gpu::ShadowViewData view;
        float zLow, zHigh;
    };
    const Setup setups[] = {
        {"spot, radius 0.1", view(1.0f, 0.1f, 30.0f, {2.0f, 2.0f}, 0.1f), 4.0f, 20.0f},
        {"spot, radius 1.5", view(1.0f, 0.1f, 30.0f, {2.0f, 1.5f}, 1.5f), 4.0f, 20.0f},
        {"cube face, bulb 0.3", view(2.0f, 0.05f, 20.0f, {2.5f, 2.5f}, 0.3f), 0.6f, 6.0f},
        // Receivers next to the bulb, off the face's axis: some cones pass 90 degrees from it.
        {"cube face, near bulb", view(2.0f, 0.05f, 20.0f, {2.5f, 2.5f}, 0.3f), 0.2f, 0.35f},
        {"sun, 6 degrees", view(0.0f, 0.0f, 40.0f, {30.0f, 24.0f}, std::tan(0.0524f)), 5.0f, 35.0f},
        {"sun, 0.5 degrees", view(0.0f, 0.0f, 40.0f, {30.0f, 30.0f}, std::tan(0.0044f)), 5.0f,
         35.0f}};
    for (const Setup& s : setups) {
        const Check check = sweep(s.view, s.zLow, s.zHigh);
        std::printf("%-20s %d points, %d above the ceiling, tightest headroom %.3f\n", s.name,
                    check.points, check.above, check.tightest);
        EXPECT_EQ(check.above, 0) << s.name;
        // Some ray comes within a tenth of the ceiling's drop: the bound is the widest ray's own.
        EXPECT_LT(check.tightest, 0.1f) << s.name;
    }
}

// The rings reach past the march: ring k's block holds every texel within 2^k of the receiver,
// and the last ring's 2^k passes smrt.maxRadius (and a texel more, for rounding).
TEST(SmrtLitCeiling, RingsCoverTheMarch) {
    for (float maxRadius : {2.0f, 3.0f, 24.0f, 255.0f, 256.0f}) {
        const uint32_t rings = gpu::smrtBoundsRings(maxRadius);
        EXPECT_GE(float(1u << rings), maxRadius + 1.0f) << maxRadius;
        EXPECT_LT(float(1u << (rings - 1)), maxRadius + 1.0f) << maxRadius << ": one ring too many";
    }
}

// The texels (first, last) per axis that a tile of `level` covers: 2^(level+1) each, the last
// tile to the map's edge (the bounds' leftovers).
glm::ivec2 tileTexels(int tile, int level, int levelSize, int mapSize) {
    const int side = 2 << level;
    return {tile * side, tile == levelSize - 1 ? mapSize - 1 : (tile + 1) * side - 1};
}

// The bounds of a map of mapSize texels: their size (half the map's, at least 1) and their levels
// down to one tile (as smrt_bounds.comp builds them).
std::pair<int, int> boundsShape(int mapSize) {
    const int boundsSize = std::max(mapSize >> 1, 1);
    int levels = 1;
    while ((boundsSize >> levels) > 0)
        ++levels;
    return {boundsSize, levels};
}

// On maps whose bounds have odd-sized levels (1000: 500, 250, 125, 62, 31, 15, 7, 3, 1) and on a
// power of two: ring k's 2x2 block holds every texel within 2^k of the receiver, and its tiles'
// children (smrtLastChild) hold exactly the block's texels.
TEST(SmrtLitCeiling, BlocksAndTheirChildrenHoldTheRing) {
    std::mt19937 engine(3);
    for (int mapSize : {1000, 1024, 77}) {
        const auto [boundsSize, levels] = boundsShape(mapSize);
        std::uniform_real_distribution<float> position(0.0f, float(mapSize) - 1e-3f);
        for (int trial = 0; trial < 400; ++trial) {
            const glm::vec2 at(position(engine), position(engine));
            for (uint32_t k = 1; k <= 9; ++k) {
                const int level = std::min(int(k), levels - 1);
                const int levelSize = std::max(boundsSize >> level, 1);
                const glm::ivec4 block = gpu::smrtBoundsBlock(at, uint32_t(level), levelSize);
                // A tile's distance from the receiver: to the nearest point of its texels.
                for (const glm::ivec2 tile :
                     {glm::ivec2(block.x, block.y), glm::ivec2(block.z, block.w)}) {
                    const glm::ivec2 xs = tileTexels(tile.x, level, levelSize, mapSize);
                    const glm::ivec2 ys = tileTexels(tile.y, level, levelSize, mapSize);
                    const float dx = std::max({float(xs.x) - at.x, at.x - float(xs.y + 1), 0.0f});
                    const float dy = std::max({float(ys.x) - at.y, at.y - float(ys.y + 1), 0.0f});
                    EXPECT_NEAR(
                        gpu::smrtTileDistance(at, tile, level, levelSize, uint32_t(mapSize)),
                        std::hypot(dx, dy), 1e-3f);
                }
                for (int axis = 0; axis < 2; ++axis) {
                    const int first = axis == 0 ? block.x : block.y;
                    const int last = axis == 0 ? block.z : block.w;
                    const int low = tileTexels(first, level, levelSize, mapSize).x;
                    const int high = tileTexels(last, level, levelSize, mapSize).y;
                    const int home = int(std::floor(at[axis]));
                    const int reach = 1 << k;
                    EXPECT_LE(low, std::max(home - reach, 0)) << mapSize << " ring " << k;
                    EXPECT_GE(high, std::min(home + reach, mapSize - 1))
                        << mapSize << " ring " << k;
                    if (level == 0)
                        continue;
                    const int childSize = std::max(boundsSize >> (level - 1), 1);
                    const int lastChild = gpu::smrtLastChild(last, levelSize, childSize);
                    EXPECT_EQ(tileTexels(2 * first, level - 1, childSize, mapSize).x, low);
                    EXPECT_EQ(tileTexels(lastChild, level - 1, childSize, mapSize).y, high)
                        << mapSize << " ring " << k << ": the children's last texel";
                }
            }
        }
    }
}

// What the proof's success says of each texel a march can read (within smrt.maxRadius and a
// texel of the receiver, distance r to its nearest point): some ring k whose inner radius is no
// more than r holds it in its block, and either its children cannot take over (level 0) or the
// child holding it is checked, not passed over as the inner ring's (smrtInnerBlock). Its block's
// ceiling and its child's are then both at distances no more than r: at least as strict as the
// texel's own. Or it is one of p's 3x3 texels (ring 0).
TEST(SmrtLitCeiling, EveryTexelTheMarchReadsIsCheckedAtItsDistance) {
    std::mt19937 engine(5);
    for (int mapSize : {1000, 1024, 77}) {
        const auto [boundsSize, levels] = boundsShape(mapSize);
        std::uniform_real_distribution<float> position(0.0f, float(mapSize) - 1e-3f);
        for (float maxRadius : {3.0f, 24.0f, 256.0f}) {
            const uint32_t rings = gpu::smrtBoundsRings(maxRadius);
            size_t skipped = 0;
            for (int trial = 0; trial < 12; ++trial) {
                const glm::vec2 at(position(engine), position(engine));
                const glm::ivec2 home(glm::floor(at));
                const int reach = int(maxRadius) + 2;
                for (int ty = std::max(home.y - reach, 0);
                     ty <= std::min(home.y + reach, mapSize - 1); ++ty)
                    for (int tx = std::max(home.x - reach, 0);
                         tx <= std::min(home.x + reach, mapSize - 1); ++tx) {
                        const float dx = std::max({float(tx) - at.x, at.x - float(tx + 1), 0.0f});
                        const float dy = std::max({float(ty) - at.y, at.y - float(ty + 1), 0.0f});
                        const float r = std::hypot(dx, dy);
                        if (r > maxRadius + 1.0f)
                            continue;
                        bool checked = std::abs(tx - home.x) <= 1 && std::abs(ty - home.y) <= 1;
                        // Outermost first, as the shader: the rings that pass it over, then one
                        // that checks it.
                        for (uint32_t k = rings; k >= 1 && !checked; --k) {
                            const int level = std::min(int(k), levels - 1);
                            const int levelSize = std::max(boundsSize >> level, 1);
                            const glm::ivec4 block =
                                gpu::smrtBoundsBlock(at, uint32_t(level), levelSize);
                            const int side = 2 << level;
                            const glm::ivec2 tile(std::min(tx / side, levelSize - 1),
                                                  std::min(ty / side, levelSize - 1));
                            if (float(1u << (k - 1)) > r || !gpu::smrtInBlock(tile, block))
                                continue;
                            if (level == 0) {
                                checked = true;
                                continue;
                            }
                            const int childSize = std::max(boundsSize >> (level - 1), 1);
                            const int childSide = 1 << level;
                            const glm::ivec2 child(std::min(tx / childSide, childSize - 1),
                                                   std::min(ty / childSide, childSize - 1));
                            const bool passedOver = gpu::smrtInBlock(
                                child, gpu::smrtInnerBlock(at, k, level, boundsSize));
                            skipped += passedOver;
                            checked = !passedOver;
                        }
                        ASSERT_TRUE(checked)
                            << mapSize << " reach " << maxRadius << " at (" << at.x << ", " << at.y
                            << "): texel (" << tx << ", " << ty << ") at " << r;
                    }
            }
            // The inner rings' blocks are passed over, or the check above proves nothing new.
            if (maxRadius > 10.0f) {
                EXPECT_GT(skipped, 0u) << mapSize << " reach " << maxRadius;
            }
        }
    }
}

// The proof compares stored depths with the ceiling's depth: smrtDepthOf inverts viewDistance
// under both projections and keeps their order.
TEST(SmrtLitCeiling, DepthOfInvertsViewDistance) {
    for (const gpu::ShadowViewData& v : {view(1.0f, 0.1f, 30.0f, {2.0f, 2.0f}, 0.1f),
                                         view(0.0f, -5.0f, 40.0f, {30.0f, 30.0f}, 0.01f)}) {
        float last = -1e30f;
        for (int i = 0; i <= 100; ++i) {
            const float z = v.frustum.x + (v.frustum.y - v.frustum.x) * float(i) / 100.0f;
            const float depth = gpu::smrtDepthOf(v, z);
            // A float depth's step stands for z^2 / near (perspective) or far - near.
            const float step = v.texel.y > 0.5f ? z * z / v.frustum.x : v.frustum.y - v.frustum.x;
            EXPECT_NEAR(gpu::viewDistance(v, depth), z, 1e-6f * std::abs(z) + 4e-7f * step);
            EXPECT_GT(depth, last);
            last = depth;
        }
    }
}

// smrt.gapSamples' check of a long step: every texel the march may read between the step's ends
// (points along it, their texels clamped to the map as smrtStored clamps them) lies in the tiles
// smrtStepTiles names, at most 2x2 of the finest level that holds them, on odd-sized and
// power-of-two maps, with ends off the map too.
TEST(SmrtStepCheck, TilesHoldEveryTexelTheStepReads) {
    std::mt19937 engine(5);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int mapSize : {1000, 1024, 77}) {
        const auto [boundsSize, levels] = boundsShape(mapSize);
        for (int trial = 0; trial < 2000; ++trial) {
            gpu::SmrtPoint a{}, b{};
            a.uv = {unit(engine) * 1.1f - 0.05f, unit(engine) * 1.1f - 0.05f};
            // Steps of a texel to most of the map, in any direction.
            const float length = std::pow(2.0f, 10.0f * unit(engine)) / float(mapSize);
            const float angle = 6.2831853f * unit(engine);
            b.uv = a.uv + length * glm::vec2(std::cos(angle), std::sin(angle));
            const glm::ivec4 box = gpu::smrtStepTexelBox(a, b, uint32_t(mapSize));
            const int level = gpu::smrtStepLevel(box, levels);
            const int levelSize = std::max(boundsSize >> level, 1);
            const glm::ivec4 tiles = gpu::smrtStepTiles(box, level, levelSize);
            EXPECT_LE(tiles.z - tiles.x, 1) << mapSize << " level " << level;
            EXPECT_LE(tiles.w - tiles.y, 1) << mapSize << " level " << level;
            const int widest = std::max(box.z - box.x, box.w - box.y) + 1;
            if (level > 0) { // the finest level that holds the box
                EXPECT_LT(2 << (level - 1), widest) << mapSize << " level " << level;
            }
            for (int i = 0; i <= 64; ++i) {
                const glm::vec2 uv = glm::mix(a.uv, b.uv, float(i) / 64.0f);
                const glm::ivec2 texel =
                    glm::clamp(glm::ivec2(glm::floor(uv * float(mapSize))), 0, mapSize - 1);
                for (int axis = 0; axis < 2; ++axis) {
                    const int first = axis == 0 ? tiles.x : tiles.y;
                    const int last = axis == 0 ? tiles.z : tiles.w;
                    ASSERT_GE(texel[axis], tileTexels(first, level, levelSize, mapSize).x)
                        << mapSize << " level " << level << " axis " << axis;
                    ASSERT_LE(texel[axis], tileTexels(last, level, levelSize, mapSize).y)
                        << mapSize << " level " << level << " axis " << axis;
                }
            }
        }
    }
}

// A tile storing at least smrtStepCeiling's depth holds no point of the step behind it: every
// point between the ends lies no farther than the ceiling's distance plus its own slack (the
// march's test), after the rounding of viewDistance, under both projections and on a cube face;
// and the ceiling stays within 2e-5 of the larger of the ends' distance less slack.
TEST(SmrtStepCheck, CeilingHoldsEveryPointOfTheStep) {
    std::mt19937 engine(9);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (const gpu::ShadowViewData& v :
         {view(1.0f, 0.1f, 30.0f, {2.0f, 2.0f}, 0.1f), view(2.0f, 0.05f, 12.0f, {2.0f, 2.0f}, 0.3f),
          view(0.0f, -5.0f, 40.0f, {30.0f, 30.0f}, 0.01f)}) {
        auto pointAt = [&](float z) {
            gpu::SmrtPoint q{};
            q.z = z;
            q.slack = gpu::smrtSlack(v, gpu::smrtScaleOf(v, kMapSize), z, kSlope);
            return q;
        };
        const float low = std::max(v.frustum.x, 0.0f) + 0.01f, high = v.frustum.y;
        for (int trial = 0; trial < 2000; ++trial) {
            const gpu::SmrtPoint a = pointAt(low + (high - low) * unit(engine));
            const gpu::SmrtPoint b = pointAt(low + (high - low) * unit(engine));
            const float ceiling = gpu::viewDistance(v, gpu::smrtStepCeiling(v, a, b));
            for (int i = 0; i <= 32; ++i) {
                const gpu::SmrtPoint q = pointAt(a.z + (b.z - a.z) * float(i) / 32.0f);
                ASSERT_LE(q.z - q.slack, ceiling) << a.z << " " << b.z << " at " << i;
            }
            const float z = std::max(a.z - a.slack, b.z - b.slack);
            const float step = v.texel.y > 0.5f ? z * z / v.frustum.x : v.frustum.y - v.frustum.x;
            EXPECT_LE(ceiling, z + 2e-5f * std::abs(z) + 1e-6f * step) << a.z << " " << b.z;
        }
    }
}

// smrt.hidden's candidate (smrtNoteHidden): the first place a ray comes out in front after a
// stretch behind, with that stretch. A later one does not replace it (the slat a ray rose under
// stays the one checked when it passes another silhouette after it), and a point that is not
// such a place (the ray in front before it, or still behind) is never one.
TEST(SmrtHidden, TheFirstExitAfterAStretchBehindIsTheCandidate) {
    gpu::SmrtHiddenCandidate c = gpu::smrtNoHiddenCandidate();
    gpu::SmrtHidden h = gpu::smrtHiddenFrom(false); // the receiver in front
    EXPECT_FALSE(c.found);
    // In front, then in front again: no stretch behind, no candidate.
    gpu::smrtNoteHidden(c, h, 0.1f, false);
    EXPECT_FALSE(c.found);
    // Behind from s = 0.2 to 0.3, out in front at 0.4: the candidate, with its stretch.
    gpu::smrtTrackHidden(h, 0.2f, true);
    gpu::smrtTrackHidden(h, 0.3f, true);
    gpu::smrtNoteHidden(c, h, 0.3f, true); // still behind: not an exit
    EXPECT_FALSE(c.found);
    gpu::smrtNoteHidden(c, h, 0.4f, false);
    ASSERT_TRUE(c.found);
    EXPECT_EQ(c.front, 0.4f);
    EXPECT_EQ(c.first, 0.2f);
    // A second stretch and exit later: the first stays.
    gpu::smrtTrackHidden(h, 0.4f, false);
    gpu::smrtTrackHidden(h, 0.6f, true);
    gpu::smrtNoteHidden(c, h, 0.7f, false);
    EXPECT_EQ(c.front, 0.4f);
    EXPECT_EQ(c.first, 0.2f);
    // A receiver already behind: its stretch starts at the receiver, s = 0.
    gpu::SmrtHiddenCandidate fromReceiver = gpu::smrtNoHiddenCandidate();
    gpu::SmrtHidden behind = gpu::smrtHiddenFrom(true);
    gpu::smrtTrackHidden(behind, 0.5f, true);
    gpu::smrtNoteHidden(fromReceiver, behind, 0.6f, false);
    ASSERT_TRUE(fromReceiver.found);
    EXPECT_EQ(fromReceiver.first, 0.0f);
    EXPECT_EQ(fromReceiver.front, 0.6f);
}

// The march's samples (smrtSampleDistance, with smrtMarch's share of a sample): they start at the
// receiver, grow with i, and the last, jittered by a whole step, reaches the march's far end, in
// distance (spots and suns) or in texels (cube faces).
TEST(SmrtMarch, SamplesSpanTheMarch) {
    for (const float kind : {0.0f, 1.0f, 2.0f}) {
        const gpu::ShadowViewData v = view(kind, kind > 0.5f ? 0.1f : -5.0f, 30.0f,
                                           kind > 0.5f ? glm::vec2(2.0f) : glm::vec2(30.0f), 0.3f);
        const glm::vec3 p{0.7f, -1.1f, 9.0f};
        const glm::vec3 d = glm::normalize(glm::vec3(0.2f, 0.1f, -1.0f));
        for (const uint32_t n : {2u, 13u, 32u}) {
            const gpu::SmrtMarch march = gpu::smrtMarch(v, p, d, 256.0f, kMapSize, n);
            ASSERT_GT(march.extent, 0.0f);
            EXPECT_EQ(gpu::smrtSampleDistance(march, p, d, 0, 0.0f), 0.0f);
            EXPECT_NEAR(gpu::smrtSampleDistance(march, p, d, n - 1, 1.0f), march.extent,
                        1e-5f * march.extent)
                << kind << " " << n;
            float previous = -1.0f;
            for (uint32_t i = 0; i < n; ++i) {
                const float s = gpu::smrtSampleDistance(march, p, d, i, 0.5f);
                EXPECT_GT(s, previous) << kind << " " << n << " " << i;
                EXPECT_LT(s, march.extent) << kind << " " << n << " " << i;
                previous = s;
            }
        }
    }
}

// A mark (SmrtMark) stands for its read: the point made again from its distance along the ray
// and its `behind` is the read's, bit for bit, so the shader's march decides as the mirror's.
TEST(SmrtMark, MakesTheReadsPointAgain) {
    for (const float kind : {0.0f, 1.0f, 2.0f}) {
        gpu::ShadowViewData v{};
        v.frustum = {0.1f, 30.0f, kind > 0.5f ? 2.0f : 12.0f, kind > 0.5f ? 2.0f : 12.0f};
        v.texel = {0.0f, kind, 0.0f, 0.3f};
        const glm::vec3 p{0.7f, -1.1f, 9.0f};
        const glm::vec3 d = glm::normalize(glm::vec3(0.2f, 0.1f, -1.0f));
        for (const float s : {0.0f, 0.37f, 2.5f, 7.9f}) {
            const gpu::SmrtScale scale = gpu::smrtScaleOf(v, 1024);
            gpu::SmrtPoint read = gpu::smrtPointAt(v, scale, p, d, s);
            gpu::smrtSetStored(read, v, scale, read.z - 0.013f * s, 8.0f);
            const gpu::SmrtPoint again =
                gpu::smrtMarkPoint(v, scale, p, d, gpu::smrtMarkOf(read), 8.0f);
            EXPECT_EQ(again.s, read.s);
            EXPECT_EQ(again.z, read.z);
            EXPECT_EQ(again.uv, read.uv);
            EXPECT_EQ(again.behind, read.behind);
            EXPECT_EQ(again.slack, read.slack);
            EXPECT_GT(read.slack, 0.0f);
        }
    }
}
