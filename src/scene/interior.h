#pragma once
// Defaults for a glTF scene that brings no lights or no camera, chosen so that interiors are lit
// and seen from inside (issue 16). The rule (README, "Scenes without lights or cameras"):
// - A scene is an interior when rays from its bounds' centre along -y, +x, -x, +z and -z all
//   meet the front of a surface (the inside of walls and the floor). The sky above may be open;
//   from inside a closed model the rays meet back faces, so a lone model is not an interior.
// - An interior's automatic camera stands at that centre and looks along the bounds' longer
//   horizontal axis, 70 degrees of vertical field of view.
// - Without lights, an interior whose centre the default sun cannot reach gets a point light
//   instead, above the centre half way to the ceiling (or the bounds' top), as bright on the
//   floor below it as the default sun would be.
#include "penumbra/scene.h"

#include <optional>

namespace penumbra {

// The loader's stand-in when an asset has no lights: a sun from above and slightly behind.
Light defaultSun();

// The distance to the first triangle along a ray and whether it is met from its front (by its
// winding); nullopt for a miss. Brute force: for the few rays of the rules above, once per load.
struct RayHit {
    float distance = 0.0f;
    bool front = false;
};
std::optional<RayHit> firstHit(const Scene& scene, const glm::vec3& origin, const glm::vec3& dir);

bool isInterior(const Scene& scene);
Camera interiorCamera(const Scene& scene);
// The default light for a scene without lights: defaultSun(), or for an interior it cannot
// light, the point light of the rule above.
Light defaultLightFor(const Scene& scene);

} // namespace penumbra
