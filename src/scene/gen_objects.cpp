// Generated families of objects over a ground (scene/generated.h): stacked plates and shelves,
// spheres, alpha-tested leaf cards, open and mis-wound meshes, creases and curved tessellation.
#include "scene/builtin_scenes.h"
#include "scene/gen_families.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace penumbra::gen {
namespace {

constexpr float kGround = 12.0f; // the ground's half-size under the objects' families

// A box centred at `centre`, turned `turn` radians about +y, of `size`.
glm::mat4 placed(const glm::vec3& centre, float turn, const glm::vec3& size) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), centre);
    m = glm::rotate(m, turn, {0, 1, 0});
    return glm::scale(m, size);
}

// The light and the camera over the content: the 3-unit footprint and every object on the ground.
Scene finish(Scene scene, GenRandom& random, const LightChoice& choice) {
    const Bounds content = contentOf(scene, footprint(3.0f));
    scene.lights.push_back(drawLight(random, content, choice));
    scene.cameras.push_back(orbitCamera(random, scene, content));
    return scene;
}

} // namespace

// Stacks of 2 to 5 thin plates (closed slabs 0.01 to 0.15 thick) or shelves (open quads on
// posts), each smaller or larger than the one below: casters over casters.
Scene plates(GenRandom& random) {
    Scene s;
    MeshBuilder mb(s);
    const uint32_t m = groundAnd(mb, random, kGround, "plates");
    const int stacks = random.integer(1, 3);
    for (int k = 0; k < stacks; ++k) {
        const float x = random.uniform(-2.5f, 2.5f);
        const float z = random.uniform(-2.5f, 2.5f);
        const float width = random.uniform(1.2f, 3.0f);
        const bool shelves = random.chance(0.4f);
        const int layers = random.integer(2, 5);
        float y = random.uniform(0.2f, 1.0f);
        for (int i = 0; i < layers; ++i) {
            const float thick = random.logUniform(0.01f, 0.15f);
            const float w = width * random.uniform(0.5f, 1.0f);
            const float d = width * random.uniform(0.4f, 1.0f);
            const float turn = random.uniform(0.0f, 0.5f * glm::pi<float>());
            if (shelves) { // shelves stay square to their posts
                mb.quad({x - w / 2, y, z + d / 2}, {x + w / 2, y, z + d / 2},
                        {x + w / 2, y, z - d / 2}, {x - w / 2, y, z - d / 2}, m);
            } else {
                const glm::mat4 slab = placed({x, y, z}, turn, {w, thick, d});
                mb.box(slab, m);
            }
            y += random.uniform(0.15f, 1.2f);
        }
        if (shelves)
            for (int post = 0; post < 4; ++post) {
                const float px = x + (post & 1 ? 0.5f : -0.5f) * 0.5f * width;
                const float pz = z + (post & 2 ? 0.5f : -0.5f) * 0.4f * width;
                mb.beam({px, 0, pz}, {px, y, pz}, 0.04f, m);
            }
    }
    return finish(std::move(s), random, {});
}

// 1 to 5 spheres (64 x 32 facets) of radius 0.3 to 1.5, resting on the ground or floating up to
// twice their radius above it.
Scene spheres(GenRandom& random) {
    Scene s;
    MeshBuilder mb(s);
    const uint32_t m = groundAnd(mb, random, kGround, "spheres");
    const int count = random.integer(1, 5);
    for (int i = 0; i < count; ++i) {
        const float r = random.uniform(0.3f, 1.5f);
        const float x = random.uniform(-3.0f, 3.0f);
        const float z = random.uniform(-3.0f, 3.0f);
        const float gap = random.chance(0.3f) ? 0.0f : random.uniform(0.05f, 2.0f) * r;
        const glm::vec3 c(x, r + gap, z);
        mb.sphere(c, r, m);
    }
    return finish(std::move(s), random, {});
}

// 5 to 30 leaf cards (alpha-tested quads of a leaf texture drawn from the seed) tilted at random
// heights, and in half the seeds a canopy of tiled leaves on four posts.
Scene leaves(GenRandom& random) {
    Scene s;
    MeshBuilder mb(s);
    const uint32_t wood = groundAnd(mb, random, kGround, "wood");
    const auto texture = static_cast<uint32_t>(random.next());
    const uint32_t leaf =
        mb.texturedMaterial("leaves", builtin::leafImage(texture, random.integer(60, 200)), {},
                            AlphaMode::Mask, builtin::kFoliageAlphaCutoff);
    const int cards = random.integer(5, 30);
    for (int i = 0; i < cards; ++i) {
        const float size = random.uniform(0.4f, 2.0f);
        const float x = random.uniform(-3.0f, 3.0f);
        const float y = random.uniform(0.3f, 3.0f);
        const float z = random.uniform(-3.0f, 3.0f);
        const float tilt = random.uniform(0.0f, 1.4f);
        const float turn = random.uniform(0.0f, 2.0f * glm::pi<float>());
        const glm::mat4 m =
            glm::rotate(glm::rotate(glm::translate(glm::mat4(1.0f), {x, y, z}), turn, {0, 1, 0}),
                        tilt, {1, 0, 0});
        glm::vec3 corner[4];
        for (int k = 0; k < 4; ++k) {
            corner[k] = glm::vec3(m * glm::vec4((k == 1 || k == 2 ? 0.5f : -0.5f) * size, 0.0f,
                                                (k < 2 ? 0.5f : -0.5f) * size, 1.0f));
        }
        mb.quad(corner[0], corner[1], corner[2], corner[3], leaf);
    }
    if (random.chance(0.5f)) {
        const float h = random.uniform(2.0f, 3.5f);
        for (int post = 0; post < 4; ++post)
            mb.beam({post & 1 ? 2.5f : -2.5f, 0, post & 2 ? 2.0f : -2.0f},
                    {post & 1 ? 2.5f : -2.5f, h, post & 2 ? 2.0f : -2.0f}, 0.1f, wood);
        mb.quad({-2.5f, h, 2}, {2.5f, h, 2}, {2.5f, h, -2}, {-2.5f, h, -2}, leaf, {2.0f, 1.6f});
    }
    return finish(std::move(s), random, {});
}

// Open boxes (1 to 3 faces missing), single-sided walls, and closed boxes with some triangles
// wound the wrong way, as exported meshes often are.
Scene open(GenRandom& random) {
    Scene s;
    MeshBuilder mb(s);
    const uint32_t m = groundAnd(mb, random, kGround, "open");
    const int count = random.integer(2, 6);
    for (int i = 0; i < count; ++i) {
        const float w = random.uniform(0.5f, 2.0f);
        const float h = random.uniform(0.3f, 2.5f);
        const float x = random.uniform(-3.0f, 3.0f);
        const float z = random.uniform(-3.0f, 3.0f);
        const float lift = random.chance(0.5f) ? 0.0f : random.uniform(0.1f, 1.5f);
        const int kind = random.integer(0, 2);
        const size_t first = s.indices.size();
        const glm::mat4 box = placed({x, lift + h / 2, z}, random.uniform(0.0f, 1.5f), {w, h, w});
        mb.box(box, m);
        if (kind == 0) { // faces removed: two triangles each
            const int missing = random.integer(1, 3);
            const auto face = static_cast<size_t>(random.integer(0, 6 - missing));
            s.indices.erase(s.indices.begin() + static_cast<std::ptrdiff_t>(first + 6 * face),
                            s.indices.begin() +
                                static_cast<std::ptrdiff_t>(first + 6 * (face + size_t(missing))));
        } else if (kind == 1) { // some triangles wound the wrong way
            for (size_t t = first; t < s.indices.size(); t += 3)
                if (random.chance(0.3f))
                    std::swap(s.indices[t + 1], s.indices[t + 2]);
        } else { // the box replaced by one wall, facing a random way
            s.indices.resize(first);
            const float turn = random.uniform(0.0f, 2.0f * glm::pi<float>());
            const glm::vec3 across(std::cos(turn), 0, std::sin(turn));
            const glm::vec3 foot(x, lift, z);
            mb.quad(foot - across * w, foot + across * w, foot + across * w + glm::vec3(0, h, 0),
                    foot - across * w + glm::vec3(0, h, 0), m);
        }
    }
    return finish(std::move(s), random, {});
}

// Creases and curved tessellation: tori, tubes and spheres of few facets (smooth-shaded, so the
// shading normal leaves the facet's), and corrugated sheets folded along their creases.
Scene curved(GenRandom& random) {
    Scene s;
    MeshBuilder mb(s);
    const uint32_t m = groundAnd(mb, random, kGround, "curved");
    const int count = random.integer(2, 5);
    for (int i = 0; i < count; ++i) {
        const float x = random.uniform(-3.0f, 3.0f);
        const float z = random.uniform(-3.0f, 3.0f);
        const float r = random.uniform(0.3f, 1.2f);
        const float lift = random.chance(0.5f) ? 0.0f : random.uniform(0.1f, 1.0f);
        const glm::vec3 c(x, lift + r, z);
        switch (random.integer(0, 3)) {
        case 0: {
            const auto segments = static_cast<uint32_t>(random.integer(8, 48));
            const auto sides = static_cast<uint32_t>(random.integer(4, 16));
            const float tilt = random.uniform(0.0f, 1.5f);
            mb.torus(c, glm::vec3(std::sin(tilt), std::cos(tilt), 0), r, 0.35f * r, m, segments,
                     sides);
            break;
        }
        case 1: {
            const auto slices = static_cast<uint32_t>(random.integer(5, 24));
            const float h = random.uniform(0.5f, 3.0f);
            mb.tube({x, lift, z}, {x, lift + h, z}, 0.5f * r, m, slices);
            break;
        }
        case 2: {
            const auto slices = static_cast<uint32_t>(random.integer(6, 24));
            mb.sphere(c, r, m, slices, std::max(3u, slices / 2));
            break;
        }
        default: { // a corrugated sheet: strips folded alternately up and down
            const int strips = random.integer(3, 10);
            const float strip = random.uniform(0.1f, 0.4f), fold = random.uniform(0.05f, 0.4f);
            const float length = random.uniform(1.0f, 3.0f);
            const float y = lift + random.uniform(0.3f, 1.5f);
            for (int k = 0; k < strips; ++k) {
                const float x0 = x + strip * static_cast<float>(k);
                const float x1 = x + strip * static_cast<float>(k + 1); // the next strip's x0
                const float y0 = y + (k % 2 ? fold : 0.0f), y1 = y + (k % 2 ? 0.0f : fold);
                mb.quad({x0, y0, z + length / 2}, {x1, y1, z + length / 2},
                        {x1, y1, z - length / 2}, {x0, y0, z - length / 2}, m);
            }
        }
        }
    }
    return finish(std::move(s), random, {});
}

} // namespace penumbra::gen
