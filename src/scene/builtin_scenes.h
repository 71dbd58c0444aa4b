#pragma once
// The built-in scenes, made in code (design.md, issue 2). Their layout is part of the test
// contract: tests compute analytic shadows from the same constants.
#include "penumbra/scene.h"

#include <glm/glm.hpp>

namespace penumbra::builtin {

// Showcase geometry, shared with the analytic tests.
inline constexpr glm::vec3 kSphereCenter{-3.0f, 2.6f, 0.0f};
inline constexpr float kSphereRadius = 1.0f;
inline constexpr float kGroundHalfSize = 12.0f;
inline constexpr glm::vec3 kPoleBase{-0.6f, 0.0f, -0.4f};
inline constexpr glm::vec3 kPoleTip{0.6f, 2.6f, -1.3f};
inline constexpr float kPoleThickness = 0.08f;
// Direction the sun's light travels (normalised when used): about 60 degrees elevation.
inline constexpr glm::vec3 kSunDirection{0.35f, -1.0f, 0.45f};
inline constexpr glm::vec3 kSpotPosition{-5.2f, 11.0f, -6.0f};
inline constexpr glm::vec3 kSpotTarget{0.0f, 0.0f, 0.5f};

// Grazing: a plane lit 85 degrees from its normal, and a low box on it.
inline constexpr float kGrazingAngleDegrees = 85.0f;
inline constexpr glm::vec3 kGrazingBoxCenter{-4.0f, 0.15f, 0.0f};
inline constexpr glm::vec3 kGrazingBoxSize{1.0f, 0.3f, 1.0f};
inline constexpr float kGrazingHalfSize = 20.0f;

Scene showcase();
Scene grazing();
Scene spot();

} // namespace penumbra::builtin
