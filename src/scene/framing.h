#pragma once
// What the automatic camera of a scene without cameras looks at, and from where (docs/scenes.md,
// "Scenes without lights or cameras"):
// - The subject is the geometry near the bulk of the scene: per axis, the 5th to 95th percentile
//   of the triangles' corners, grown by a quarter of its diagonal (the region). Triangles
//   wholly outside the region (sky planes, far outliers) do not count; one longer than the
//   region's diagonal that crosses it (a huge ground) counts only inside it.
// - An exterior view looks at the subject's centre from the front-right (30 degrees round from
//   +z), 20 degrees above the horizon for a compact subject and up to 50 degrees for a flat one
//   (a level), as near as keeps the subject's box inside a 16:9 view.
#include "penumbra/scene.h"
#include "scene/ray_cast.h"

#include <cstddef>
#include <optional>

namespace penumbra {

Bounds subjectBounds(const Scene& scene);
// The exposure (EV) a scene is shaded with when composite.exposure is not set: 0 when its
// brightest light's irradiance at the subject's centre (a sun's intensity; a spot's or point
// light's intensity / d^2, d at least a tenth of the subject's radius) is within a factor 4 of
// the default sun's (2), as in scenes authored for display; else log2(2 / irradiance), to half a
// stop: photometric lights (lux, candela) come out as bright as the default sun.
float automaticExposure(const Scene& scene);
Camera exteriorCamera(const Scene& scene, const Bounds& subject);
// Near and far planes that hold the whole scene seen from `position` (the far plane 1.1 times
// the farthest corner of its box, the near one 1e-4 of that): a camera placed by a rule or by
// --camera-pos.
glm::vec2 depthRangeFrom(const Scene& scene, const glm::vec3& position);

// Camera `index` when it is the file's own (an animation may move it): none for an index past
// the cameras or below 0, or a camera Penumbra framed (`automatic`, held at the first frame's
// view).
std::optional<size_t> ownCamera(const Scene& scene, int index);

} // namespace penumbra
