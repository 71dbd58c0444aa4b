#pragma once
// Generated scenes of the kinds the automatic framing must tell apart (rooms, courtyards, solid
// models, buildings with rooms, levels under a sky plane, lone objects), and a CPU census of what
// a camera sees of them: how much of the view the subject fills and how much of it lies in a cast
// shadow.
#include "penumbra/scene.h"
#include "scene/framing.h"
#include "scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>

namespace penumbra::test {

inline glm::mat4 boxAt(const glm::vec3& centre, const glm::vec3& size) {
    return glm::scale(glm::translate(glm::mat4(1.0f), centre), size);
}

// A 20 x 4 x 12 room whose walls, floor and (optional) ceiling face inwards, a table inside.
inline Scene room(bool ceiling) {
    Scene scene;
    scene.name = "room";
    MeshBuilder mb(scene);
    const uint32_t m = mb.material("walls", glm::vec3(0.6f));
    const float x = 10.0f, y = 4.0f, z = 6.0f;
    mb.quad({-x, 0, z}, {x, 0, z}, {x, 0, -z}, {-x, 0, -z}, m);   // floor, facing up
    mb.quad({-x, 0, -z}, {x, 0, -z}, {x, y, -z}, {-x, y, -z}, m); // back wall, facing +z
    mb.quad({x, 0, z}, {-x, 0, z}, {-x, y, z}, {x, y, z}, m);     // front wall, facing -z
    mb.quad({-x, 0, z}, {-x, 0, -z}, {-x, y, -z}, {-x, y, z}, m); // left wall, facing +x
    mb.quad({x, 0, -z}, {x, 0, z}, {x, y, z}, {x, y, -z}, m);     // right wall, facing -x
    if (ceiling)
        mb.quad({-x, y, -z}, {x, y, -z}, {x, y, z}, {-x, y, z}, m); // facing down
    mb.box(glm::scale(glm::translate(glm::mat4(1.0f), {2.0f, 0.5f, 1.0f}), {2.0f, 1.0f, 1.0f}), m);
    return scene;
}

// A solid 4 x 4 x 4 box (outward faces): a model, not a room.
inline Scene solidBox() {
    Scene scene;
    scene.name = "solid box";
    MeshBuilder mb(scene);
    mb.box(boxAt({0, 2, 0}, glm::vec3(4.0f)), mb.material("box", glm::vec3(0.5f)));
    return scene;
}

// A 20 x 8 x 12 building: a closed outer shell facing out, and inside it a floor and walls facing
// in (modelled rooms). Seen from outside, like a tower with its floors modelled.
inline Scene buildingWithRooms() {
    Scene scene = room(true);
    scene.name = "building";
    MeshBuilder mb(scene);
    mb.box(boxAt({0, 2.0f, 0}, {20.4f, 4.4f, 12.4f}), mb.material("facade", glm::vec3(0.7f)));
    return scene;
}

// A courtyard: four solid wings (outward faces) round an open square with a paved floor.
inline Scene courtyard() {
    Scene scene;
    scene.name = "courtyard";
    MeshBuilder mb(scene);
    const uint32_t m = mb.material("stone", glm::vec3(0.6f));
    mb.quad({-8, 0, 8}, {8, 0, 8}, {8, 0, -8}, {-8, 0, -8}, m);
    mb.box(boxAt({0, 2, -7}, {16, 4, 2}), m);
    mb.box(boxAt({0, 2, 7}, {16, 4, 2}), m);
    mb.box(boxAt({-7, 2, 0}, {2, 4, 12}), m);
    mb.box(boxAt({7, 2, 0}, {2, 4, 12}), m);
    return scene;
}

// A level: 12 blocks of different heights on a 60 x 60 ground before a 400 x 200 sky backdrop
// 150 behind it, with a stray triangle 900 away.
inline Scene levelUnderSky() {
    Scene scene;
    scene.name = "level";
    MeshBuilder mb(scene);
    const uint32_t m = mb.material("ground", glm::vec3(0.5f));
    mb.quad({-30, 0, 30}, {30, 0, 30}, {30, 0, -30}, {-30, 0, -30}, m);
    for (int i = 0; i < 12; ++i) {
        const float x = -15.0f + 10.0f * static_cast<float>(i % 4);
        const float z = -10.0f + 10.0f * static_cast<float>(i / 4);
        const float h = 1.0f + static_cast<float>((i * 7) % 5);
        mb.box(boxAt({x, 0.5f * h, z}, {3.0f, h, 3.0f}), m);
    }
    mb.quad({-200, 0, -150}, {200, 0, -150}, {200, 200, -150}, {-200, 200, -150}, m);
    mb.quad({900, 0, 0}, {901, 0, 0}, {901, 1, 0}, {900, 1, 0}, m);
    return scene;
}

// A lone model: a tall box with a smaller one leaning on it, no ground.
inline Scene loneObject() {
    Scene scene;
    scene.name = "lone";
    MeshBuilder mb(scene);
    const uint32_t m = mb.material("model", glm::vec3(0.7f));
    mb.box(boxAt({0, 1.5f, 0}, {1, 3, 1}), m);
    mb.box(boxAt({1.0f, 0.5f, 0.3f}, {1, 1, 1}), m);
    return scene;
}

// What `camera` sees of `scene` in a w x h image: the share of pixels that show the subject
// (a surface inside subjectBounds), and the share that show any surface facing `light` (within a
// spot's cone) with another triangle between it and the light (a cast shadow, not a surface
// turned away). By brute force over every triangle: a census independent of the hierarchy the
// product's own measure (scene/first_picture.h) uses.
struct ViewCensus {
    float subject = 0.0f, castShadow = 0.0f;
};
inline ViewCensus viewCensus(const Scene& scene, const Camera& camera, const Light& light,
                             Bounds subject, int w = 64, int h = 36) {
    const ViewFrustum f = viewFrustum(camera, static_cast<float>(w) / static_cast<float>(h));
    std::vector<Ray> rays;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const glm::vec2 ndc((2.0f * static_cast<float>(x) + 1.0f) / static_cast<float>(w) - 1,
                                1 - (2.0f * static_cast<float>(y) + 1.0f) / static_cast<float>(h));
            const glm::vec2 half = f.halfExtentPerDistance;
            rays.push_back({.origin = f.position + ndc.x * f.halfExtent.x * f.right +
                                      ndc.y * f.halfExtent.y * f.up,
                            .direction = glm::normalize(f.forward + ndc.x * half.x * f.right +
                                                        ndc.y * half.y * f.up)});
        }
    const auto hits = firstHitsBruteForce(scene, rays);
    subject.min -= 1e-3f, subject.max += 1e-3f;
    std::vector<Ray> shadowRays;
    std::vector<float> reach;
    for (size_t i = 0; i < rays.size(); ++i) {
        if (!hits[i])
            continue;
        const glm::vec3 p = rays[i].origin + hits[i]->distance * rays[i].direction;
        const uint32_t* t = &scene.indices[3 * size_t{hits[i]->triangle}];
        const glm::vec3 a = scene.vertices[t[0]].position;
        glm::vec3 n = glm::normalize(
            glm::cross(scene.vertices[t[1]].position - a, scene.vertices[t[2]].position - a));
        if (glm::dot(n, rays[i].direction) > 0) // the side the camera sees
            n = -n;
        glm::vec3 toLight = -light.direction;
        float distance = std::numeric_limits<float>::infinity();
        if (light.type != LightType::Directional) {
            distance = glm::length(light.position - p);
            toLight = (light.position - p) / distance;
            if (light.type == LightType::Spot &&
                glm::dot(-toLight, light.direction) < std::cos(light.outerConeAngle))
                continue;
        }
        if (glm::dot(n, toLight) <= 0.05f)
            continue;
        shadowRays.push_back({.origin = p + 1e-3f * n, .direction = toLight});
        reach.push_back(distance - 1e-3f);
    }
    int subjectPixels = 0;
    for (size_t i = 0; i < rays.size(); ++i)
        if (hits[i]) {
            const glm::vec3 p = rays[i].origin + hits[i]->distance * rays[i].direction;
            subjectPixels += glm::all(glm::lessThanEqual(subject.min, p)) &&
                             glm::all(glm::lessThanEqual(p, subject.max));
        }
    const auto blocked = firstHitsBruteForce(scene, shadowRays);
    int shadowed = 0;
    for (size_t i = 0; i < blocked.size(); ++i)
        shadowed += blocked[i] && blocked[i]->distance < reach[i];
    const float pixels = static_cast<float>(rays.size());
    return {.subject = static_cast<float>(subjectPixels) / pixels,
            .castShadow = static_cast<float>(shadowed) / pixels};
}

} // namespace penumbra::test
