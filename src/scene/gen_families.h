#pragma once
// The generated families' builders (scene/generated.h) and what they share: a light drawn from
// the seed, a camera round the content.
#include "scene/generated.h"
#include "scene/mesh_builder.h"

namespace penumbra::gen {

// Which lights a family may draw, and how high its suns stand (degrees above the horizon).
struct LightChoice {
    bool sun = true, spot = true, point = true;
    float lowestSun = 25.0f, highestSun = 70.0f;
};

// A light over `content`: a sun (angular diameter 0, or 0.25 to 8 degrees), a spot from above
// (its cone holding the content, radius 0 or up to a tenth of the content's size) or a bulb
// above it (likewise); as bright on the content as the default sun. One in five has no size.
Light drawLight(GenRandom& random, const Bounds& content, const LightChoice& choice);
// A camera round `content`, from a random side, 15 to 50 degrees up (`lowest` to `highest`),
// as near as keeps the content in view: of 4 drawn, the one that shows the most cast shadow of
// the scene's first light (measured with rays, scene/first_picture.h).
Camera orbitCamera(GenRandom& random, const Scene& scene, const Bounds& content,
                   float lowest = 15.0f, float highest = 50.0f);
// A ground quad of half-size `half` at height 0, facing up, of a drawn colour; returns a material
// of another drawn colour named `objects`, for what stands on it.
uint32_t groundAnd(MeshBuilder& mb, GenRandom& random, float half, const std::string& objects);
// The box from (-half, 0, -half) to (half, height, half): the content's footprint.
Bounds footprint(float half, float height = 0.0f);
// The vertices groundAnd adds first: one quad.
inline constexpr size_t kGroundVertices = 4;
// What the light and the camera hold: `around` grown by every vertex after the ground's.
Bounds contentOf(const Scene& scene, Bounds around);
// A drawn grey-ish colour, so that materials differ between seeds.
glm::vec3 drawColor(GenRandom& random);

Scene plates(GenRandom& random);
Scene spheres(GenRandom& random);
Scene leaves(GenRandom& random);
Scene open(GenRandom& random);
Scene curved(GenRandom& random);
Scene interior(GenRandom& random);
Scene grazing(GenRandom& random);
Scene longView(GenRandom& random);
Scene clutter(GenRandom& random);

} // namespace penumbra::gen
