// The conventions of src/core/projection.h, tested by where points of each view volume land.
#include "core/light_space.h"
#include "core/projection.h"
#include "light_geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace penumbra;

namespace {

glm::vec3 project(const glm::mat4& m, const glm::vec3& p) {
    const glm::vec4 c = m * glm::vec4(p, 1.0f);
    return glm::vec3(c) / c.w;
}

void expectNear(const glm::vec3& a, const glm::vec3& b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

} // namespace

TEST(Projection, OrthographicMapsTheSeedsBoxOntoNdc) {
    // [-w/2, w/2] x [-h/2, h/2] x [n, f] (distance along -z) -> [-1,1]^2 x [0,1]
    const float w = 6, h = 4, n = 2, f = 12;
    const glm::mat4 m = orthographic(-w / 2, w / 2, -h / 2, h / 2, n, f);
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner(i & 1 ? w / 2 : -w / 2, i & 2 ? h / 2 : -h / 2, i & 4 ? -f : -n);
        expectNear(project(m, corner), {i & 1 ? 1.f : -1.f, i & 2 ? 1.f : -1.f, i & 4 ? 1.f : 0.f});
    }
    // Depth is linear: the seeds' z' = z/(f-n) + n/(n-f) with the typo'd row corrected.
    EXPECT_NEAR(project(m, {0, 0, -7}).z, (7.0f - n) / (f - n), 1e-6f);
    // Row-vector form of the seeds: the last row is [0, 0, n/(n-f), 1], no 2/h in it.
    EXPECT_FLOAT_EQ(m[3][1], 0.0f);
    EXPECT_FLOAT_EQ(m[3][2], n / (n - f));
}

TEST(Projection, PerspectiveLightNearIsZeroFarIsOneNoFlip) {
    const float fov = 1.2f, n = 0.5f, f = 40.0f;
    const glm::mat4 m = perspectiveLight(fov, 1.0f, n, f);
    EXPECT_NEAR(project(m, {0, 0, -n}).z, 0.0f, 1e-6f);
    EXPECT_NEAR(project(m, {0, 0, -f}).z, 1.0f, 1e-6f);
    const float d = 10.0f, edge = d * std::tan(fov / 2);
    expectNear(project(m, {edge, edge, -d}), {1.0f, 1.0f, project(m, {0, 0, -d}).z});
    // Depth grows monotonically with distance.
    EXPECT_LT(project(m, {0, 0, -3}).z, project(m, {0, 0, -4}).z);
}

TEST(Projection, CameraIsReverseZAndUpIsTheTopRow) {
    const float fov = 0.8f, n = 0.1f, f = 100.0f;
    const glm::mat4 m = perspectiveCameraReverseZ(fov, 2.0f, n, f);
    EXPECT_NEAR(project(m, {0, 0, -n}).z, 1.0f, 1e-6f);
    EXPECT_NEAR(project(m, {0, 0, -f}).z, 0.0f, 1e-6f);
    const float d = 5.0f, top = d * std::tan(fov / 2);
    // Vulkan NDC y = -1 is the framebuffer's first row: world-up must land there.
    EXPECT_NEAR(project(m, {0, top, -d}).y, -1.0f, 1e-5f);
    EXPECT_NEAR(project(m, {2.0f * top, 0, -d}).x, 1.0f, 1e-5f);
}

TEST(Projection, TextureMatrixMapsNdcCornersToTextureCorners) {
    const glm::mat4 t = textureMatrix();
    expectNear(project(t, {-1, -1, 0.25f}), {0, 0, 0.25f});
    expectNear(project(t, {1, 1, 0.75f}), {1, 1, 0.75f});
    expectNear(project(t, {0, 0, 0}), {0.5f, 0.5f, 0});
}

TEST(Projection, LookAtPutsEyeAtOriginAndTargetDownMinusZ) {
    const glm::vec3 eye(3, 4, 5), target(-1, 0, 2);
    const glm::mat4 v = lookAt(eye, target, {0, 1, 0});
    expectNear(project(v, eye), {0, 0, 0});
    expectNear(project(v, target), {0, 0, -glm::length(target - eye)}, 1e-5f);
    EXPECT_GT(project(v, eye + glm::vec3(0, 1, 0)).y, 0.0f); // world up stays up
}

TEST(LightSpace, DirectionalBoxFitsTheSceneTightly) {
    Bounds b;
    b.grow({-5, 0, -3});
    b.grow({4, 2, 6});
    const Light sun{.type = LightType::Directional,
                    .direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.5f))};
    const LightProjection p = fitDirectional(sun, b, 1024);
    const glm::mat4 st = textureMatrix() * p.viewProj;
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 c(i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y,
                          i & 4 ? b.max.z : b.min.z);
        const glm::vec3 s = project(st, c);
        lo = glm::min(lo, s), hi = glm::max(hi, s);
    }
    // Every corner inside [0,1]^3, and the box touches each face (tight fit).
    expectNear(lo, {0, 0, 0}, 1e-3f);
    expectNear(hi, {1, 1, 1}, 1e-3f);
    // Moving along the light direction increases depth.
    EXPECT_GT(project(st, b.center() + sun.direction).z, project(st, b.center()).z);
    EXPECT_NEAR(p.texelWorldSize * 1024.0f,
                std::max(p.window.y - p.window.x, p.window.w - p.window.z), 1e-4f);
}

namespace {

// An 8 x 1 x 8 box on the ground, and a spot 10 units above it looking down, cone 0.5 rad.
Bounds groundBox() {
    Bounds b;
    b.grow({-4, 0, -4});
    b.grow({4, 1, 4});
    return b;
}

Light spotAbove(float range = 0.0f) {
    return {.type = LightType::Spot,
            .position = {0, 10, 0},
            .direction = {0, -1, 0},
            .range = range,
            .outerConeAngle = 0.5f};
}

} // namespace

TEST(LightSpace, SpotFrustumCoversTheConeAndTheScene) {
    const Light spot = spotAbove();
    const LightProjection p = fitSpot(spot, groundBox(), 512);
    const glm::mat4 st = textureMatrix() * p.viewProj;
    // The cone's rim lands on the edge of the map.
    const glm::vec3 rim = spot.position + 8.0f * glm::vec3(std::sin(0.5f), -std::cos(0.5f), 0);
    const glm::vec3 s = project(st, rim);
    EXPECT_NEAR(std::max(std::abs(s.x - 0.5f), std::abs(s.y - 0.5f)), 0.5f, 1e-4f);
    // Scene depths fall inside [0,1].
    EXPECT_GE(project(st, {0, 1, 0}).z, 0.0f);
    EXPECT_LE(project(st, {4, 0, 4}).z, 1.0f);
    EXPECT_LT(p.nearPlane, 9.0f + 1e-3f);
    EXPECT_GE(p.farPlane, 10.0f); // axial depth of the ground, not Euclidean distance
}

TEST(LightSpace, SpotRangeCutsTheFarPlaneAndTexelSizeFollowsTheCone) {
    const Bounds b = groundBox();
    Light spot = spotAbove(9.5f);
    const LightProjection cut = fitSpot(spot, b, 512);
    // The ground (10 along the axis) lies beyond the range: the far plane stops at the range.
    EXPECT_NEAR(cut.farPlane, 9.5f * 1.001f, 1e-4f);
    EXPECT_NEAR(project(textureMatrix() * cut.viewProj, {0, 0.5f, 0}).z, 1.0f, 0.01f);
    spot.range = 50.0f; // past the scene: the scene decides
    const LightProjection whole = fitSpot(spot, b, 512);
    EXPECT_NEAR(whole.farPlane, 10.0f * 1.001f, 1e-3f);
    // One texel at unit distance spans the cone's full width over the map's texels.
    EXPECT_NEAR(whole.texelWorldSize * 512.0f, 2.0f * std::tan(0.5f), 1e-5f);
    EXPECT_NEAR(whole.yfov, 1.0f, 1e-6f);
}

TEST(Projection, AutomaticCameraFramesTheWholeScene) {
    // A scene without cameras: every vertex of its subject (here the whole scene) lies between
    // the automatic camera's near and far planes and inside its field of view.
    Scene scene;
    for (const glm::vec3& p : {glm::vec3(-30, 0, -5), glm::vec3(40, 2, -5), glm::vec3(40, 25, 60)})
        scene.vertices.push_back({p, {0, 1, 0}, 0});
    scene.indices = {0, 1, 2};
    const Camera c = scene.camera("");
    EXPECT_EQ(c.name, "auto");
    const glm::mat4 view = lookAt(c.position, c.target, c.up);
    for (int i = 0; i < 3; ++i) {
        const glm::vec3 corner = scene.vertices[static_cast<size_t>(i)].position;
        const glm::vec3 v = glm::vec3(view * glm::vec4(corner, 1.0f));
        const float distance = -v.z;
        EXPECT_GT(distance, c.znear) << "corner " << i;
        EXPECT_LT(distance, c.zfar) << "corner " << i;
        // Inside the vertical field of view, and the horizontal one of a 16:9 image.
        EXPECT_LT(std::abs(v.y) / distance, std::tan(0.5f * c.yfov)) << "corner " << i;
        EXPECT_LT(std::abs(v.x) / distance, 16.0f / 9.0f * std::tan(0.5f * c.yfov))
            << "corner " << i;
    }
    EXPECT_LT(c.znear, c.zfar);
}

namespace {

// Directions on a fine sphere grid, the axes, the face borders and the cube's corners.
std::vector<glm::vec3> testDirections() {
    std::vector<glm::vec3> d;
    for (int i = 0; i < 64; ++i)
        for (int j = 0; j <= 32; ++j) {
            const float phi = 6.2831853f * (static_cast<float>(i) + 0.37f) / 64.0f;
            const float theta = 3.1415927f * static_cast<float>(j) / 32.0f;
            d.push_back({std::sin(theta) * std::cos(phi), std::cos(theta),
                         std::sin(theta) * std::sin(phi)});
        }
    for (int x = -1; x <= 1; ++x)
        for (int y = -1; y <= 1; ++y)
            for (int z = -1; z <= 1; ++z)
                if (x || y || z)
                    d.push_back(glm::normalize(glm::vec3(x, y, z)));
    return d;
}

} // namespace

TEST(LightSpace, CubeFacesHoldEveryDirectionInsideTheirGuardBand) {
    const Light bulb{.type = LightType::Point, .position = {1.0f, 2.0f, -3.0f}};
    const Bounds scene{.min = {-20, -1, -25}, .max = {15, 9, 10}};
    const uint32_t size = 256, guard = 20;
    const float nearest = 0.5f;
    const std::vector<LightProjection> faces =
        fitLightViews(bulb, scene, size, {.guard = guard, .nearestSurface = nearest});
    ASSERT_EQ(faces.size(), kCubeFaces);
    const char* names[] = {"+x", "-x", "+y", "-y", "+z", "-z"};
    const float tanHalf = 256.0f / (256.0f - 40.0f);
    for (uint32_t f = 0; f < kCubeFaces; ++f) {
        EXPECT_STREQ(faces[f].name, names[f]);
        EXPECT_TRUE(faces[f].perspective);
        EXPECT_NEAR(faces[f].yfov, 2.0f * std::atan(tanHalf), 1e-6f);
        EXPECT_NEAR(faces[f].texelWorldSize, 2.0f * tanHalf / 256.0f, 1e-7f);
    }
    const float inner = static_cast<float>(guard) / static_cast<float>(size);
    for (const glm::vec3& d : testDirections()) {
        const uint32_t f = gpu::cubeFace(d);
        const LightProjection& face = faces[f];
        // The chosen face holds the direction inside its 90 degrees (the guard band stays free
        // for the kernels), at every distance between the nearest surface and the far plane.
        for (float distance : {nearest, 3.0f, 0.999f * face.farPlane}) {
            const glm::vec3 uvz =
                project(textureMatrix() * face.viewProj, bulb.position + distance * d);
            EXPECT_GE(uvz.x, inner - 1e-5f) << names[f] << " " << d.x << "," << d.y << "," << d.z;
            EXPECT_LE(uvz.x, 1.0f - inner + 1e-5f) << names[f];
            EXPECT_GE(uvz.y, inner - 1e-5f) << names[f];
            EXPECT_LE(uvz.y, 1.0f - inner + 1e-5f) << names[f];
            EXPECT_GE(uvz.z, 0.0f) << names[f] << ": a surface at " << distance << " is clipped";
            EXPECT_LE(uvz.z, 1.0f) << names[f];
        }
        // The face's whole frustum, guard band included, starts beyond the near plane: even the
        // far corner of the guard band at the nearest surface's distance is kept.
        glm::vec3 cornerDir(0.0f);
        const int axis = static_cast<int>(f / 2);
        cornerDir[axis] = f % 2 == 0 ? 1.0f : -1.0f;
        cornerDir[(axis + 1) % 3] = tanHalf;
        cornerDir[(axis + 2) % 3] = tanHalf;
        const glm::vec3 corner = project(textureMatrix() * face.viewProj,
                                         bulb.position + nearest * glm::normalize(cornerDir));
        EXPECT_GE(corner.z, 0.0f) << names[f];
    }
    // The far planes reach the scene's farthest corner along each axis.
    EXPECT_NEAR(faces[0].farPlane, 14.0f * 1.001f, 1e-3f); // +x: 15 - 1
    EXPECT_NEAR(faces[1].farPlane, 21.0f * 1.001f, 1e-3f); // -x: 1 + 20
    EXPECT_NEAR(faces[2].farPlane, 7.0f * 1.001f, 1e-3f);  // +y
    EXPECT_NEAR(faces[3].farPlane, 3.0f * 1.001f, 1e-3f);  // -y
    EXPECT_NEAR(faces[4].farPlane, 13.0f * 1.001f, 1e-3f); // +z
    EXPECT_NEAR(faces[5].farPlane, 22.0f * 1.001f, 1e-3f); // -z
}

TEST(LightSpace, CubeFacesHonourRangeAndCapTheGuardBand) {
    const Light bulb{.type = LightType::Point, .position = {0, 0, 0}, .range = 4.0f};
    const Bounds scene{.min = {-50, -50, -50}, .max = {50, 50, 50}};
    const std::vector<LightProjection> faces =
        fitLightViews(bulb, scene, 64, {.guard = 1000u, .nearestSurface = 1.0f});
    for (const LightProjection& face : faces) {
        EXPECT_NEAR(face.farPlane, 4.0f * 1.001f, 1e-4f) << face.name;
        // A guard band past a quarter of the map is capped there: tangent 2.
        EXPECT_NEAR(std::tan(0.5f * face.yfov), 2.0f, 1e-5f) << face.name;
    }
    // No surface known: the near plane keeps far / near at 1e4.
    const auto unknown = fitLightViews(bulb, scene, 64, {.nearestSurface = INFINITY});
    EXPECT_NEAR(unknown[0].nearPlane, unknown[0].farPlane * 1e-4f, 1e-7f);
    // A sun and a spot have one view.
    EXPECT_EQ(fitLightViews({.type = LightType::Directional}, scene, 64, {}).size(), 1u);
    EXPECT_EQ(
        fitLightViews({.type = LightType::Spot, .position = {0, 60, 0}}, scene, 64, {}).size(), 1u);
}

TEST(LightSpace, NearestSurfaceDistanceFindsFacesEdgesAndCorners) {
    Scene scene;
    auto vertex = [&](glm::vec3 p) {
        scene.vertices.push_back({.position = p});
        return static_cast<uint32_t>(scene.vertices.size() - 1);
    };
    // One triangle in the plane z = 0 with corners (0,0), (4,0), (0,4); a far one for company.
    scene.indices = {vertex({0, 0, 0}),   vertex({4, 0, 0}),   vertex({0, 4, 0}),
                     vertex({100, 0, 0}), vertex({101, 0, 0}), vertex({100, 1, 0})};
    EXPECT_NEAR(nearestSurfaceDistance(scene, {1, 1, 3}), 3.0f, 1e-5f);            // face
    EXPECT_NEAR(nearestSurfaceDistance(scene, {2, -2, 0}), 2.0f, 1e-5f);           // edge y = 0
    EXPECT_NEAR(nearestSurfaceDistance(scene, {3, 3, 0}), std::sqrt(2.0f), 1e-5f); // hypotenuse
    EXPECT_NEAR(nearestSurfaceDistance(scene, {-3, -4, 0}), 5.0f, 1e-5f);          // corner
    EXPECT_NEAR(nearestSurfaceDistance(scene, {7, 0, 4}), 5.0f, 1e-5f);            // corner (4,0)
    EXPECT_NEAR(nearestSurfaceDistance(scene, {100.5f, 0.2f, -2}), 2.0f, 1e-5f);   // the far one
    EXPECT_EQ(nearestSurfaceDistance(Scene{}, {0, 0, 0}), INFINITY);
    // The nearest triangle listed after a farther one, a little nearer than it: the cull that
    // skips triangles by their boxes must not skip it.
    Scene order;
    for (float z : {10.0f, 6.0f, 7.0f}) {
        const auto first = static_cast<uint32_t>(order.vertices.size());
        order.vertices.push_back({.position = {-1, -1, z}});
        order.vertices.push_back({.position = {1, -1, z}});
        order.vertices.push_back({.position = {0, 1, z}});
        order.indices.insert(order.indices.end(), {first, first + 1, first + 2});
    }
    EXPECT_NEAR(nearestSurfaceDistance(order, {0, 0, 0}), 6.0f, 1e-5f);
}
