// Invalidation by caster (src/core/moved_casters.h): what moved between two poses, as boxes that
// hold each moved run where it was and where it is; and the resident pages of every light type's
// levels those boxes may draw into, checked against each page's own projection (pageViewProj).
#include "core/moved_casters.h"
#include "scene/mesh_builder.h"
#include "virtual_field.h"
#include "virtual_pages.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <random>

using namespace penumbra;
using namespace penumbra::virtual_field;

namespace {

// A floor and a sphere (its triangles after the floor's two).
Scene floorAndSphere() {
    Scene scene;
    MeshBuilder mb(scene);
    const uint32_t grey = mb.material("floor", {0.7f, 0.7f, 0.7f});
    mb.quad({-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, {-5, 0, -5}, grey);
    mb.sphere({0.5f, 1.0f, -0.5f}, 0.4f, mb.material("ball", {0.7f, 0.2f, 0.2f}));
    return scene;
}
constexpr size_t kFloorVertices = 4;

Bounds boundsOf(const Scene& s, size_t firstVertex) {
    Bounds b;
    for (size_t v = firstVertex; v < s.vertices.size(); ++v)
        b.grow(s.vertices[v].position);
    return b;
}

bool holds(const Bounds& b, glm::vec3 p) {
    return glm::all(glm::lessThanEqual(b.min, p)) && glm::all(glm::lessThanEqual(p, b.max));
}

// Whether `box` may draw into `page` of `level`, from the page's own projection: its corners'
// rectangle in the page's NDC overlaps the page widened by `texels`. Corners behind a
// perspective eye: all of them, never; some, always.
bool drawsInto(const VirtualLevel& level, const PageKey& page, const Bounds& box, double texels) {
    const glm::dmat4 m(pageViewProj(level, page.page - level.firstPage));
    glm::dvec2 lo(1e300), hi(-1e300);
    int behind = 0;
    for (int c = 0; c < 8; ++c) {
        const glm::dvec4 clip =
            m * glm::dvec4((c & 1) ? box.max.x : box.min.x, (c & 2) ? box.max.y : box.min.y,
                           (c & 4) ? box.max.z : box.min.z, 1.0);
        if (level.projection.perspective && clip.w <= 0.0) {
            ++behind;
            continue;
        }
        lo = glm::min(lo, glm::dvec2(clip) / clip.w);
        hi = glm::max(hi, glm::dvec2(clip) / clip.w);
    }
    if (behind > 0)
        return behind < 8;
    const double edge = 1.0 + 2.0 * texels / small().pageSize;
    return lo.x <= edge && lo.y <= edge && hi.x >= -edge && hi.y >= -edge;
}

// Whether `triangle` may draw into `page` of `level`, from the page's own projection: the
// triangle of its projected corners meets the page widened by `texels` (separating axes: the
// square's two, the triangle's three edge normals). A corner behind a perspective eye: as its
// box.
bool drawsInto(const VirtualLevel& level, const PageKey& page, const MovedTriangle& triangle,
               double texels) {
    const glm::dmat4 m(pageViewProj(level, page.page - level.firstPage));
    std::array<glm::dvec2, 3> p;
    Bounds box;
    for (size_t k = 0; k < 3; ++k) {
        const glm::dvec4 clip = m * glm::dvec4(glm::dvec3(triangle.corners[k]), 1.0);
        box.grow(triangle.corners[k]);
        if (level.projection.perspective && clip.w <= 0.0)
            return drawsInto(level, page, box, texels);
        p[k] = glm::dvec2(clip) / clip.w;
    }
    const double edge = 1.0 + 2.0 * texels / small().pageSize;
    for (int axis = 0; axis < 2; ++axis) {
        const double lo = std::min({p[0][axis], p[1][axis], p[2][axis]});
        const double hi = std::max({p[0][axis], p[1][axis], p[2][axis]});
        if (lo > edge || hi < -edge)
            return false;
    }
    for (size_t k = 0; k < 3; ++k) {
        const glm::dvec2 d = p[(k + 1) % 3] - p[k];
        const glm::dvec2 normal(-d.y, d.x);
        double lo = 1e300, hi = -1e300;
        for (const glm::dvec2& q : p) {
            lo = std::min(lo, glm::dot(normal, q));
            hi = std::max(hi, glm::dot(normal, q));
        }
        const double reach = edge * (std::abs(normal.x) + std::abs(normal.y)); // the square's
        if (lo > reach || hi < -reach)
            return false;
    }
    return true;
}

Bounds boundsOf(const MovedTriangle& t) {
    Bounds b;
    for (const glm::vec3& c : t.corners)
        b.grow(c);
    return b;
}

// A cache that holds every page of `levels` and of `elsewhere` (a sun's windows for another
// camera: pages kept past the window's edge).
PageCache everyPage(const std::vector<VirtualLevel>& levels,
                    const std::vector<VirtualLevel>& elsewhere) {
    std::vector<PageKey> all;
    for (const auto* set : {&levels, &elsewhere})
        for (const VirtualLevel& l : *set)
            for (uint32_t e = 0; e < l.tableEntries(); ++e)
                all.push_back(pageKeyOf(l, l.tableOffset + e));
    PageCache cache(static_cast<uint32_t>(all.size()));
    cache.update(all, 1);
    return cache;
}

} // namespace

TEST(MovedCasters, NothingMovedDropsNothing) {
    const Scene s = floorAndSphere();
    Scene turned = s;
    turned.vertices[7].normal = -turned.vertices[7].normal; // the depth pass reads no normal
    turned.vertices[7].color.x = 0.1f;                      // nor a colour but its alpha
    for (const Scene* after : std::initializer_list<const Scene*>{&s, &turned})
        EXPECT_TRUE(movedCasters(s, *after).boxes.empty());
}

Bounds triangleBounds(const Scene& s, size_t t) {
    Bounds b;
    for (int k = 0; k < 3; ++k)
        b.grow(s.vertices[s.indices[3 * t + size_t(k)]].position);
    return b;
}

bool sameBox(const Bounds& a, const Bounds& b) {
    return a.min == b.min && a.max == b.max;
}

// Triangle t of `s`, its corners in order.
bool sameTriangle(const MovedTriangle& m, const Scene& s, size_t t) {
    for (size_t k = 0; k < 3; ++k)
        if (m.corners[k] != s.vertices[s.indices[3 * t + k]].position)
            return false;
    return true;
}

// A moved sphere: each of its triangles bounded where it was, then where it is, in order; the
// floor in none, and nothing between the two places (the sweep).
TEST(MovedCasters, EachMovedTriangleIsBoundedWhereItWasAndWhereItIs) {
    const Scene before = floorAndSphere();
    Scene after = before;
    const glm::vec3 step{0.9f, -0.2f, 0.1f}; // more than the ball's width: the places apart
    for (size_t v = kFloorVertices; v < after.vertices.size(); ++v)
        after.vertices[v].position += step;
    const MovedCasters m = movedCasters(before, after);
    const size_t sphereTriangles = before.triangleCount() - 2;
    ASSERT_EQ(m.boxes.size(), 2 * sphereTriangles);
    ASSERT_EQ(m.triangles.size(), m.boxes.size());
    ASSERT_EQ(m.indices.size(), sphereTriangles) << "each moved triangle once";
    for (size_t t = 2; t < before.triangleCount(); ++t) {
        EXPECT_EQ(m.indices[t - 2], t);
        EXPECT_TRUE(sameBox(m.boxes[2 * (t - 2)], triangleBounds(before, t))) << t;
        EXPECT_TRUE(sameBox(m.boxes[2 * (t - 2) + 1], triangleBounds(after, t))) << t;
        EXPECT_TRUE(sameTriangle(m.triangles[2 * (t - 2)], before, t)) << t;
        EXPECT_TRUE(sameTriangle(m.triangles[2 * (t - 2) + 1], after, t)) << t;
    }
    const glm::vec3 between = boundsOf(before, kFloorVertices).center() + 0.5f * step;
    for (const Bounds& b : m.boxes) {
        EXPECT_FALSE(holds(b, before.vertices[0].position)) << "the floor's corner did not move";
        EXPECT_FALSE(holds(b, between)) << "the sweep between the poses holds no triangle";
    }
}

// A scene from nothing (the first pose of a streamed level) or to nothing: every triangle is
// bounded where it is, or was, and nothing is read of the empty pose.
TEST(MovedCasters, ASceneFromOrToNothingIsBoundedTriangleByTriangle) {
    const Scene scene = floorAndSphere();
    const Scene nothing;
    for (const bool appears : {true, false}) {
        const MovedCasters m =
            appears ? movedCasters(nothing, scene) : movedCasters(scene, nothing);
        ASSERT_EQ(m.boxes.size(), scene.triangleCount()) << appears;
        ASSERT_EQ(m.triangles.size(), scene.triangleCount()) << appears;
        ASSERT_EQ(m.indices.size(), scene.triangleCount()) << appears;
        for (size_t t = 0; t < scene.triangleCount(); ++t) {
            EXPECT_EQ(m.indices[t], t) << appears;
            EXPECT_TRUE(sameBox(m.boxes[t], triangleBounds(scene, t))) << appears << " " << t;
            EXPECT_TRUE(sameTriangle(m.triangles[t], scene, t)) << appears << " " << t;
        }
    }
    EXPECT_TRUE(movedCasters(nothing, nothing).boxes.empty());
}

// What the alpha test reads moves a triangle too; triangles apart are runs apart; triangles
// added or removed are bounded where they are; the same corners under other indices did not move,
// turned about they did.
TEST(MovedCasters, WhatTheDepthPassReadsMovesATriangle) {
    const Scene before = floorAndSphere();
    auto editedFloor = [&](auto edit) {
        Scene after = before;
        edit(after.vertices[2]); // the floor quad's corner in both of its triangles
        const MovedCasters m = movedCasters(before, after);
        // The floor's two triangles, each one box: their corners stayed.
        EXPECT_EQ(m.boxes.size(), 2u);
        for (size_t t = 0; t < std::min<size_t>(2, m.boxes.size()); ++t)
            EXPECT_TRUE(sameBox(m.boxes[t], triangleBounds(before, t))) << t;
    };
    editedFloor([](Vertex& v) { v.uv.x += 0.5f; });
    editedFloor([](Vertex& v) { v.color.w = 0.5f; });
    editedFloor([](Vertex& v) { v.material = 1; });
    // The first and the last triangle of the sphere: their own boxes, not one over the sphere.
    Scene apart = before;
    const size_t last = before.triangleCount() - 1;
    apart.vertices[before.indices[3 * 2]].position.y += 0.01f;
    apart.vertices[before.indices[3 * last + 2]].position.y += 0.01f;
    const MovedCasters two = movedCasters(before, apart);
    ASSERT_GE(two.boxes.size(), 4u);
    EXPECT_TRUE(sameBox(two.boxes.front(), triangleBounds(before, 2)));
    EXPECT_TRUE(sameBox(two.boxes.back(), triangleBounds(apart, last)));
    for (const Bounds& b : two.boxes)
        EXPECT_LT(glm::length(b.extent()), 0.5f) << "a triangle's box, not the sphere's";
    // The sphere's last triangle removed, then added back: one box, that triangle's.
    const size_t lastTriangle = before.triangleCount() - 1;
    Bounds lastOne;
    for (int k = 0; k < 3; ++k)
        lastOne.grow(before.vertices[before.indices[3 * lastTriangle + size_t(k)]].position);
    Scene fewer = before;
    fewer.indices.resize(fewer.indices.size() - 3);
    for (const MovedCasters& m : {movedCasters(before, fewer), movedCasters(fewer, before)}) {
        ASSERT_EQ(m.boxes.size(), 1u);
        EXPECT_EQ(m.boxes[0].min, lastOne.min);
        EXPECT_EQ(m.boxes[0].max, lastOne.max);
    }
    // The same corners through vertices of their own (an unused vertex, a copy of the first
    // triangle's first corner): nothing moved. Its corners turned about: it did.
    Scene copied = before;
    copied.vertices.push_back(copied.vertices[copied.indices[0]]);
    copied.indices[0] = static_cast<uint32_t>(copied.vertices.size() - 1);
    EXPECT_TRUE(movedCasters(before, copied).boxes.empty());
    // One corner of the first triangle alone through a moved copy of its vertex: that triangle.
    for (size_t k = 0; k < 3; ++k) {
        Scene corner = before;
        Vertex copy = corner.vertices[corner.indices[k]];
        copy.position.y += 0.5f;
        corner.vertices.push_back(copy);
        corner.indices[k] = static_cast<uint32_t>(corner.vertices.size() - 1);
        const MovedCasters m = movedCasters(before, corner);
        ASSERT_EQ(m.boxes.size(), 2u) << "corner " << k << ": where it was and where it is";
        EXPECT_TRUE(sameBox(m.boxes[0], triangleBounds(before, 0))) << "corner " << k;
        EXPECT_TRUE(sameBox(m.boxes[1], triangleBounds(corner, 0))) << "corner " << k;
        EXPECT_TRUE(holds(m.boxes[1], copy.position)) << "corner " << k;
    }
    Scene turned = before;
    std::swap(turned.indices[0], turned.indices[1]);
    const MovedCasters flipped = movedCasters(before, turned);
    ASSERT_EQ(flipped.boxes.size(), 1u) << "the floor's first triangle, wound the other way";
    EXPECT_TRUE(holds(flipped.boxes[0], before.vertices[before.indices[0]].position));
}

// For a sun's clipmap (pages past its window's edge included), a spot's map and a point light's
// faces: exactly the pages a box may draw into are dropped, within the roundoff's slack.
TEST(MovedCasters, ThePagesDroppedAreThoseTheBoxDrawsInto) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> across(-20.0f, 20.0f), size(0.05f, 3.0f);
    for (const Light& light : {kSun, kSpot, kPoint}) {
        const std::vector<VirtualLevel> levels = levelsOf(light, {4, 2, 1});
        const std::vector<VirtualLevel> elsewhere = levelsOf(light, {-9, 2, 14});
        size_t dropped = 0, kept = 0;
        for (int i = 0; i < 6; ++i) {
            const glm::vec3 at{across(rng), 0.5f * std::abs(across(rng)), across(rng)};
            const Bounds box{.min = at, .max = at + glm::vec3(size(rng), size(rng), size(rng))};
            PageCache cache = everyPage(levels, elsewhere);
            const uint32_t resident = cache.resident();
            const uint32_t n = dropMovedPages(cache, levels, {&box, 1}, small().pageSize);
            EXPECT_EQ(cache.resident(), resident - n);
            for (const auto* set : {&levels, &elsewhere})
                for (const VirtualLevel& l : *set)
                    for (uint32_t e = 0; e < l.tableEntries(); ++e) {
                        const PageKey k = pageKeyOf(l, l.tableOffset + e);
                        const bool gone = !cache.physicalOf(k);
                        // Exactly: within a texel it must go; past one and a half it must stay.
                        if (drawsInto(l, k, box, 1.0)) {
                            EXPECT_TRUE(gone) << int(light.type) << " level " << l.level;
                        } else if (!drawsInto(l, k, box, 1.5)) {
                            EXPECT_FALSE(gone) << int(light.type) << " level " << l.level;
                        }
                        (gone ? dropped : kept) += 1;
                    }
        }
        EXPECT_GT(dropped, 20u) << int(light.type);
        EXPECT_GT(kept, 10 * dropped) << int(light.type) << ": a small box drops few pages";
    }
}

// With its triangle, a box drops exactly the pages the triangle itself may draw into: long thin
// triangles across many pages (a rod, a limb) drop far fewer than their boxes.
TEST(MovedCasters, ThePagesDroppedAreThoseTheTriangleDrawsInto) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> across(-12.0f, 12.0f), reach(-2.0f, 2.0f),
        thin(-0.05f, 0.05f);
    size_t allTriangles = 0, allBoxes = 0;
    for (const Light& light : {kSun, kSpot, kPoint}) {
        const std::vector<VirtualLevel> levels = levelsOf(light, {4, 2, 1});
        const std::vector<VirtualLevel> elsewhere = levelsOf(light, {-9, 2, 14});
        size_t dropped = 0, kept = 0, triangleDropped = 0, boxDropped = 0;
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 a{across(rng), 0.3f * std::abs(across(rng)), across(rng)};
            const glm::vec3 b = a + glm::vec3{reach(rng), reach(rng), reach(rng)};
            const MovedTriangle triangle{
                .corners = {a, b, a + glm::vec3{thin(rng), thin(rng), thin(rng)}}};
            const Bounds box = boundsOf(triangle);
            PageCache cache = everyPage(levels, elsewhere);
            PageCache byBox = cache;
            const uint32_t resident = cache.resident();
            const uint32_t n =
                dropMovedPages(cache, levels, {&box, 1}, small().pageSize, {&triangle, 1});
            EXPECT_EQ(cache.resident(), resident - n);
            triangleDropped += n;
            boxDropped += dropMovedPages(byBox, levels, {&box, 1}, small().pageSize);
            for (const auto* set : {&levels, &elsewhere})
                for (const VirtualLevel& l : *set)
                    for (uint32_t e = 0; e < l.tableEntries(); ++e) {
                        const PageKey k = pageKeyOf(l, l.tableOffset + e);
                        const bool gone = !cache.physicalOf(k);
                        if (drawsInto(l, k, triangle, 1.0)) {
                            EXPECT_TRUE(gone) << int(light.type) << " level " << l.level;
                        } else if (!drawsInto(l, k, triangle, 1.5)) {
                            EXPECT_FALSE(gone) << int(light.type) << " level " << l.level;
                        }
                        EXPECT_TRUE(!gone || byBox.physicalOf(k) == std::nullopt)
                            << "a triangle's pages are some of its box's";
                        (gone ? dropped : kept) += 1;
                    }
        }
        std::printf("light %d: the triangles drop %zu pages, their boxes %zu\n", int(light.type),
                    triangleDropped, boxDropped);
        EXPECT_GT(dropped, 20u) << int(light.type);
        EXPECT_GT(kept, 10 * dropped) << int(light.type);
        EXPECT_LE(triangleDropped, boxDropped) << int(light.type);
        allTriangles += triangleDropped, allBoxes += boxDropped;
    }
    EXPECT_LT(allTriangles * 2, allBoxes) << "long thin triangles: half their boxes' pages at most";
}

// A box round a point light is partly behind every face's eye: every page goes. One wholly behind
// a spot draws nothing: every page stays. A page of a level the frame does not have goes.
TEST(MovedCasters, BoxesBehindTheEyeAndLevelsNotThere) {
    const std::vector<VirtualLevel> faces = levelsOf(kPoint, {0, 2, 0});
    PageCache round = everyPage(faces, {});
    const Bounds atTheBulb{.min = kPoint.position - 0.1f, .max = kPoint.position + 0.1f};
    EXPECT_EQ(dropMovedPages(round, faces, {&atTheBulb, 1}, small().pageSize), round.capacity());
    const Light spot{.type = LightType::Spot,
                     .position = {3, 40, 2},
                     .direction = {0, -1, 0},
                     .outerConeAngle = 0.6f};
    const std::vector<VirtualLevel> levels = levelsOf(spot, {0, 2, 0});
    PageCache cache = everyPage(levels, {});
    const Bounds above{.min = {-50, 41, -50}, .max = {50, 45, 50}};
    EXPECT_EQ(dropMovedPages(cache, levels, {&above, 1}, small().pageSize), 0u);
    const Bounds far{.min = {900, 0, 900}, .max = {901, 1, 901}}; // outside the cone
    EXPECT_EQ(dropMovedPages(cache, levels, {&far, 1}, small().pageSize), 0u);
    EXPECT_EQ(dropMovedPages(cache, levels, {}, small().pageSize), 0u);
    const std::vector<VirtualLevel> allButFinest(levels.begin() + 1, levels.end());
    EXPECT_EQ(dropMovedPages(cache, allButFinest, {&far, 1}, small().pageSize),
              levels[0].tableEntries());
}

// Keeping the static layers (virtual.staticLayer), the pages a box would drop are marked stale
// instead, in their places, and leave the table; pages of a level the frame lacks still go.
TEST(MovedCasters, KeepingStaticLayersMarksStaleWhatADropWouldDrop) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> across(-20.0f, 20.0f), size(0.05f, 3.0f);
    for (const Light& light : {kSun, kSpot, kPoint}) {
        const std::vector<VirtualLevel> levels = levelsOf(light, {4, 2, 1});
        const std::vector<VirtualLevel> elsewhere = levelsOf(light, {-9, 2, 14});
        for (int i = 0; i < 3; ++i) {
            const glm::vec3 at{across(rng), 0.5f * std::abs(across(rng)), across(rng)};
            const Bounds box{.min = at, .max = at + glm::vec3(size(rng), size(rng), size(rng))};
            const PageCache before = everyPage(levels, elsewhere);
            PageCache dropped = before, kept = before;
            const uint32_t resident = kept.resident();
            const uint32_t n = dropMovedPages(dropped, levels, {&box, 1}, small().pageSize);
            EXPECT_EQ(
                dropMovedPages(kept, levels, {&box, 1}, small().pageSize, {}, MovedPage::Stale), n);
            uint32_t stale = 0, gone = 0;
            for (uint32_t physical = 0; physical < kept.capacity(); ++physical) {
                const std::optional<PageKey> k = dropped.keyOf(physical);
                if (!before.keyOf(physical))
                    continue;
                const bool inLevels = levelOf(levels, *before.keyOf(physical)) != nullptr;
                if (!kept.keyOf(physical)) {
                    ++gone;
                    EXPECT_FALSE(inLevels);
                    continue;
                }
                EXPECT_EQ(kept.stale(physical), !k.has_value()) << int(light.type);
                stale += kept.stale(physical);
            }
            EXPECT_GT(stale, 0u) << int(light.type);
            EXPECT_EQ(stale + gone, n);
            // Drawn again, a stale page keeps its layer; one whose layer was lost does not.
            PageCache lost = before;
            dropMovedPages(lost, levels, {&box, 1}, small().pageSize, {},
                           MovedPage::StaleLayerLost);
            for (uint32_t physical = 0; physical < kept.capacity(); ++physical)
                if (kept.stale(physical)) {
                    EXPECT_TRUE(lost.stale(physical));
                    const PageKey k = *kept.keyOf(physical);
                    EXPECT_EQ(kept.update({k}, 2).staticHeld, std::vector<uint8_t>{1});
                    EXPECT_EQ(lost.update({k}, 2).staticHeld, std::vector<uint8_t>{0});
                    break;
                }
            EXPECT_EQ(kept.resident(), resident - gone);
            const uint32_t entries = elsewhere.back().tableOffset + elsewhere.back().tableEntries();
            const std::vector<uint32_t> table = pageTable(levels, kept, entries);
            for (const VirtualLevel& l : levels)
                for (uint32_t e = 0; e < l.tableEntries(); ++e) {
                    const uint32_t physical =
                        kept.physicalOf(pageKeyOf(l, l.tableOffset + e)).value();
                    EXPECT_EQ(table[l.tableOffset + e] == VIRTUAL_NOT_RESIDENT,
                              kept.stale(physical));
                }
        }
        // A level the frame lacks: its pages go, whatever keeps the layers.
        PageCache cache = everyPage(levels, {});
        const uint32_t resident = cache.resident();
        const std::vector<VirtualLevel> allButFinest(levels.begin() + 1, levels.end());
        const Bounds far{.min = glm::vec3(1e6f), .max = glm::vec3(1e6f + 1.0f)};
        EXPECT_GE(
            dropMovedPages(cache, allButFinest, {&far, 1}, small().pageSize, {}, MovedPage::Stale),
            levels[0].tableEntries());
        EXPECT_EQ(cache.resident(), resident - levels[0].tableEntries());
    }
}

// Many boxes at once (a moved figure's triangles, some close together, some apart, projected in
// runs and only where pages are held) drop exactly the pages the boxes drop one at a time.
TEST(MovedCasters, ManyBoxesDropWhatEachBoxDropsAlone) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> across(-12.0f, 12.0f), near(-1.5f, 1.5f),
        size(0.02f, 0.4f), unit(0.0f, 1.0f);
    for (const Light& light : {kSun, kSpot, kPoint}) {
        const std::vector<VirtualLevel> levels = levelsOf(light, {4, 2, 1});
        const std::vector<VirtualLevel> elsewhere = levelsOf(light, {-9, 2, 14});
        std::vector<Bounds> boxes;
        // The cluster by the camera: the finest levels' windows hold it.
        const glm::vec3 centre = glm::vec3{4, 1, 1} + 0.3f * glm::vec3{near(rng), 0, near(rng)};
        for (int i = 0; i < 70; ++i) {
            const glm::vec3 at = i % 3 == 2 ? glm::vec3{across(rng), unit(rng) * 4.0f, across(rng)}
                                            : centre + glm::vec3{near(rng), near(rng), near(rng)};
            boxes.push_back({.min = at, .max = at + glm::vec3(size(rng), size(rng), size(rng))});
        }
        // The pool holds, level by level in turn: none of its pages (the first), only the page
        // under a point beside the cluster (a run's bounds reach it and others, few boxes do),
        // or a scattered part of them (from this frame's windows and a sun's other windows).
        const Bounds dot{.min = centre + glm::vec3(2, 0, -2), .max = centre + glm::vec3(2, 0, -2)};
        const std::vector<std::vector<PageRect>> beside =
            movedPageRects(levels, {&dot, 1}, small().pageSize);
        PageCache held = everyPage(levels, elsewhere);
        held.dropIf([&](const PageKey& k) {
            const VirtualLevel* l = levelOf(levels, k);
            const auto i = static_cast<size_t>(l - levels.data());
            if (i == 0)
                return true;
            if (i % 2 == 1 && !beside[i].empty())
                return beside[i][0].wholeLevel || k.page != beside[i][0].lo;
            return unit(rng) < 0.6f;
        });
        // And the same boxes with a triangle each (one across the box's diagonal).
        std::vector<MovedTriangle> triangles;
        for (const Bounds& b : boxes)
            triangles.push_back({.corners = {b.min, b.max, glm::vec3(b.min.x, b.max.y, b.min.z)}});
        for (const bool byTriangle : {false, true}) {
            const std::span<const MovedTriangle> with =
                byTriangle ? std::span<const MovedTriangle>(triangles)
                           : std::span<const MovedTriangle>();
            PageCache together = held;
            dropMovedPages(together, levels, boxes, small().pageSize, with);
            std::vector<PageCache> alone;
            for (size_t b = 0; b < boxes.size(); ++b) {
                alone.push_back(held);
                dropMovedPages(alone.back(), levels, {&boxes[b], 1}, small().pageSize,
                               byTriangle ? with.subspan(b, 1) : with);
            }
            size_t gone = 0, stayed = 0;
            for (uint32_t physical = 0; physical < held.capacity(); ++physical) {
                const std::optional<PageKey> k = held.keyOf(physical);
                if (!k)
                    continue;
                const bool anyAlone =
                    std::any_of(alone.begin(), alone.end(),
                                [&](const PageCache& c) { return !c.keyOf(physical); });
                EXPECT_EQ(!together.keyOf(physical), anyAlone)
                    << int(light.type) << " level " << k->level << " page " << k->page.x << ","
                    << k->page.y << (byTriangle ? " by triangle" : "");
                (anyAlone ? gone : stayed) += 1;
            }
            EXPECT_GT(gone, 5u) << int(light.type);
            EXPECT_GT(stayed, gone) << int(light.type);
        }
    }
}
