#pragma once
// The rule dropInvalidTriangles (penumbra/scene.h) keeps a triangle by: finite corners within
// kMaxCoordinate and an area above zero (in double). The loader counts what it will drop with it.
#include <glm/glm.hpp>

namespace penumbra {

bool triangleIsUsable(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);

} // namespace penumbra
