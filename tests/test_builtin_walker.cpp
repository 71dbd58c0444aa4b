// builtin:walker (issue 59): a figure placed by linear blend skinning, walking a circle, posed
// from its kWalker* constants alone: the pose repeats each stride turned by the lap's share,
// the lower foot always touches the floor, the swinging foot lifts, the figure faces along the
// circle, and a skin keeps the surface whole where the knees and elbows bend.
#include "penumbra/scene.h"
#include "scene/builtin_scenes.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

using namespace penumbra;
using namespace penumbra::builtin;

namespace {

// The figure's vertices (all but the floor's four), posed at `time`.
std::vector<Vertex> figure(double time) {
    const Scene s = loadScene("builtin:walker", {.time = time});
    return {s.vertices.begin() + 4, s.vertices.end()};
}

// The figure's heading at `time`: its place on the circle and the turn about +y that takes its
// own frame (facing +z) to the world's.
float heading(double time) {
    return float(2.0 * std::numbers::pi * time / kWalkerLapSeconds);
}

// A world point in the walker's own frame at `time`: x to its side, z ahead of it.
glm::vec3 local(glm::vec3 p, double time) {
    const float h = heading(time);
    const glm::vec3 place(kWalkerCircleRadius * std::cos(h), 0.0f,
                          kWalkerCircleRadius * std::sin(h));
    return glm::vec3(glm::rotate(glm::mat4(1.0f), h, glm::vec3(0, 1, 0)) *
                     glm::vec4(p - place, 1.0f));
}

// The lowest height of the figure's vertices on its left (x < 0) or right side, in its frame.
float lowest(const std::vector<Vertex>& f, double time, bool left) {
    float y = INFINITY;
    for (const Vertex& v : f) {
        const glm::vec3 p = local(v.position, time);
        if ((p.x < -0.05f) == left && std::abs(p.x) > 0.05f)
            y = std::min(y, p.y);
    }
    return y;
}

} // namespace

TEST(BuiltinWalker, ItsLightsCameraAndAnimationAreTheConstants) {
    const Scene s = loadScene("builtin:walker", {.time = 1.3, .animation = "walk"});
    EXPECT_EQ(s.animation, "walk");
    EXPECT_EQ(s.animationDuration, float(kWalkerLapSeconds));
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.lights[0].type, LightType::Directional);
    EXPECT_LT(glm::length(s.lights[0].direction - glm::normalize(kWalkerSunDirection)), 1e-6f);
    EXPECT_EQ(s.lights[1].type, LightType::Point);
    EXPECT_EQ(s.lights[1].position, kWalkerBulbPosition);
    EXPECT_EQ(s.vertices[0].position.y, 0.0f) << "the floor first";
    EXPECT_EQ(std::abs(s.vertices[0].position.x), kWalkerFloorHalfSize);
}

// A stride later the pose is the same, turned about +y by the stride's share of the lap
// (positions and normals alike); a lap later it is the same pose.
TEST(BuiltinWalker, EachStrideRepeatsThePoseTurnedAlongTheCircle) {
    for (const double t : {0.0, 0.3, 1.7, 4.45}) {
        const std::vector<Vertex> a = figure(t), b = figure(t + kWalkerStrideSeconds),
                                  lap = figure(t + kWalkerLapSeconds);
        ASSERT_EQ(a.size(), b.size());
        ASSERT_EQ(a.size(), lap.size());
        const float turn =
            -float(2.0 * std::numbers::pi * kWalkerStrideSeconds / kWalkerLapSeconds);
        const glm::mat3 r(glm::rotate(glm::mat4(1.0f), turn, glm::vec3(0, 1, 0)));
        float position = 0.0f, normal = 0.0f, again = 0.0f;
        for (size_t i = 0; i < a.size(); ++i) {
            position = std::max(position, glm::length(r * a[i].position - b[i].position));
            normal = std::max(normal, glm::length(r * a[i].normal - b[i].normal));
            again = std::max(again, glm::length(a[i].position - lap[i].position));
        }
        EXPECT_LT(position, 1e-4f) << t;
        EXPECT_LT(normal, 1e-4f) << t;
        EXPECT_LT(again, 1e-4f) << t;
    }
}

// Every frame of a lap the lower foot stands on the floor (its sole within a facet's sag of
// y = 0, never below), so the contact moves with it.
TEST(BuiltinWalker, TheLowerFootAlwaysTouchesTheFloor) {
    for (int k = 0; k < 40; ++k) {
        const double t = k * kWalkerLapSeconds / 40.0;
        float y = INFINITY;
        for (const Vertex& v : figure(t))
            y = std::min(y, v.position.y);
        EXPECT_GE(y, -1e-5f) << t;
        EXPECT_LE(y, 0.01f) << t;
    }
}

// A quarter stride in, the left leg is forward and the right back, in the walker's own frame
// (facing along the circle, counter-clockwise seen from above); half a stride later, the other
// way, and the hands the other way round. At the stride's start the left knee bends and its foot
// lifts while the right stands; half a stride later the right lifts.
TEST(BuiltinWalker, TheLegsSwingAndTheSwingingFootLifts) {
    const auto feet = [](double t, bool left) {
        float z = 0.0f;
        size_t n = 0;
        for (const Vertex& v : figure(t)) {
            const glm::vec3 p = local(v.position, t);
            if (p.y < 0.2f && (p.x < 0.0f) == left)
                z += p.z, ++n;
        }
        return n ? z / float(n) : NAN;
    };
    // The hands (the arms hang outside the legs' reach) swing against the legs.
    const auto hands = [](double t, bool left) {
        float z = 0.0f;
        size_t n = 0;
        for (const Vertex& v : figure(t)) {
            const glm::vec3 p = local(v.position, t);
            if (p.y < 1.1f && p.y > 0.6f && std::abs(p.x) > 0.26f && (p.x < 0.0f) == left)
                z += p.z, ++n;
        }
        return n ? z / float(n) : NAN;
    };
    const double quarter = kWalkerStrideSeconds / 4.0, half = kWalkerStrideSeconds / 2.0;
    EXPECT_LT(hands(quarter, true), -0.02f); // the forearms, bent forward, hold it near
    EXPECT_GT(hands(quarter, false), 0.1f);
    EXPECT_GT(hands(quarter + half, true), 0.1f);
    EXPECT_GT(feet(quarter, true), 0.15f);
    EXPECT_LT(feet(quarter, false), -0.15f);
    EXPECT_LT(feet(quarter + half, true), -0.15f);
    EXPECT_GT(feet(quarter + half, false), 0.15f);
    const std::vector<Vertex> start = figure(0.0), later = figure(half);
    EXPECT_GT(lowest(start, 0.0, true), 0.05f);
    EXPECT_LT(lowest(start, 0.0, false), 0.01f);
    EXPECT_LT(lowest(later, half, true), 0.01f);
    EXPECT_GT(lowest(later, half, false), 0.05f);
}

// Vertices that coincide in one pose (the rings where a limb's pieces meet) coincide in every
// pose: each is placed by the same blend of its joints' matrices, so a bending knee opens no
// crack. And the knees do bend: some edges change their length while most keep it.
TEST(BuiltinWalker, TheSkinKeepsTheSurfaceWholeWhereTheLimbsBend) {
    const std::vector<Vertex> a = figure(0.0);
    std::vector<std::pair<size_t, size_t>> together;
    for (size_t i = 0; i < a.size(); ++i)
        for (size_t j = i + 1; j < a.size(); ++j)
            if (glm::length(a[i].position - a[j].position) < 1e-6f)
                together.emplace_back(i, j);
    ASSERT_GT(together.size(), 100u);
    for (const double t : {0.25, 0.5, 3.1}) {
        const std::vector<Vertex> b = figure(t);
        float apart = 0.0f;
        for (const auto& [i, j] : together)
            apart = std::max(apart, glm::length(b[i].position - b[j].position));
        EXPECT_LT(apart, 1e-5f) << t;
    }
    const Scene s0 = loadScene("builtin:walker", {.time = 0.0});
    const Scene s1 = loadScene("builtin:walker", {.time = 0.5});
    size_t kept = 0, changed = 0;
    for (size_t i = 6; i < s0.indices.size(); i += 3) { // past the floor's two triangles
        const uint32_t p = s0.indices[i], q = s0.indices[i + 1];
        const float before = glm::length(s0.vertices[p].position - s0.vertices[q].position);
        const float after = glm::length(s1.vertices[p].position - s1.vertices[q].position);
        (std::abs(after - before) < 1e-4f ? kept : changed) += 1;
    }
    EXPECT_GT(changed, 20u) << "the knees and elbows bend";
    EXPECT_GT(kept, 8 * changed) << "the rest moves rigidly";
}

// Parts that touch in one pose touch in every pose: a foot stays on its shin and a hand on its
// forearm (each moves with its joint), a thigh at the pelvis and an arm at the shoulders. Near
// a hip the thigh turns inside the pelvis (0.45 radians either way), which moves a vertex 0.2
// below the joint up to 9 cm: vertices of separate meshes within 5 cm at the stride's start stay
// within 20 cm all the lap. A shin that followed the hip instead would leave its foot 38 cm
// away (0.9 radians over 0.43).
TEST(BuiltinWalker, PartsThatTouchStayTogether) {
    const Scene s = loadScene("builtin:walker", {.time = 0.0});
    // The meshes: vertices joined by triangles (union-find), the floor's left out.
    std::vector<uint32_t> parent(s.vertices.size());
    for (uint32_t v = 0; v < parent.size(); ++v)
        parent[v] = v;
    const auto root = [&](uint32_t v) {
        while (parent[v] != v)
            v = parent[v] = parent[parent[v]];
        return v;
    };
    for (size_t i = 6; i < s.indices.size(); i += 3)
        for (size_t k = 1; k < 3; ++k)
            parent[root(s.indices[i + k])] = root(s.indices[i]);
    std::vector<std::pair<uint32_t, uint32_t>> touching;
    for (uint32_t i = 4; i < s.vertices.size(); ++i)
        for (uint32_t j = i + 1; j < s.vertices.size(); ++j)
            if (root(i) != root(j) &&
                glm::length(s.vertices[i].position - s.vertices[j].position) < 0.05f)
                touching.emplace_back(i, j);
    ASSERT_GT(touching.size(), 50u);
    for (const double t : {0.2, 0.5, 0.75, 2.6}) {
        const Scene later = loadScene("builtin:walker", {.time = t});
        float apart = 0.0f;
        for (const auto& [i, j] : touching)
            apart = std::max(apart,
                             glm::length(later.vertices[i].position - later.vertices[j].position));
        EXPECT_LT(apart, 0.2f) << t;
    }
}

// A pose late in a long run is as fine as an early one: ten million seconds is a whole number
// of laps and strides, so the pose then is the pose at the start, a tenth of a second apart.
TEST(BuiltinWalker, LatePosesAreAsFineAsEarlyOnes) {
    for (const double t : {0.1, 0.2, 0.73}) {
        const std::vector<Vertex> early = figure(t), late = figure(1e7 + t);
        ASSERT_EQ(early.size(), late.size());
        float apart = 0.0f;
        for (size_t i = 0; i < early.size(); ++i)
            apart = std::max(apart, glm::length(early[i].position - late[i].position));
        EXPECT_LT(apart, 1e-3f) << t;
    }
}
