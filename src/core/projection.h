#pragma once
// Penumbra's coordinate conventions, in one place (docs/architecture.md repeats them):
//  - World and view spaces are right-handed, +Y up; a view looks down its -Z axis.
//  - Matrices act on column vectors (p' = M p, GLM's layout). The seeds write row vectors
//    (p' = p M), so their printed matrices are the transposes of these.
//  - Clip space is Vulkan's: NDC x right, y DOWN (y = -1 is the framebuffer's first row),
//    depth in [0, 1].
//  - Light projections keep the seeds' depth: near -> 0, far -> 1, and a point p is lit when
//    d(p) <= s(p). They do not flip y, so shadow-map row 0 is NDC y = -1 and the texture matrix
//    is u = x/2 + 1/2, v = y/2 + 1/2 (the seeds' -1/2 belongs to D3D, whose NDC y points up).
//  - The camera uses reverse-Z (near -> 1, far -> 0: floats are densest near 0, where distant
//    depths land) and flips y so that world-up is image-up.
#include "penumbra/scene.h"

#include <glm/glm.hpp>

namespace penumbra {

// Right-handed view matrix: eye at the origin, looking down -Z, `up` projected to +Y.
glm::mat4 lookAt(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up);

// The seeds' orthographic box, generalised to an off-centre window: view-space
// [l, r] x [b, t] x (distance -z in [n, f]) -> NDC [-1, 1]^2 x [0, 1].
glm::mat4 orthographic(float l, float r, float b, float t, float n, float f);

// Perspective frustum for lights: distance -z in [n, f] -> depth [0, 1], no y flip.
glm::mat4 perspectiveLight(float yfov, float aspect, float n, float f);

// Perspective for the camera: reverse-Z (n -> 1, f -> 0) and y flipped.
glm::mat4 perspectiveCameraReverseZ(float yfov, float aspect, float n, float f);

// Orthographic camera, reverse-Z and y flipped like the perspective one: view-space
// [-ymag aspect, ymag aspect] x [-ymag, ymag] x (distance in [n, f]) -> NDC, depth 1 at n.
glm::mat4 orthographicCameraReverseZ(float ymag, float aspect, float n, float f);

// The camera's projection (perspective or orthographic, reverse-Z, y flipped) and its world ->
// clip matrix (projection x view, as the G-buffer pass draws it) for an image of width / height
// `aspect`.
glm::mat4 cameraProjection(const Camera& camera, float aspect);
glm::mat4 cameraViewProj(const Camera& camera, float aspect);

// T: NDC -> shadow-map texture space, (x, y, z) -> (x/2 + 1/2, y/2 + 1/2, z).
glm::mat4 textureMatrix();

} // namespace penumbra
