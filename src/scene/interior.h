#pragma once
// Exterior or interior, and the default light (docs/scenes.md, "Scenes without lights or
// cameras"). Measured with rays, once per load:
// - A room point is a point of the subject (a 5 x 5 grid, at a quarter and half its height) from
//   which the ray straight down and at least 7 of 8 horizontal rays meet the front of a surface
//   (a floor, the inside of walls; one doorway may let a ray out, the sky above may be open).
//   Inside a closed model the rays meet back faces: a solid box has no room points.
// - Exterior rays look at the subject from 8 sides, 15 degrees above the horizon.
// - A scene is an interior when it has a room point wider than a twentieth of the subject whose
//   walls span at least half the subject's footprint, and fewer than half the exterior rays that
//   meet a surface meet its front: walls modelled to be seen from inside. A building with its
//   rooms modelled has fronts outside too, and an inside-out box on a wide ground (a mis-wound
//   model) spans little of it: both exterior.
// - An interior's automatic camera stands at the most open room point (the largest clearance to
//   the nearest wall; of equals, the nearest to the subject's centre) and looks along its longest
//   horizontal free line, 70 degrees of vertical view.
// - The standard default light is a sun from the camera's front left, 45 degrees up, so that cast
//   shadows fall to the right and away, in view. An interior whose camera the sun cannot reach
//   gets a point light instead, half way to the ceiling above the camera (or the bounds' top),
//   as bright on the floor below it as the sun would be.
#include "penumbra/scene.h"
#include "scene/framing.h"

#include <optional>

namespace penumbra {

struct RoomPoint {
    glm::vec3 position{0.0f};
    glm::vec3 along{1.0f, 0.0f, 0.0f}; // the longest free horizontal line from it
    float openness = 0.0f;             // the shortest horizontal free distance
    float coverage = 0.0f; // the share of the subject's footprint its walls span (seen from above)
};

struct ViewMeasure {
    float exteriorFront = 1.0f;    // of the exterior rays that met a surface, the share of fronts
    std::optional<RoomPoint> room; // the most open room point
    float subjectWidth = 0.0f;
    bool interior() const;
};
ViewMeasure measureView(const Scene& scene, const Bounds& subject);

bool isInterior(const Scene& scene);
// Stands at `measure`'s room point, or lacking one at the subject's centre looking along its
// longer horizontal side.
Camera interiorCamera(const Scene& scene, const ViewMeasure& measure, const Bounds& subject);
Camera interiorCamera(const Scene& scene);
// Exterior or interior as `choice` says, or as measured for ViewChoice::Auto; named
// "auto (exterior)" or "auto (interior)".
Camera automaticCamera(const Scene& scene, ViewChoice choice);

// The stand-in sun for a scene without lights, placed for a camera as above.
Light defaultSun(const Camera& camera = Camera{});
// defaultSun(camera), or for an interior camera the sun cannot reach, the point light above.
Light standardLightFor(const Scene& scene, const Camera& camera, bool interior);
// The standard light, or when it shows too little cast shadow in the camera's view, a better
// placed one (scene/first_picture.h).
Light defaultLightFor(const Scene& scene, const Camera& camera, bool interior);

} // namespace penumbra
