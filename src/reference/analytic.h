#pragma once
// Closed-form visibility for a sphere occluder, the pbrt-style checks of the ground truth:
// the solid angle two spherical caps share, and from it the visible fraction of a spherical or
// directional light behind a sphere.
#include <glm/glm.hpp>

#include <cmath>

namespace penumbra::analytic {

// Solid angle of the intersection of two caps of angular radii a1, a2 (radians, each < pi/2)
// whose centres are `gamma` apart on the unit sphere.
double capIntersection(double a1, double a2, double gamma);
inline double capArea(double a) {
    return 2.0 * 3.14159265358979323846 * (1.0 - std::cos(a));
}

// Visible fraction of a cone of directions (axis, half-angle alpha; uniform in solid angle)
// seen from p past a sphere (centre, radius) that lies between p and the light.
double coneVisibilityPastSphere(const glm::dvec3& p, const glm::dvec3& axis, double alpha,
                                const glm::dvec3& center, double radius);

} // namespace penumbra::analytic
