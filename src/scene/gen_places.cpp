// Generated families of places (scene/generated.h): rooms with thin walls and windows, grazing
// light, long views under a low sun, bulbs among clutter.
#include "scene/framing.h"
#include "scene/gen_families.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace penumbra::gen {
namespace {

glm::mat4 boxBetween(const glm::vec3& lo, const glm::vec3& hi) {
    return glm::scale(glm::translate(glm::mat4(1.0f), 0.5f * (lo + hi)), hi - lo);
}

Camera lookingFrom(const Scene& scene, const glm::vec3& from, const glm::vec3& at, float yfov) {
    Camera c{.name = "generated", .position = from, .target = at, .yfov = yfov};
    const glm::vec2 depth = depthRangeFrom(scene, c.position);
    c.znear = depth.x, c.zfar = depth.y;
    return c;
}

} // namespace

// A room of thin walls (closed slabs 0.05 to 0.3 thick) with a window in the wall at -z (and in
// half the seeds one at +x), a ceiling, a table and cabinets; lit by a sun through the window, a
// bulb under the ceiling or a spot from a corner; seen from inside.
Scene interior(GenRandom& random) {
    Scene s;
    MeshBuilder mb(s);
    const uint32_t wall = mb.material("walls", drawColor(random));
    const uint32_t wood = mb.material("furniture", drawColor(random));
    const float w = random.uniform(3.0f, 7.0f); // half-width along x
    const float d = random.uniform(2.5f, 5.0f); // half-depth along z
    const float h = random.uniform(2.5f, 4.0f);
    const float t = random.logUniform(0.05f, 0.3f);
    // The window: its half-width and its sill and lintel heights.
    const float ww = random.uniform(0.4f, 0.35f * w);
    const float sill = random.uniform(0.3f, 1.0f), lintel = random.uniform(sill + 0.6f, h - 0.2f);
    const float wx = random.uniform(-w + ww + 0.2f, w - ww - 0.2f);
    mb.box(boxBetween({-w - t, -t, -d - t}, {w + t, 0, d + t}), wall); // floor slab
    mb.box(boxBetween({-w - t, h, -d - t}, {w + t, h + t, d + t}), wall);
    // The wall at -z round its window: left, right, below, above.
    mb.box(boxBetween({-w - t, 0, -d - t}, {wx - ww, h, -d}), wall);
    mb.box(boxBetween({wx + ww, 0, -d - t}, {w + t, h, -d}), wall);
    mb.box(boxBetween({wx - ww, 0, -d - t}, {wx + ww, sill, -d}), wall);
    mb.box(boxBetween({wx - ww, lintel, -d - t}, {wx + ww, h, -d}), wall);
    mb.box(boxBetween({-w - t, 0, d}, {w + t, h, d + t}), wall);
    mb.box(boxBetween({-w - t, 0, -d}, {-w, h, d}), wall);
    if (random.chance(0.5f)) { // a second window, in the wall at +x
        const float wz = random.uniform(-d + 1.0f, d - 1.0f);
        mb.box(boxBetween({w, 0, -d}, {w + t, h, wz - 0.5f}), wall);
        mb.box(boxBetween({w, 0, wz + 0.5f}, {w + t, h, d}), wall);
        mb.box(boxBetween({w, 0, wz - 0.5f}, {w + t, sill, wz + 0.5f}), wall);
        mb.box(boxBetween({w, lintel, wz - 0.5f}, {w + t, h, wz + 0.5f}), wall);
    } else {
        mb.box(boxBetween({w, 0, -d}, {w + t, h, d}), wall);
    }
    // A table (top and legs) and 1 to 3 cabinets along the walls.
    const float tx = random.uniform(-0.5f * w, 0.5f * w);
    const float tz = random.uniform(-0.4f * d, 0.4f * d);
    const float th = random.uniform(0.6f, 1.0f);
    mb.box(boxBetween({tx - 0.8f, th - 0.05f, tz - 0.5f}, {tx + 0.8f, th, tz + 0.5f}), wood);
    for (int leg = 0; leg < 4; ++leg) {
        const float lx = tx + (leg & 1 ? 0.7f : -0.7f), lz = tz + (leg & 2 ? 0.4f : -0.4f);
        mb.beam({lx, 0, lz}, {lx, th - 0.05f, lz}, 0.06f, wood);
    }
    const int cabinets = random.integer(1, 3);
    for (int i = 0; i < cabinets; ++i) {
        const float cx = random.uniform(-w + 0.6f, w - 0.6f);
        const float ch = random.uniform(0.8f, 0.9f * h);
        mb.box(boxBetween({cx - 0.5f, 0, d - 0.6f}, {cx + 0.5f, ch, d}), wood);
    }
    const Bounds room{.min = {-w, 0, -d}, .max = {w, h, d}};
    const int kind = random.integer(0, 2);
    Light light;
    if (kind == 0) { // a sun through the window at -z, from outside it
        const float up = glm::radians(random.uniform(20.0f, 55.0f));
        const float aside = random.uniform(-0.5f, 0.5f);
        light = {.name = "generated sun",
                 .type = LightType::Directional,
                 .direction = glm::normalize(glm::vec3(aside, -std::tan(up), 1.0f)),
                 .intensity = 2.0f,
                 .angularDiameter = random.chance(0.2f) ? 0.0f : random.logUniform(0.25f, 4.0f)};
    } else {
        light = drawLight(random, room, {.sun = false, .spot = kind == 2, .point = kind == 1});
        light.position.y = random.uniform(0.75f, 0.95f) * h; // under the ceiling
        light.position.x = std::clamp(light.position.x, -w + 0.3f, w - 0.3f);
        light.position.z = std::clamp(light.position.z, -d + 0.3f, d - 0.3f);
        if (light.type == LightType::Spot) {
            light.direction = glm::normalize(glm::vec3(tx, 0.0f, tz) - light.position);
            light.outerConeAngle = 1.0f, light.innerConeAngle = 0.8f;
        }
        const float reach = light.position.y;
        light.intensity = 2.0f * reach * reach;
        light.radius = std::min(light.radius, 0.2f);
    }
    s.lights.push_back(light);
    // From near the corner at +x+z, looking at the table (where the shadows fall).
    const float ex = random.uniform(0.3f, 0.9f) * w;
    const float ey = random.uniform(1.2f, 0.8f * h);
    const float fov = random.uniform(0.9f, 1.3f);
    s.cameras.push_back(lookingFrom(s, {ex, ey, 0.8f * d}, {tx, 0.3f, tz}, fov));
    return s;
}

// Grazing light: a ground, low boxes and a ramp under a sun 3 to 12 degrees up, or a spot low at
// the side.
Scene grazing(GenRandom& random) {
    Scene s;
    MeshBuilder mb(s);
    const uint32_t m = groundAnd(mb, random, 30.0f, "blocks");
    const int count = random.integer(2, 8);
    for (int i = 0; i < count; ++i) {
        const float x = random.uniform(-4.0f, 4.0f);
        const float z = random.uniform(-4.0f, 4.0f);
        const float size = random.uniform(0.3f, 1.5f);
        const float height = random.uniform(0.05f, 0.6f);
        mb.box(boxBetween({x - size / 2, 0, z - size / 2}, {x + size / 2, height, z + size / 2}),
               m);
    }
    const float rise = random.uniform(0.05f, 0.5f); // a ramp: a receiver tilted off the ground
    mb.quad({-4, 0, 6}, {4, 0, 6}, {4, 4 * rise, 2}, {-4, 4 * rise, 2}, m);
    const Bounds content = contentOf(s, footprint(4.0f, 0.5f));
    LightChoice choice{.spot = false, .point = false, .lowestSun = 3.0f, .highestSun = 12.0f};
    Light light = drawLight(random, content, choice);
    if (random.chance(0.3f)) { // a spot low at the side instead
        const float x = random.uniform(-12.0f, 12.0f);
        light = {.name = "generated spot",
                 .type = LightType::Spot,
                 .position = {x, random.uniform(0.5f, 1.5f), -14.0f},
                 .intensity = 2.0f * 200.0f,
                 .innerConeAngle = 0.55f,
                 .outerConeAngle = 0.7f,
                 .radius = random.chance(0.2f) ? 0.0f : random.uniform(0.02f, 0.2f)};
        light.direction = glm::normalize(content.center() - light.position);
    }
    s.lights.push_back(light);
    s.cameras.push_back(orbitCamera(random, s, content, 25.0f, 60.0f));
    return s;
}

// A long view: a ground 300 to 1000 long, buildings and posts spread from near the camera to the
// far end (spaced more widely with distance), a sun 8 to 30 degrees up; the camera near the
// ground looking along it.
Scene longView(GenRandom& random) {
    Scene s;
    MeshBuilder mb(s);
    const float length = random.uniform(300.0f, 1000.0f);
    const uint32_t grass = mb.material("ground", drawColor(random));
    mb.quad({-60, 0, 20}, {60, 0, 20}, {60, 0, -length}, {-60, 0, -length}, grass);
    const uint32_t m = mb.material("buildings", drawColor(random));
    float z = -random.uniform(3.0f, 8.0f);
    while (z > -0.9f * length) {
        const float x = random.uniform(-25.0f, 25.0f);
        const float w = random.uniform(0.5f, 6.0f) * (1.0f - 0.02f * z);
        const float h = random.uniform(0.5f, 4.0f) * std::sqrt(1.0f - 0.05f * z);
        if (random.chance(0.3f))
            mb.beam({x, 0, z}, {x, h, z}, 0.1f * w, m); // a post
        else
            mb.box(boxBetween({x - w / 2, 0, z - w / 2}, {x + w / 2, h, z + w / 2}), m);
        z -= random.uniform(2.0f, 8.0f) * (1.0f - 0.01f * z);
    }
    const Bounds content{.min = {-30, 0, -length}, .max = {30, 10, 0}};
    s.lights.push_back(drawLight(
        random, content, {.spot = false, .point = false, .lowestSun = 8.0f, .highestSun = 30.0f}));
    const float ex = random.uniform(-5.0f, 5.0f);
    const float ey = random.uniform(1.5f, 8.0f);
    const float ahead = random.uniform(40.0f, 120.0f);
    const float fov = random.uniform(0.6f, 1.0f);
    s.cameras.push_back(lookingFrom(s, {ex, ey, 10.0f}, {ex, 0.0f, -ahead}, fov));
    return s;
}

// 30 to 80 small objects (boxes, low spheres, posts) in a cluster 2 to 4 across, and a bulb or
// spot close among them, 0.1 to 1 above their tops.
Scene clutter(GenRandom& random) {
    Scene s;
    MeshBuilder mb(s);
    const uint32_t m = groundAnd(mb, random, 10.0f, "clutter");
    const float spread = random.uniform(1.0f, 2.0f);
    const int count = random.integer(30, 80);
    for (int i = 0; i < count; ++i) {
        const float x = random.uniform(-spread, spread);
        const float z = random.uniform(-spread, spread);
        const float size = random.uniform(0.08f, 0.4f);
        const int kind = random.integer(0, 2);
        if (kind == 0) {
            const float height = random.uniform(0.5f, 2.0f) * size;
            mb.box(
                boxBetween({x - size / 2, 0, z - size / 2}, {x + size / 2, height, z + size / 2}),
                m);
        } else if (kind == 1) {
            mb.sphere({x, size / 2, z}, size / 2, m, 12, 6);
        } else {
            const float height = random.uniform(2.0f, 5.0f) * size;
            mb.beam({x, 0, z}, {x, height, z}, 0.15f * size, m);
        }
    }
    const Bounds content = contentOf(s, footprint(spread, 0.1f));
    Light light = drawLight(random, content, {.sun = false});
    const float x = random.uniform(-0.8f * spread, 0.8f * spread);
    const float z = random.uniform(-0.8f * spread, 0.8f * spread);
    light.position = {x, content.max.y + random.uniform(0.1f, 1.0f), z};
    light.radius = std::min(light.radius, 0.05f);
    if (light.type == LightType::Spot) {
        light.direction = glm::vec3(0, -1, 0);
        light.outerConeAngle = 1.2f, light.innerConeAngle = 1.0f;
    }
    const float reach = light.position.y;
    light.intensity = 2.0f * reach * reach;
    s.lights.push_back(light);
    s.cameras.push_back(orbitCamera(random, s, content, 30.0f, 65.0f));
    return s;
}

} // namespace penumbra::gen
