#pragma once
// The CPU reference of the `sdf` technique's field (issue 13): the exact distance from a point to
// a scene's triangles, signed by the generalised winding number [Jacobson et al. 2013] where the
// geometry is closed. The GPU field builder is checked against it; it is a brute-force loop over
// every triangle, for tests and small scenes only.
#include "penumbra/scene.h"

#include <glm/glm.hpp>

namespace penumbra {

// The point of triangle (a, b, c) closest to p [Ericson, Real-Time Collision Detection, 5.1.5]:
// by the Voronoi region of p among the triangle's vertices, edges and face.
glm::dvec3 closestPointOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                  const glm::dvec3& c);

// The solid angle triangle (a, b, c) subtends at p over 4 pi [Van Oosterom and Strackee 1983],
// positive when p lies behind it (on the side its normal (b - a) x (c - a) points away from).
// Summed over a closed mesh wound counter-clockwise seen from outside: 1 inside, 0 outside.
double windingContribution(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                           const glm::dvec3& c);

struct FieldSample {
    double distance = 0; // to the nearest triangle, >= 0
    double winding = 0;  // generalised winding number of the whole scene at the point
    // Negative inside closed geometry (winding above one half), positive elsewhere.
    double signedDistance() const { return winding > 0.5 ? -distance : distance; }
};

FieldSample sampleDistanceField(const Scene& scene, const glm::dvec3& p);

} // namespace penumbra
