// The CPU side of the `sdf` technique: the field's grid, which surfaces are closed, the column
// crossings that sign the field, the brick lists, and the tracer's maths (sdf_math.h) against
// closed forms.
#include "bias.h"
#include "penumbra/error.h"
#include "reference/distance_field.h"
#include "scene/mesh_builder.h"
#include "sdf_math.h"
#include "shadows/sdf_field.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

using namespace penumbra;
using namespace penumbra::shadows;

namespace {

Bounds boundsOf(glm::vec3 lo, glm::vec3 hi) {
    Bounds b;
    b.grow(lo);
    b.grow(hi);
    return b;
}

// The crossings of every triangle of `scene` on the column through (x, y), below height z.
int windingBelow(const Scene& scene, glm::vec2 column, float z, int* total = nullptr) {
    int below = 0, all = 0;
    for (size_t t = 0; t < scene.triangleCount(); ++t) {
        const glm::vec3 a = scene.vertices[scene.indices[3 * t]].position;
        const glm::vec3 b = scene.vertices[scene.indices[3 * t + 1]].position;
        const glm::vec3 c = scene.vertices[scene.indices[3 * t + 2]].position;
        float hit = 0.0f;
        const int crossing = gpu::columnCrossing(column, a, b, c, hit);
        all += crossing;
        if (crossing != 0 && hit < z)
            below += crossing;
    }
    if (total)
        *total = all;
    return below;
}

} // namespace

TEST(SdfField, LayoutCoversTheBoundsWithCubicVoxelsInWholeBricks) {
    const Bounds b = boundsOf({-20.0f, 0.0f, -20.0f}, {20.0f, 2.1f, 20.0f});
    const FieldLayout l = fieldLayout(b, 128);
    EXPECT_FLOAT_EQ(l.voxel, 40.0f / 128.0f);
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_EQ(l.size[axis] % FIELD_BRICK, 0u) << axis;
        // kFieldPadding voxels of free space on each side, at least.
        EXPECT_LE(l.origin[axis], b.min[axis] - kFieldPadding * l.voxel + 1e-4f) << axis;
        EXPECT_GE(l.origin[axis] + static_cast<float>(l.size[axis]) * l.voxel,
                  b.max[axis] + kFieldPadding * l.voxel - 1e-4f)
            << axis;
    }
    EXPECT_EQ(l.size.x, 132u); // 128 + 2 x 2, a whole number of bricks
    EXPECT_EQ(l.size.y, 12u);  // ceil(2.1 / 0.3125) = 7, + 4 = 11, rounded up to 12
    // The voxel centres are where the tracer's trilinear reads put them.
    EXPECT_EQ(l.voxelCentre({0, 0, 0}), l.origin + 0.5f * l.voxel);
    // A flat scene still gets a box around its plane.
    const FieldLayout flat = fieldLayout(boundsOf({0, 0, 0}, {10, 0, 10}), 64);
    EXPECT_EQ(flat.size.y, 8u);
    EXPECT_LT(flat.origin.y, -2.0f * flat.voxel + 1e-6f);
    // Past 2^27 voxels: refused, naming the parameter.
    EXPECT_THROW(fieldLayout(boundsOf({0, 0, 0}, {1, 1, 1}), 1024), InputError);
    EXPECT_NO_THROW(fieldLayout(boundsOf({0, 0, 0}, {1, 1, 1}), 500));
}

// sdf.resolution 0: the finest resolution whose bounds hold the voxel budget, between its bounds.
TEST(SdfField, TheAutomaticResolutionSpendsTheVoxelBudgetOnTheScenesShape) {
    const auto innerVoxels = [](const Bounds& b, uint32_t n) {
        const glm::vec3 e = b.extent();
        const float longest = std::max({e.x, e.y, e.z}), voxel = longest / float(n);
        double count = 1.0;
        for (int axis = 0; axis < 3; ++axis)
            count *= std::max(std::ceil(double(e[axis]) / double(voxel)), 1.0);
        return count;
    };
    // A cube: the budget's cube root is under the floor, so the floor (the former default).
    const Bounds cube = boundsOf({-1, -1, -1}, {1, 1, 1});
    EXPECT_EQ(fieldResolution(cube, 0), kAutoFieldResolutionMin);
    // A wide ground with low casters (60 x 2 x 60, the bulbs' scene): finer, the finest within
    // the budget, so 16 more voxels would pass it.
    const Bounds flat = boundsOf({-30, 0, -30}, {30, 2, 30});
    const uint32_t n = fieldResolution(flat, 0);
    EXPECT_GT(n, 600u);
    EXPECT_LT(n, kAutoFieldResolutionMax);
    EXPECT_LE(innerVoxels(flat, n), double(kAutoFieldVoxels));
    EXPECT_GT(innerVoxels(flat, n + 16), double(kAutoFieldVoxels));
    EXPECT_FLOAT_EQ(fieldLayout(flat, 0).voxel, 60.0f / float(n));
    // A plane alone: the ceiling.
    EXPECT_EQ(fieldResolution(boundsOf({0, 0, 0}, {10, 0, 10}), 0), kAutoFieldResolutionMax);
    // A value asked for is kept; 1 to 15 are refused, naming the parameter.
    EXPECT_EQ(fieldResolution(flat, 128), 128u);
    EXPECT_EQ(fieldResolution(flat, 16), 16u);
    EXPECT_THROW(fieldResolution(flat, 15), InputError);
    EXPECT_THROW(fieldLayout(flat, 1), InputError);
}

TEST(SdfField, ClosedSurfacesAreFoundByTheirEdges) {
    Scene scene;
    MeshBuilder mb(scene);
    const uint32_t grey = mb.material("grey", glm::vec3(0.5f));
    mb.sphere({0, 1, 0}, 0.5f, grey, 16, 8);
    const size_t sphereEnd = scene.triangleCount();
    mb.quad({-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, {-5, 0, -5}, grey);
    const size_t quadEnd = scene.triangleCount();
    mb.box(glm::translate(glm::mat4(1.0f), glm::vec3(3, 1, 0)), grey);
    const size_t boxEnd = scene.triangleCount();
    // The same box inside out.
    mb.box(glm::translate(glm::mat4(1.0f), glm::vec3(-3, 1, 0)), grey);
    for (size_t t = boxEnd; t < scene.triangleCount(); ++t)
        std::swap(scene.indices[3 * t + 1], scene.indices[3 * t + 2]);
    const size_t flippedEnd = scene.triangleCount();
    // A box with one face missing.
    mb.box(glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 3)), grey);
    scene.indices.resize(scene.indices.size() - 6);
    dropInvalidTriangles(scene);

    const Closure c = closedSurfaces(scene);
    ASSERT_EQ(c.closed.size(), scene.triangleCount());
    for (size_t t = 0; t < scene.triangleCount(); ++t) {
        const bool closed = t < sphereEnd || (t >= quadEnd && t < flippedEnd);
        EXPECT_EQ(c.closed[t], closed) << t;
        EXPECT_EQ(c.flipped[t], t >= boxEnd && t < flippedEnd) << t;
    }
    // Open by an edge: the quad's 2 and the open box's 10, every one of them (the box's far
    // faces too, which touch no open edge).
    EXPECT_EQ(c.openEdged, 2u + 10u);

    // An alpha-tested material is never closed: its holes are not in the triangles.
    Scene masked;
    MeshBuilder mm(masked);
    const uint32_t leaf = mm.material("leaf", glm::vec3(0.3f, 0.6f, 0.2f));
    masked.materials[leaf].alphaMode = AlphaMode::Mask;
    mm.box(glm::mat4(1.0f), leaf);
    for (bool closed : closedSurfaces(masked).closed)
        EXPECT_FALSE(closed);
    EXPECT_EQ(closedSurfaces(masked).openEdged, 0u) << "alpha-tested: meant thin, not open";
    // With one triangle of its 12 gone, a masked box counts as open-edged only when opaque.
    masked.indices.resize(masked.indices.size() - 3);
    EXPECT_EQ(closedSurfaces(masked).openEdged, 0u);
    masked.materials[leaf].alphaMode = AlphaMode::Opaque;
    EXPECT_EQ(closedSurfaces(masked).openEdged, 11u);
}

// A column meets a closed mesh's surface an even number of times, entering +1 and leaving -1,
// even where it runs exactly through the mesh's vertices and edges (the edge rule gives a shared
// edge to one triangle only): winding 1 inside, 0 outside.
TEST(SdfField, ColumnsCrossClosedMeshesOnceAtEveryEntryAndExit) {
    Scene scene;
    MeshBuilder mb(scene);
    const uint32_t grey = mb.material("grey", glm::vec3(0.5f));
    mb.box(glm::rotate(glm::mat4(1.0f), 0.0f, glm::vec3(0, 1, 0)), grey); // the unit cube
    std::vector<glm::vec2> columns;
    for (float x : {-0.5f, -0.25f, 0.0f, 0.25f, 0.5f})
        for (float y : {-0.5f, -0.25f, 0.0f, 0.25f, 0.5f})
            columns.push_back({x, y});
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(-0.7f, 0.7f);
    for (int i = 0; i < 200; ++i)
        columns.push_back({unit(rng), unit(rng)});
    for (const glm::vec2 column : columns) {
        int total = 0;
        const int inside = windingBelow(scene, column, 0.0f, &total);
        EXPECT_EQ(total, 0) << column.x << ", " << column.y;
        const bool within = std::abs(column.x) < 0.5f && std::abs(column.y) < 0.5f;
        if (within || std::max(std::abs(column.x), std::abs(column.y)) > 0.5f) {
            EXPECT_EQ(inside, within ? 1 : 0) << column.x << ", " << column.y;
        }
    }
    // A sphere tilted so that columns meet it anywhere, its own vertices included.
    Scene ball;
    MeshBuilder(ball).sphere({0.1f, 0.2f, 0.0f}, 1.0f, 0, 24, 12);
    const glm::mat4 tilt = glm::rotate(glm::mat4(1.0f), 0.4f, glm::vec3(1, 0.5f, 0));
    for (Vertex& v : ball.vertices) {
        v.position = glm::vec3(tilt * glm::vec4(v.position, 1.0f));
        v.normal = glm::vec3(tilt * glm::vec4(v.normal, 0.0f));
    }
    dropInvalidTriangles(ball);
    std::vector<glm::vec2> ballColumns;
    // Not its poles nor its seam: MeshBuilder computes the pole and seam vertices of each slice
    // apart, a few 1e-8 from each other, which leaves hairline cracks a column exactly through
    // them may pass (or cross twice).
    for (size_t i = 0; i < ball.vertices.size(); i += 7)
        if (i % 25 != 0 && i % 25 != 24 && i >= 25 && i + 25 < ball.vertices.size())
            ballColumns.push_back(glm::vec2(ball.vertices[i].position));
    for (int i = 0; i < 300; ++i)
        ballColumns.push_back({1.3f * unit(rng), 1.3f * unit(rng)});
    for (const glm::vec2 column : ballColumns) {
        int total = 0;
        (void)windingBelow(ball, column, 0.0f, &total);
        EXPECT_EQ(total, 0) << column.x << ", " << column.y;
    }
    // The ball's centre column: inside at its centre, outside above and below it.
    const glm::vec3 centre = glm::vec3(glm::rotate(glm::mat4(1.0f), 0.4f, glm::vec3(1, 0.5f, 0)) *
                                       glm::vec4(0.1f, 0.2f, 0.0f, 1.0f));
    EXPECT_EQ(windingBelow(ball, glm::vec2(centre), centre.z), 1);
    EXPECT_EQ(windingBelow(ball, glm::vec2(centre), centre.z + 1.5f), 0);
    EXPECT_EQ(windingBelow(ball, glm::vec2(centre), centre.z - 1.5f), 0);
}

// Every triangle within a brick of a brick's box is in its list: checked at points sampled in
// the brick, each against every triangle's exact distance.
TEST(SdfField, BrickListsHoldEveryTriangleNearTheirBrick) {
    Scene scene;
    MeshBuilder mb(scene);
    const uint32_t grey = mb.material("grey", glm::vec3(0.5f));
    mb.sphere({0, 1, 0}, 0.7f, grey, 12, 6);
    mb.quad({-3, 0, 3}, {3, 0, 3}, {3, 0, -3}, {-3, 0, -3}, grey);
    mb.beam({-2, 0.5f, -2}, {2, 2.0f, 1}, 0.1f, grey);
    dropInvalidTriangles(scene);
    const FieldLayout layout = fieldLayout(scene.bounds(), 48);
    const FieldGeometry g = fieldGeometry(scene, layout, 0.75f * layout.voxel);
    ASSERT_EQ(g.triangles.size(), scene.triangleCount());
    EXPECT_EQ(g.closedTriangles + g.openTriangles, g.triangles.size());
    EXPECT_EQ(g.openTriangles, 2u); // the quad
    const glm::uvec3 bricks = layout.bricks();
    ASSERT_EQ(g.brickStarts.size(), size_t{bricks.x} * bricks.y * bricks.z + 1);
    const float brickSide = FIELD_BRICK * layout.voxel;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    size_t near = 0;
    for (int i = 0; i < 3000; ++i) {
        const glm::uvec3 brick(static_cast<uint32_t>(unit(rng) * float(bricks.x)) % bricks.x,
                               static_cast<uint32_t>(unit(rng) * float(bricks.y)) % bricks.y,
                               static_cast<uint32_t>(unit(rng) * float(bricks.z)) % bricks.z);
        const glm::vec3 p =
            layout.origin +
            (glm::vec3(brick) + glm::vec3(unit(rng), unit(rng), unit(rng))) * brickSide;
        const size_t b = (size_t{brick.z} * bricks.y + brick.y) * bricks.x + brick.x;
        const auto first = g.brickList.begin() + g.brickStarts[b];
        const auto last = g.brickList.begin() + g.brickStarts[b + 1];
        for (uint32_t t = 0; t < g.triangles.size(); ++t) {
            const gpu::FieldTriangle& tri = g.triangles[t];
            const float d = glm::distance(
                p, gpu::nearestOnTriangle(p, glm::vec3(tri.a), glm::vec3(tri.b), glm::vec3(tri.c)));
            if (d > brickSide)
                continue;
            ++near;
            EXPECT_NE(std::find(first, last, t), last) << "triangle " << t << " brick " << b;
        }
    }
    EXPECT_GT(near, 1000u);
}

// Two sphere-tracing samples past a point obstacle: the spheres of their free distances meet at
// the obstacle itself, so the closest approach is exactly its distance from the ray.
TEST(SdfMath, ClosestApproachFindsAPointObstacleBetweenTwoSamples) {
    const glm::vec2 obstacle(2.0f, 0.3f); // at 2 along the ray, 0.3 off it
    auto freeDistance = [&](float t) { return glm::length(glm::vec2(t, 0.0f) - obstacle); };
    for (float t0 : {0.5f, 1.0f, 1.5f}) {
        const float h0 = freeDistance(t0);
        const float t1 = t0 + h0;
        const glm::vec2 miss = gpu::closestApproach(freeDistance(t1), h0, h0, t1);
        if (t1 < obstacle.x + 0.3f) { // the obstacle lies between the samples' spheres' circle
            EXPECT_NEAR(miss.x, obstacle.y, 1e-5f) << t0;
            EXPECT_NEAR(miss.y, obstacle.x, 1e-5f) << t0;
        }
        EXPECT_LE(miss.x, freeDistance(t1) + 1e-6f);
    }
    // A step shorter than the free distance (as the tracer's minimum step inside solids is
    // longer): the spheres still meet at the obstacle when the two samples straddle it.
    const float t0 = 1.9f, h0 = freeDistance(t0), t2 = t0 + 0.6f * h0;
    ASSERT_GT(t2, obstacle.x);
    const glm::vec2 shorter = gpu::closestApproach(freeDistance(t2), h0, 0.6f * h0, t2);
    EXPECT_NEAR(shorter.x, obstacle.y, 1e-5f);
    EXPECT_NEAR(shorter.y, obstacle.x, 1e-5f);
    // No circle: the first step, a sample inside, spheres that do not meet.
    EXPECT_EQ(gpu::closestApproach(0.5f, -1.0f, 0.0f, 1.0f), glm::vec2(0.5f, 1.0f));
    EXPECT_EQ(gpu::closestApproach(-0.1f, 0.2f, 0.2f, 1.0f), glm::vec2(-0.1f, 1.0f));
    EXPECT_EQ(gpu::closestApproach(1.0f, 0.1f, 0.1f, 1.0f), glm::vec2(1.0f, 1.0f));
}

TEST(SdfMath, ConeEdgeAndDiscFractionMeetTheirClosedForms) {
    // A miss of d at t is asin(d / t) from the cone's axis, in light radii.
    const float sinRadius = std::sin(0.05f);
    EXPECT_NEAR(gpu::coneEdge(0.05f * 2.0f, 2.0f, sinRadius, 0.0f), std::asin(0.05f) / 0.05f,
                1e-5f);
    EXPECT_NEAR(gpu::coneEdge(-0.02f, 1.0f, sinRadius, 0.0f), std::asin(-0.02f) / 0.05f, 1e-5f);
    EXPECT_FLOAT_EQ(gpu::coneEdge(0.3f, 2.0f, sinRadius, 8.0f), 8.0f * 0.3f / 2.0f); // Quilez's k
    EXPECT_EQ(gpu::coneEdge(1e-3f, 5.0f, 0.0f, 0.0f), 1.0f); // a point light: open or not
    EXPECT_EQ(gpu::coneEdge(-1e-3f, 5.0f, 0.0f, 0.0f), -1.0f);
    // The part of a unit disc beyond a chord at x from its centre, against a numeric integral.
    for (float x : {-1.0f, -0.6f, -0.1f, 0.0f, 0.35f, 0.9f, 1.0f}) {
        double open = 0.0;
        const int n = 20000;
        for (int i = 0; i < n; ++i) { // strips across the disc, uncovered below the chord at x
            const double u = -1.0 + (i + 0.5) * 2.0 / n;
            if (u < x)
                open += 2.0 * std::sqrt(1.0 - u * u) * 2.0 / n;
        }
        EXPECT_NEAR(gpu::discFraction(x), open / std::numbers::pi, 1e-4) << x;
    }
    EXPECT_EQ(gpu::discFraction(-3.0f), 0.0f);
    EXPECT_EQ(gpu::discFraction(3.0f), 1.0f);
}

TEST(SdfMath, TracesStartOnTheReceiversOwnRay) {
    const glm::vec3 world(1.0f, 0.0f, 2.0f), face(0.0f, 1.0f, 0.0f);
    for (float elevation : {90.0f, 30.0f, 10.0f, 2.0f}) {
        const float e = glm::radians(elevation);
        const glm::vec3 toLight(std::cos(e), std::sin(e), 0.0f);
        float along = 0.0f;
        const glm::vec3 start = gpu::traceStart(world, face, toLight, 0.1f, along);
        EXPECT_NEAR(start.y, 0.1f, 1e-5f) << elevation; // the height asked for, always
        if (std::sin(e) >= 0.25f) {                     // on the ray itself
            EXPECT_NEAR(glm::distance(start, world + along * toLight), 0.0f, 1e-5f) << elevation;
            EXPECT_NEAR(along, 0.1f / std::sin(e), 1e-5f) << elevation;
        } else { // grazing: at most 4 x the height along it, the rest along the normal
            EXPECT_NEAR(along, 0.4f, 1e-6f) << elevation;
        }
    }
    // A light behind the face: the start is on the light's side of it.
    float along = 0.0f;
    const glm::vec3 start =
        gpu::traceStart(world, face, glm::normalize(glm::vec3(0.3f, -1.0f, 0.0f)), 0.1f, along);
    EXPECT_NEAR(start.y, -0.1f, 1e-5f);
}

// Inside a solid: the cone's radius is where coneEdge reaches 1 (t tan R, or t / k); the nearest
// way out of the solid among the probes sets the edge, by the linear zero crossing between the
// sample and the probe; -1 when every probe is inside.
TEST(SdfMath, AcrossEdgeFindsTheNearestWayOut) {
    EXPECT_NEAR(gpu::coneRadius(2.0f, 0.6f, 0.0f), 1.5f, 1e-6f); // tan R = 0.75
    EXPECT_NEAR(gpu::coneRadius(2.0f, 0.0f, 4.0f), 0.5f, 1e-6f);
    EXPECT_NEAR(gpu::coneEdge(gpu::coneRadius(2.0f, 0.0f, 4.0f), 2.0f, 0.0f, 4.0f), 1.0f, 1e-6f);
    EXPECT_EQ(gpu::acrossEdge(-0.1f, glm::vec4(-0.1f, -0.05f, -0.2f, -0.1f)), -1.0f);
    // Out at 0.1 / 0.4 of r one way, 0.1 / 0.2 another: the nearer counts.
    EXPECT_NEAR(gpu::acrossEdge(-0.1f, glm::vec4(0.3f, -0.1f, 0.1f, -0.1f)), -0.25f, 1e-6f);
    EXPECT_NEAR(gpu::acrossEdge(-0.1f, glm::vec4(-0.1f, 0.1f, -0.1f, -0.1f)), -0.5f, 1e-6f);
}

// Each probe lies r across the ray (four ways: two opposite pairs at right angles) and in the
// plane of the surface through the sample; a ray grazing its surface is not slid.
TEST(SdfMath, AcrossProbesStayInTheSurfacesPlane) {
    const glm::vec3 p(0.3f, 1.0f, -0.2f), toLight = glm::normalize(glm::vec3(0.4f, 1.0f, 0.2f));
    const glm::vec3 n = glm::normalize(glm::vec3(-0.3f, 1.0f, 0.5f));
    const float r = 0.2f;
    glm::vec3 across[4];
    for (int k = 0; k < 4; ++k) {
        const glm::vec3 q = gpu::acrossProbe(p, toLight, n, r, k);
        EXPECT_NEAR(glm::dot(q - p, n), 0.0f, 1e-5f) << k;
        across[k] = (q - p) - glm::dot(q - p, toLight) * toLight;
        EXPECT_NEAR(glm::length(across[k]), r, 1e-5f) << k;
    }
    EXPECT_NEAR(glm::length(across[0] + across[1]), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(across[2] + across[3]), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(across[0], across[2]), 0.0f, 1e-5f);
    const glm::vec3 flat = glm::normalize(glm::cross(toLight, glm::vec3(0, 0, 1)));
    EXPECT_NEAR(glm::dot(gpu::acrossProbe(p, toLight, flat, r, 0) - p, toLight), 0.0f, 1e-6f);
}

// A slab 0.04 thick filling a field box of 1 x 1 x 1 at y = 0.5, over receivers at y = 0.1,
// under a sun of 20 degrees straight above: its depth alone would leave a third of the sun open
// (asin(0.02 / 0.4) over asin(sin 10 degrees)). In the middle every probe is inside: dark. At
// 0.03 from the box's side the probes past it read open (the field holds nothing there): lit
// in part.
TEST(SdfMath, AcrossProbesOutsideTheFieldAreOpen) {
    FieldGrid field{.origin = glm::vec3(0.0f), .voxel = 1.0f / 64.0f, .size = glm::uvec3(64)};
    field.values.resize(64 * 64 * 64);
    for (uint32_t z = 0; z < 64; ++z)
        for (uint32_t y = 0; y < 64; ++y)
            for (uint32_t x = 0; x < 64; ++x)
                field.values[(size_t{z} * 64 + y) * 64 + x] =
                    std::abs((static_cast<float>(y) + 0.5f) / 64.0f - 0.5f) - 0.02f;
    const Light sun{.type = LightType::Directional, .direction = {0, -1, 0}, .angularDiameter = 20};
    const TraceSettings s{
        .steps = 256, .startOffset = 1.0f, .minStep = 0.25f, .thickness = 0.0f, .horizon = false};
    EXPECT_EQ(traceFieldVisibility(field, sun, {0.5f, 0.1f, 0.5f}, {0, 1, 0}, s), 0.0f);
    EXPECT_GT(traceFieldVisibility(field, sun, {0.03f, 0.1f, 0.5f}, {0, 1, 0}, s), 0.05f);
}
