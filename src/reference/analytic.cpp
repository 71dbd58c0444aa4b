#include "reference/analytic.h"

#include <algorithm>
#include <cmath>

namespace penumbra::analytic {

// Spherical-lune formula for two overlapping caps (see e.g. Tovchigrechko & Vakser 2001):
// 2 [pi - acos((cg - c1 c2)/(s1 s2)) - c1 acos((c2 - cg c1)/(sg s1)) - c2 acos((c1 - cg c2)/(sg
// s2))]
double capIntersection(double a1, double a2, double gamma) {
    constexpr double pi = 3.14159265358979323846;
    if (gamma >= a1 + a2)
        return 0.0;
    if (gamma <= std::abs(a1 - a2))
        return capArea(std::min(a1, a2));
    const double c1 = std::cos(a1), c2 = std::cos(a2), cg = std::cos(gamma);
    const double s1 = std::sin(a1), s2 = std::sin(a2), sg = std::sin(gamma);
    auto acosClamped = [](double x) { return std::acos(std::clamp(x, -1.0, 1.0)); };
    return 2.0 * (pi - acosClamped((cg - c1 * c2) / (s1 * s2)) -
                  c1 * acosClamped((c2 - cg * c1) / (sg * s1)) -
                  c2 * acosClamped((c1 - cg * c2) / (sg * s2)));
}

double coneVisibilityPastSphere(const glm::dvec3& p, const glm::dvec3& axis, double alpha,
                                const glm::dvec3& center, double radius) {
    const glm::dvec3 toCenter = center - p;
    const double d = glm::length(toCenter);
    const double beta = std::asin(std::min(radius / d, 1.0));
    const double gamma = std::acos(std::clamp(glm::dot(toCenter / d, axis), -1.0, 1.0));
    if (alpha <= 0.0)
        return gamma < beta ? 0.0 : 1.0;
    return 1.0 - capIntersection(alpha, beta, gamma) / capArea(alpha);
}

} // namespace penumbra::analytic
