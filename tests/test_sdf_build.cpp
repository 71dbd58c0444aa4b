// The `sdf` field's inputs for real assets: alpha-tested triangles cut into few pieces (merged
// where covered), each brick's nearest triangle (what far voxels start from), closed surfaces
// that hold something inside taken as shells, and the counts the stats report.
#include "scene/mesh_builder.h"
#include "sdf_math.h"
#include "shadows/sdf_cut.h"
#include "shadows/sdf_field.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace penumbra;
using namespace penumbra::shadows;

namespace {

Bounds boundsOf(glm::vec3 lo, glm::vec3 hi) {
    Bounds b;
    b.grow(lo);
    b.grow(hi);
    return b;
}

// A card over a ground plane, its material `texels` x `texels` (alpha 255 where `covered`),
// alpha-tested.
Scene maskedCard(bool (*covered)(uint32_t x, uint32_t y), uint32_t texels = 8) {
    Scene scene;
    MeshBuilder mb(scene);
    mb.quad({-4, 0, 4}, {4, 0, 4}, {4, 0, -4}, {-4, 0, -4}, mb.material("ground", glm::vec3(0.7f)));
    TextureImage image{.name = "mask", .width = texels, .height = texels};
    for (uint32_t y = 0; y < texels; ++y)
        for (uint32_t x = 0; x < texels; ++x)
            image.rgba.insert(image.rgba.end(), {200, 200, 200, uint8_t(covered(x, y) ? 255 : 0)});
    const uint32_t card = mb.texturedMaterial(
        "card", image,
        {.wrapS = TextureWrap::ClampToEdge, .wrapT = TextureWrap::ClampToEdge, .nearest = true},
        AlphaMode::Mask);
    mb.quad({-2, 2, 2}, {2, 2, 2}, {2, 2, -2}, {-2, 2, -2}, card);
    dropInvalidTriangles(scene);
    return scene;
}

double area(const gpu::FieldTriangle& t) {
    return 0.5 * glm::length(glm::cross(glm::dvec3(t.b - t.a), glm::dvec3(t.c - t.a)));
}

} // namespace

// A fully covered card stays two triangles without outlines; a card whose left half is a hole
// keeps exactly the right half's area, in far fewer pieces than its grid, with outlines only on
// the pieces along the hole (the hole's edge runs along the subdivision's midlines: few).
TEST(SdfField, AlphaTestedTrianglesAreMergedWhereCovered) {
    const FieldLayout layout = fieldLayout(boundsOf({-4, 0, -4}, {4, 2, 4}), 128);
    const FieldGeometry whole =
        fieldGeometry(maskedCard([](uint32_t, uint32_t) { return true; }), layout, layout.voxel);
    EXPECT_EQ(whole.sceneTriangles, 4u);
    EXPECT_EQ(whole.alphaTriangles, 2u);
    EXPECT_EQ(whole.alphaPieces, 2u);
    for (size_t t = 2; t < whole.triangles.size(); ++t)
        EXPECT_EQ(flagsOf(whole.triangles[t]), uint32_t{FIELD_OPEN}) << t;

    const FieldGeometry half = fieldGeometry(
        maskedCard([](uint32_t x, uint32_t) { return x >= 4; }), layout, layout.voxel);
    EXPECT_EQ(half.alphaTriangles, 2u);
    EXPECT_EQ(half.triangles.size(), size_t{half.alphaPieces} + 2);
    double covered = 0.0;
    size_t outlined = 0;
    for (size_t t = 2; t < half.triangles.size(); ++t) {
        const gpu::FieldTriangle& p = half.triangles[t];
        covered += area(p);
        const glm::vec3 centre = (glm::vec3(p.a) + glm::vec3(p.b) + glm::vec3(p.c)) / 3.0f;
        EXPECT_GT(centre.x, 0.0f) << "a piece in the hole"; // u = 0 at x = -2
        outlined += (flagsOf(p) & (FIELD_OUTLINE_AB | FIELD_OUTLINE_BC | FIELD_OUTLINE_CA)) != 0;
    }
    EXPECT_NEAR(covered, 8.0, 0.25); // half the 4x4 card, up to the pieces along the diagonal
    // The grid has 2 x 64^2 pieces; merged, about the hole's edge's worth.
    EXPECT_LT(half.alphaPieces, 1000u);
    EXPECT_GE(outlined, 1u);
    EXPECT_LT(outlined, half.alphaPieces);
}

// The cut is as coarse as the field allows: its finest pieces are at most 1.5 voxels across and
// more than half that (one subdivision fewer would pass 1.5). A fine random mask leaves single
// grid pieces uncovered next to covered ones, so the finest pieces are the grid's. Under a small
// budget the grid coarsens until n^2 fits, and the budget shrinks by n^2.
TEST(SdfField, AlphaTestedPiecesAreAsCoarseAsTheFieldAllows) {
    const Scene scene = maskedCard(
        [](uint32_t x, uint32_t y) { return ((x * 73856093u) ^ (y * 19349663u)) % 3u != 0u; }, 256);
    auto finestPiece = [&](float voxel, uint64_t& budget) {
        std::vector<gpu::FieldTriangle> pieces;
        for (size_t t = 2; t < 4; ++t) { // the card's two triangles, after the ground's
            const std::array<const Vertex*, 3> v{&scene.vertices[scene.indices[3 * t]],
                                                 &scene.vertices[scene.indices[3 * t + 1]],
                                                 &scene.vertices[scene.indices[3 * t + 2]]};
            cutByCoverage(scene, v, voxel, budget, pieces);
        }
        float finest = std::numeric_limits<float>::infinity();
        for (const gpu::FieldTriangle& p : pieces) {
            const glm::vec3 a(p.a), b(p.b), c(p.c);
            finest = std::min(
                finest, std::max({glm::distance(a, b), glm::distance(b, c), glm::distance(c, a)}));
        }
        EXPECT_GT(pieces.size(), 2u) << "the mask leaves holes";
        return finest;
    };
    // The card's triangles are 4 x 4 x 5.66: 8 x 8 pieces of 0.707 at a voxel of 0.5 (1.41
    // voxels); 16 x 16 would be 0.71 voxels, 4 x 4 2.83 voxels.
    for (const float voxel : {0.5f, 0.25f, 0.2f}) {
        uint64_t budget = 1'000'000;
        const float finest = finestPiece(voxel, budget) / voxel;
        EXPECT_LE(finest, 1.5f + 1e-4f) << "voxel " << voxel;
        EXPECT_GT(finest, 0.75f) << "voxel " << voxel;
        const uint64_t n =
            static_cast<uint64_t>(std::lround(4.0f * std::sqrt(2.0f) / (finest * voxel)));
        EXPECT_EQ(budget, 1'000'000 - 2 * n * n) << "voxel " << voxel;
    }
    uint64_t ample = 1'000'000;
    EXPECT_NEAR(finestPiece(0.001f, ample), 4.0f * std::sqrt(2.0f) / 64.0f, 1e-4f)
        << "64 x 64 pieces at most, however fine the field";
    uint64_t small = 70; // the first triangle takes 8 x 8; 6 are left for the second
    const float coarse = finestPiece(0.5f, small);
    EXPECT_NEAR(coarse, 4.0f * std::sqrt(2.0f) / 8.0f, 1e-4f) << "the first triangle's 8 x 8";
    EXPECT_EQ(small, 70u - 64u - 4u) << "then 2 x 2, the largest square within the 6 left";
}

// Each brick's nearest triangle: exact where one of its list is within a brick of its centre;
// elsewhere (jump flooded over
// the bricks) within a voxel of the nearest, for a sphere, a plane and a beam.
TEST(SdfField, EveryBrickKnowsItsNearestTriangle) {
    Scene scene;
    MeshBuilder mb(scene);
    const uint32_t grey = mb.material("grey", glm::vec3(0.5f));
    mb.sphere({0, 1, 0}, 0.7f, grey, 12, 6);
    mb.quad({-3, 0, 3}, {3, 0, 3}, {3, 0, -3}, {-3, 0, -3}, grey);
    mb.beam({-2, 0.5f, -2}, {2, 2.0f, 1}, 0.1f, grey);
    dropInvalidTriangles(scene);
    const FieldLayout layout = fieldLayout(scene.bounds(), 64);
    const float thickness = 0.75f * layout.voxel;
    const FieldGeometry g = fieldGeometry(scene, layout, thickness);
    const glm::uvec3 bricks = layout.bricks();
    ASSERT_EQ(g.brickNearest.size(), size_t{bricks.x} * bricks.y * bricks.z);
    auto distance = [&](uint32_t id, glm::vec3 p) {
        const gpu::FieldTriangle& t = g.triangles[id];
        return gpu::fieldTriangleDistance(p, glm::vec3(t.a), glm::vec3(t.b), glm::vec3(t.c),
                                          flagsOf(t), thickness);
    };
    size_t listed = 0, far = 0;
    float worst = 0.0f;
    for (uint32_t z = 0; z < bricks.z; ++z)
        for (uint32_t y = 0; y < bricks.y; ++y)
            for (uint32_t x = 0; x < bricks.x; ++x) {
                const size_t b = (size_t{z} * bricks.y + y) * bricks.x + x;
                const glm::vec3 centre =
                    layout.origin + (glm::vec3(x, y, z) + 0.5f) * (FIELD_BRICK * layout.voxel);
                float nearest = std::numeric_limits<float>::infinity();
                for (uint32_t t = 0; t < g.triangles.size(); ++t)
                    nearest = std::min(nearest, distance(t, centre));
                ASSERT_NE(g.brickNearest[b], FIELD_NO_TRIANGLE);
                const float got = distance(g.brickNearest[b], centre);
                if (nearest <= FIELD_BRICK * layout.voxel) {
                    ++listed;
                    EXPECT_FLOAT_EQ(got, nearest) << b;
                } else {
                    ++far;
                    worst = std::max(worst, got - nearest);
                }
            }
    EXPECT_GT(listed, 100u);
    EXPECT_GT(far, 1000u);
    EXPECT_LT(worst, layout.voxel) << "world units";

    // The far candidates lose nothing: at every voxel of a brick that lists any, the nearest of
    // them is the nearest of the 27 bricks' nearest triangles.
    ASSERT_EQ(g.farCandidates.size(), size_t{g.farCandidates[g.brickNearest.size()]});
    size_t voxels = 0, mismatched = 0;
    for (uint32_t z = 0; z < bricks.z; ++z)
        for (uint32_t y = 0; y < bricks.y; ++y)
            for (uint32_t x = 0; x < bricks.x; ++x) {
                const size_t b = (size_t{z} * bricks.y + y) * bricks.x + x;
                if (g.farCandidates[b] == g.farCandidates[b + 1])
                    continue;
                for (uint32_t v = 0; v < FIELD_BRICK * FIELD_BRICK * FIELD_BRICK; v += 7) {
                    const glm::uvec3 voxel =
                        glm::uvec3(x, y, z) * FIELD_BRICK +
                        glm::uvec3(v % FIELD_BRICK, v / FIELD_BRICK % FIELD_BRICK,
                                   v / (FIELD_BRICK * FIELD_BRICK));
                    const glm::vec3 p = layout.voxelCentre(voxel);
                    float listedBest = std::numeric_limits<float>::infinity();
                    for (uint32_t i = g.farCandidates[b]; i < g.farCandidates[b + 1]; ++i)
                        listedBest = std::min(listedBest, distance(g.farCandidates[i], p));
                    float all = std::numeric_limits<float>::infinity();
                    for (int dz = -1; dz <= 1; ++dz)
                        for (int dy = -1; dy <= 1; ++dy)
                            for (int dx = -1; dx <= 1; ++dx) {
                                const glm::ivec3 q = glm::ivec3(x, y, z) + glm::ivec3(dx, dy, dz);
                                if (glm::any(glm::lessThan(q, glm::ivec3(0))) ||
                                    glm::any(glm::greaterThanEqual(q, glm::ivec3(bricks))))
                                    continue;
                                all = std::min(
                                    all,
                                    distance(g.brickNearest[(size_t(q.z) * bricks.y + size_t(q.y)) *
                                                                bricks.x +
                                                            size_t(q.x)],
                                             p));
                            }
                    ++voxels;
                    mismatched += listedBest != all;
                }
            }
    EXPECT_GT(voxels, 1000u);
    EXPECT_EQ(mismatched, 0u) << "of " << voxels;
}

// A closed box around the camera (a sky box, a room seen from inside) or around a point light:
// taken as a shell, open, with a warning naming its material and what it holds. A box around
// other geometry alone (a tower's envelope around its floors), a ball inside it, and a box
// resting on another stay solids; so does a box with a light on its surface.
TEST(SdfField, ClosedSurfacesHoldingTheLightOrCameraAreShells) {
    Scene scene;
    MeshBuilder mb(scene);
    const uint32_t glass = mb.material("glass", glm::vec3(0.5f));
    const uint32_t grey = mb.material("grey", glm::vec3(0.5f));
    mb.box(glm::scale(glm::mat4(1.0f), glm::vec3(4.0f)), glass); // [-2, 2]^3, the camera inside
    const size_t skyEnd = scene.triangleCount();
    mb.sphere({0, 0, 0}, 0.5f, grey, 12, 6);
    mb.box(glm::translate(glm::mat4(1.0f), glm::vec3(5, 0.5f, 0)), grey); // [4.5, 5.5] x [0, 1]
    mb.box(glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(5, 1.25f, 0)), glm::vec3(0.5f)),
           grey); // resting on it: [4.75, 5.25] x [1, 1.5]
    mb.box(glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(5, 4, 0)), glm::vec3(2.0f)),
           grey); // [4, 6] x [3, 5] around a small box: an envelope around floors
    mb.box(glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(5, 4, 0)), glm::vec3(0.5f)), grey);
    const size_t solidEnd = scene.triangleCount();
    mb.box(glm::translate(glm::scale(glm::mat4(1.0f), glm::vec3(2.0f)), glm::vec3(-4, 0, 0)),
           grey); // [-9, -7]: a room around a point light
    scene.lights.push_back({.name = "bulb", .type = LightType::Point, .position = {-8, 0, 0}});
    scene.lights.push_back({.name = "lamp", .type = LightType::Point, .position = {5, 1.0f, 0}});
    scene.cameras.push_back({.name = "inside", .position = {0, 1.5f, 0}});
    dropInvalidTriangles(scene);
    const Closure c = closedSurfaces(scene);
    for (size_t t = 0; t < scene.triangleCount(); ++t) {
        const bool shell = t < skyEnd || t >= solidEnd;
        EXPECT_EQ(c.closed[t], !shell) << t;
    }
    ASSERT_EQ(c.shells.size(), 2u);
    std::string all = c.shells[0] + "\n" + c.shells[1];
    EXPECT_NE(all.find("(material 'glass') holds camera 'inside'"), std::string::npos) << all;
    EXPECT_NE(all.find("(material 'grey') holds light 'bulb'"), std::string::npos) << all;
}
