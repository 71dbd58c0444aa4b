// The `sdf` technique's CPU reference field (issue 13): exact point-triangle distance in every
// Voronoi region, the generalised winding number's sign, and whole meshes against their closed
// forms.
#include "reference/distance_field.h"
#include "scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace penumbra;

// Against a dense sampling of the triangle: the returned point lies on it and no sample is
// nearer. Points are drawn all around, so every vertex, edge and face region is visited.
TEST(Reference, DistanceFieldClosestPointIsTheNearestPointOfTheTriangle) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    auto random = [&] { return glm::dvec3(unit(rng), unit(rng), unit(rng)); };
    constexpr int n = 120;
    for (int t = 0; t < 60; ++t) {
        const glm::dvec3 a = random(), b = random(), c = random();
        const glm::dvec3 normal = glm::cross(b - a, c - a);
        if (glm::length(normal) < 0.05)
            continue;
        for (int k = 0; k < 20; ++k) {
            const glm::dvec3 p = 2.0 * random();
            const glm::dvec3 q = closestPointOnTriangle(p, a, b, c);
            // On the triangle: barycentric coordinates in [0, 1], no distance off its plane.
            const double area = glm::dot(normal, normal);
            const double u = glm::dot(glm::cross(c - b, q - b), normal) / area;
            const double v = glm::dot(glm::cross(a - c, q - c), normal) / area;
            EXPECT_NEAR(glm::dot(q - a, normal) / glm::length(normal), 0.0, 1e-12);
            EXPECT_GE(u, -1e-12);
            EXPECT_GE(v, -1e-12);
            EXPECT_LE(u + v, 1.0 + 1e-12);
            const double found = glm::distance(p, q);
            double sampled = 1e30;
            for (int i = 0; i <= n; ++i)
                for (int j = 0; i + j <= n; ++j) {
                    const glm::dvec3 s = a + (b - a) * (i / double(n)) + (c - a) * (j / double(n));
                    sampled = std::min(sampled, glm::distance(p, s));
                }
            EXPECT_LE(found, sampled + 1e-12) << "triangle " << t << ", point " << k;
            EXPECT_GE(found, sampled - 2.0 / n) << "triangle " << t << ", point " << k;
        }
    }
}

// A box of half-extents h rotated and moved: the signed distance of a box, length(max(q, 0)) +
// min(max(q.x, q.y, q.z), 0) with q = |p| - h in the box's frame, to 1e-9 inside and out.
TEST(Reference, DistanceFieldOfABoxMeetsItsClosedForm) {
    Scene scene;
    MeshBuilder mb(scene);
    const glm::vec3 half(0.5f, 0.25f, 1.0f), centre(0.3f, -0.2f, 0.7f);
    const glm::mat4 rotation =
        glm::rotate(glm::mat4(1.0f), 0.6f, glm::normalize(glm::vec3(1, 2, 3)));
    const glm::mat4 transform = glm::translate(glm::mat4(1.0f), centre) * rotation *
                                glm::scale(glm::mat4(1.0f), 2.0f * half);
    mb.box(transform, mb.material("box", glm::vec3(0.5f)));
    const glm::dmat4 toBox =
        glm::inverse(glm::dmat4(glm::translate(glm::mat4(1.0f), centre) * rotation));
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(-1.2, 1.2);
    int inside = 0;
    for (int k = 0; k < 400; ++k) {
        const glm::dvec3 p(unit(rng), unit(rng), unit(rng));
        const glm::dvec3 local(toBox * glm::dvec4(p, 1.0));
        const glm::dvec3 q = glm::abs(local) - glm::dvec3(half);
        const double expected =
            glm::length(glm::max(q, 0.0)) + std::min(std::max({q.x, q.y, q.z}), 0.0);
        const FieldSample s = sampleDistanceField(scene, p);
        EXPECT_NEAR(s.signedDistance(), expected, 1e-6) << p.x << ", " << p.y << ", " << p.z;
        EXPECT_NEAR(s.winding, expected < 0 ? 1.0 : 0.0, 1e-9);
        inside += expected < 0;
    }
    EXPECT_GT(inside, 10);
}

// A tessellated sphere: |distance to the centre - r| within the facets' sagitta; the sign from
// the winding number; an open quad (a ground) stays unsigned on both sides.
TEST(Reference, DistanceFieldOfASphereAndAnOpenQuad) {
    Scene scene;
    MeshBuilder mb(scene);
    const uint32_t m = mb.material("grey", glm::vec3(0.5f));
    const glm::vec3 centre(0.0f, 1.3f, 0.0f);
    const float r = 0.8f;
    mb.sphere(centre, r, m);
    const double sagitta = r * (1.0 - std::cos(3.14159265 / 32)); // 32 stacks, 64 slices
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int k = 0; k < 200; ++k) {
        const glm::dvec3 d = glm::normalize(glm::dvec3(unit(rng), unit(rng), unit(rng)));
        const double radius = 0.2 + 1.2 * (unit(rng) + 1.0);
        const glm::dvec3 p = glm::dvec3(centre) + d * radius;
        const FieldSample s = sampleDistanceField(scene, p);
        EXPECT_NEAR(s.signedDistance(), radius - r, 2.0 * sagitta) << radius;
        // The facets lie up to the sagitta inside the sphere: between, either side may hold.
        if (radius < r - sagitta || radius > r) {
            EXPECT_NEAR(s.winding, radius < r ? 1.0 : 0.0, 1e-6) << radius;
        }
    }
    Scene ground;
    MeshBuilder(ground).quad({-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, {-5, 0, -5}, 0);
    for (double y : {-0.7, -0.01, 0.01, 0.4}) {
        const FieldSample s = sampleDistanceField(ground, {0.3, y, -1.2});
        EXPECT_NEAR(s.distance, std::abs(y), 1e-12);
        EXPECT_LT(std::abs(s.winding), 0.5) << y;
        EXPECT_GT(s.signedDistance(), 0.0) << y;
    }
}
