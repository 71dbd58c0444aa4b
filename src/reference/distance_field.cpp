#include "reference/distance_field.h"

#include "bias.h"
#include "params_sdf.h"
#include "penumbra/error.h"
#include "sdf_math.h"
#include "shadows/technique.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace penumbra {

glm::dvec3 closestPointOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                  const glm::dvec3& c) {
    const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0 && d2 <= 0)
        return a;
    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3)
        return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0)
        return a + ab * (d1 / (d1 - d3));
    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6)
        return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0)
        return a + ac * (d2 / (d2 - d6));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const double sum = va + vb + vc;
    if (!(sum > 0)) // a degenerate triangle: its nearest vertex
        return glm::distance(p, a) <= glm::distance(p, b)
                   ? (glm::distance(p, a) <= glm::distance(p, c) ? a : c)
                   : (glm::distance(p, b) <= glm::distance(p, c) ? b : c);
    return a + ab * (vb / sum) + ac * (vc / sum);
}

double windingContribution(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                           const glm::dvec3& c) {
    const glm::dvec3 x = a - p, y = b - p, z = c - p;
    const double lx = glm::length(x), ly = glm::length(y), lz = glm::length(z);
    const double numerator = glm::dot(x, glm::cross(y, z));
    const double denominator =
        lx * ly * lz + glm::dot(x, y) * lz + glm::dot(y, z) * lx + glm::dot(z, x) * ly;
    // tan(Omega / 2) = numerator / denominator; atan2 keeps the quadrant.
    return 2.0 * std::atan2(numerator, denominator) / (4.0 * std::numbers::pi);
}

FieldSample sampleDistanceField(const Scene& scene, const glm::dvec3& p) {
    FieldSample s{.distance = std::numeric_limits<double>::infinity()};
    for (size_t t = 0; t + 2 < scene.indices.size(); t += 3) {
        const glm::dvec3 a(scene.vertices[scene.indices[t]].position);
        const glm::dvec3 b(scene.vertices[scene.indices[t + 1]].position);
        const glm::dvec3 c(scene.vertices[scene.indices[t + 2]].position);
        s.distance = std::min(s.distance, glm::distance(p, closestPointOnTriangle(p, a, b, c)));
        s.winding += windingContribution(p, a, b, c);
    }
    return s;
}

float FieldGrid::sample(const glm::vec3& p) const {
    const glm::vec3 g =
        glm::clamp((p - origin) / voxel - 0.5f, glm::vec3(0.0f), glm::vec3(size) - 1.0f);
    const glm::uvec3 lo(glm::floor(g));
    const glm::uvec3 hi = glm::min(lo + 1u, size - 1u);
    const glm::vec3 f = g - glm::vec3(lo);
    auto at = [&](uint32_t x, uint32_t y, uint32_t z) {
        return values[(size_t{z} * size.y + y) * size.x + x];
    };
    auto alongX = [&](uint32_t y, uint32_t z) {
        return at(lo.x, y, z) + f.x * (at(hi.x, y, z) - at(lo.x, y, z));
    };
    const float y0 = alongX(lo.y, lo.z) + f.y * (alongX(hi.y, lo.z) - alongX(lo.y, lo.z));
    const float y1 = alongX(lo.y, hi.z) + f.y * (alongX(hi.y, hi.z) - alongX(lo.y, hi.z));
    return y0 + f.z * (y1 - y0);
}

bool FieldGrid::contains(const glm::vec3& p) const {
    const glm::vec3 extent = voxel * glm::vec3(size);
    return glm::all(glm::greaterThanEqual(p, origin)) &&
           glm::all(glm::lessThanEqual(p, origin + extent));
}

TraceSettings traceSettingsOf(const shadows::TechniqueModule& module,
                              const ParameterValues& parameters) {
    PENUMBRA_CHECK(module.tracedField.has_value(),
                   std::string(module.info.name) + " traces no distance field");
    shadows::ParamBlock block;
    module.pack(parameters, block);
    const gpu::SdfParams sdf = block.get<gpu::SdfParams>();
    bool horizon = false;
    for (const shadows::SpecConstant& c : shadows::visibilityConstants(module, parameters))
        if (c.id == SPEC_HORIZON)
            horizon = c.value != 0;
    return {.steps = static_cast<uint32_t>(sdf.steps),
            .startOffset = sdf.startOffset,
            .k = sdf.k,
            .minStep = sdf.minStep,
            .thickness = sdf.thickness,
            .horizon = horizon};
}

namespace {

// shadow_sdf.glsl's acrossField on the CPU.
float acrossField(const FieldGrid& field, const glm::vec3& p, const glm::vec3& toLight, float h,
                  float r) {
    const float e = 0.5f * field.voxel;
    glm::vec3 g(0.0f);
    for (int axis = 0; axis < 3; ++axis) {
        glm::vec3 d(0.0f);
        d[axis] = e;
        g[axis] = field.sample(p + d) - field.sample(p - d);
    }
    const glm::vec3 n = glm::dot(g, g) > 0.0f ? glm::normalize(g) : toLight;
    glm::vec4 probes;
    for (int k = 0; k < 4; ++k) {
        const glm::vec3 q = gpu::acrossProbe(p, toLight, n, r, k);
        probes[k] = field.contains(q) ? field.sample(q) : r;
    }
    return gpu::acrossEdge(h, probes);
}

} // namespace

float traceFieldVisibility(const FieldGrid& field, const Light& light, const glm::vec3& world,
                           const glm::vec3& face, const TraceSettings& s) {
    glm::vec3 toLight;
    float reach = std::numeric_limits<float>::max(), sinRadius = 0.0f;
    if (light.type == LightType::Directional) {
        toLight = -glm::normalize(light.direction);
        sinRadius = std::sin(glm::radians(0.5f * light.angularDiameter));
    } else {
        const glm::vec3 offset = light.position - world;
        const float distance = glm::length(offset);
        toLight = offset / std::max(distance, 1e-20f);
        sinRadius = std::min(light.radius / std::max(distance, 1e-6f), 1.0f);
        reach = distance * (1.0f - sinRadius);
    }
    gpu::ConeTrace c{.edge = 1.0f, .t = 0.0f, .previous = -1.0f, .step = 0.0f};
    if (s.horizon && (sinRadius > 0.0f || s.k > 0.0f))
        c.edge = gpu::coneEdge(glm::dot(face, toLight), 1.0f, sinRadius, s.k);
    if (c.edge <= -1.0f)
        return 0.0f;
    float apex = 0.0f;
    const glm::vec3 origin =
        gpu::traceStart(world, face, toLight, s.startOffset * field.voxel, apex);
    const glm::vec3 up = glm::dot(face, toLight) < 0.0f ? -face : face;
    for (uint32_t i = 0; i < s.steps && c.t < reach - apex; ++i) {
        const glm::vec3 p = origin + c.t * toLight;
        if (!field.contains(p))
            break;
        const float h = field.sample(p);
        const bool own =
            s.horizon && gpu::ownSurface(h, glm::dot(p - world, up), s.thickness * field.voxel,
                                         0.05f * field.voxel);
        float across = 1.0f;
        if (h < 0.0f && !own && (sinRadius > 0.0f || s.k > 0.0f))
            across = acrossField(field, p, toLight, h, gpu::coneRadius(c.t + apex, sinRadius, s.k));
        if (!gpu::coneTraceStep(c, h, apex, sinRadius, s.k, s.minStep * field.voxel, own, across))
            return 0.0f;
    }
    return gpu::discFraction(c.edge);
}

} // namespace penumbra
