#include "reference/embree_scene.h"

#include "core/fault_injection.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <utility>

namespace penumbra {
namespace {

const char* errorName(RTCError code) {
    switch (code) {
    case RTC_ERROR_NONE:
        return "no error";
    case RTC_ERROR_UNKNOWN:
        return "unknown error";
    case RTC_ERROR_INVALID_ARGUMENT:
        return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
        return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
        return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
        return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
        return "cancelled";
    }
    return "error";
}

void onEmbreeError(void* user, RTCError code, const char* message) {
    auto* error = static_cast<std::string*>(user);
    if (error->empty())
        *error = fmt::format("{} ({})", message ? message : "", errorName(code));
}

// Rejects a hit in a hole of an alpha-tested triangle (Embree's barycentrics u, v weight the
// second and third vertices).
void skipHoles(const RTCFilterFunctionNArguments* args) {
    const auto& data = *static_cast<const EmbreeScene::FilterData*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1)
            continue;
        const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
        const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
        const EmbreeScene::FilteredTriangle& t = data.triangles[prim];
        const float w = 1.0f - u - v;
        const glm::vec2 uv = w * t.uv[0] + u * t.uv[1] + v * t.uv[2];
        const float alpha = w * t.color[0].w + u * t.color[1].w + v * t.color[2].w;
        if (!data.scene->covers(t.material, uv, alpha))
            args->valid[i] = 0;
    }
}

// The context of a shadow ray's occlusion query: what it has kept so far, and the translucent
// triangles it crossed and where. With RTC_BUILD_QUALITY_HIGH Embree may report one triangle more
// than once (spatial splits put it in several leaves), so each counts once; and a ray through
// the edge or corner triangles share meets each at one point, where it crosses the surface once.
struct TransmittanceContext {
    RTCIntersectContext base; // first: Embree hands the filters a pointer to it
    glm::vec3 through{1.0f};
    std::array<unsigned, 64> crossed; // the first crossedCount are set
    std::array<float, 64> distance;   // where the ray met each
    unsigned crossedCount = 0;
};
static_assert(std::is_standard_layout_v<TransmittanceContext>);

glm::vec3 transmittanceAt(const EmbreeScene::FilterData& data, unsigned prim, float u, float v) {
    const EmbreeScene::FilteredTriangle& t = data.triangles[prim];
    const float w = 1.0f - u - v;
    return data.scene->transmittance(t.material, w * t.uv[0] + u * t.uv[1] + v * t.uv[2],
                                     w * t.color[0] + u * t.color[1] + v * t.color[2]);
}

// Whether two triangles have a corner at the same place.
bool shareCorner(const EmbreeScene::FilteredTriangle& a, const EmbreeScene::FilteredTriangle& b) {
    int shared = 0;
    for (const glm::vec3& p : a.corner)
        shared += std::find(std::begin(b.corner), std::end(b.corner), p) != std::end(b.corner);
    return shared >= 1;
}

// Whether hits at distances ta and tb on triangles a and b are one crossing of the surface: the
// same point (one distance, to 1e-5 of it or of 1) on triangles with a corner in common.
bool sameCrossing(float ta, const EmbreeScene::FilteredTriangle& a, float tb,
                  const EmbreeScene::FilteredTriangle& b) {
    return std::abs(ta - tb) <= 1e-5f * std::max(ta, 1.0f) && shareCorner(a, b);
}

// Whether the ray has crossed this point of the surface already: a triangle with a corner in
// common met at the same distance, so at the same point (the same triangle reported twice, or
// the ray passing through the edge or corner two share; separate layers that merely touch count
// twice).
bool crossedAlready(const TransmittanceContext& context, const EmbreeScene::FilterData& data,
                    unsigned prim, float t) {
    for (unsigned k = 0; k < context.crossedCount; ++k) {
        const unsigned other = context.crossed[k];
        if (sameCrossing(t, data.triangles[prim], context.distance[k], data.triangles[other]))
            return true;
    }
    return false;
}

// Occlusion queries: a translucent hit multiplies what the ray keeps and is rejected, so the ray
// goes on, until nothing is left (then it stops there: occluded).
void throughTranslucent(const RTCFilterFunctionNArguments* args) {
    const auto& data = *static_cast<const EmbreeScene::FilterData*>(args->geometryUserPtr);
    auto* context = reinterpret_cast<TransmittanceContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1)
            continue;
        const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
        const float t = RTCRayN_tfar(args->ray, args->N, i); // the hit's distance, in a filter
        const glm::vec3 through = transmittanceAt(data, prim, RTCHitN_u(args->hit, args->N, i),
                                                  RTCHitN_v(args->hit, args->N, i));
        // A clear hit (a card's empty border) changes nothing: it takes no place in the list.
        if (glm::all(glm::greaterThanEqual(through, glm::vec3(1.0f))) ||
            crossedAlready(*context, data, prim, t)) {
            args->valid[i] = 0;
            continue;
        }
        if (context->crossedCount < context->crossed.size()) { // past 64 layers, little is left
            context->distance[context->crossedCount] = t;
            context->crossed[context->crossedCount++] = prim;
        }
        context->through *= through;
        if (glm::any(glm::greaterThan(context->through, glm::vec3(0.0f))))
            args->valid[i] = 0;
    }
}

// Nearest-hit queries (the occluder's distance, the receiver's face): a translucent surface is
// hit where it keeps any light back.
void skipClear(const RTCFilterFunctionNArguments* args) {
    const auto& data = *static_cast<const EmbreeScene::FilterData*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i)
        if (args->valid[i] == -1 &&
            glm::all(glm::greaterThanEqual(
                transmittanceAt(data, RTCHitN_primID(args->hit, args->N, i),
                                RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i)),
                glm::vec3(1.0f))))
            args->valid[i] = 0;
}

// Embree asks before each allocation; refusing one makes it fail with RTC_ERROR_OUT_OF_MEMORY,
// which is how PENUMBRA_FAULT=embree:N tests the truth's out-of-memory path.
bool allowAllocation(void* /*user*/, ssize_t bytes, bool /*post*/) {
    return bytes <= 0 || !injectFault(FaultSite::Embree);
}

} // namespace

void EmbreeScene::addGeometry(const Scene& scene, const std::vector<uint32_t>& triangles,
                              Kind kind) {
    if (triangles.empty())
        return;
    RTCGeometry geometry = rtcNewGeometry(mDevice, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* positions = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), scene.vertices.size()));
    auto* indices = static_cast<uint32_t*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(uint32_t), triangles.size()));
    if (!positions || !indices) { // out of memory: the error function has the reason
        if (geometry)
            rtcReleaseGeometry(geometry);
        throwIfFailed("allocating geometry buffers");
    }
    for (size_t i = 0; i < scene.vertices.size(); ++i)
        std::memcpy(positions + 3 * i, &scene.vertices[i].position, 3 * sizeof(float));
    for (size_t k = 0; k < triangles.size(); ++k)
        std::memcpy(indices + 3 * k, scene.indices.data() + 3 * size_t{triangles[k]},
                    3 * sizeof(uint32_t));
    if (kind != Kind::Opaque) {
        FilterData& data = kind == Kind::Translucent ? mTranslucent : mFilter;
        data.scene = &scene;
        for (uint32_t t : triangles) {
            FilteredTriangle filtered{.material = scene.vertices[scene.indices[3 * t]].material};
            for (int c = 0; c < 3; ++c) {
                const Vertex& v = scene.vertices[scene.indices[3 * size_t{t} + c]];
                filtered.uv[c] = v.uv;
                filtered.color[c] = v.color;
                filtered.corner[c] = v.position;
            }
            data.triangles.push_back(filtered);
        }
        rtcSetGeometryUserData(geometry, &data);
    }
    if (kind == Kind::Translucent) {
        rtcSetGeometryOccludedFilterFunction(geometry, throughTranslucent);
        rtcSetGeometryIntersectFilterFunction(geometry, skipClear);
    }
    if (kind == Kind::AlphaTested) {
        rtcSetGeometryOccludedFilterFunction(geometry, skipHoles);
        rtcSetGeometryIntersectFilterFunction(geometry, skipHoles);
    }
    rtcCommitGeometry(geometry);
    const unsigned id = rtcAttachGeometry(mScene, geometry);
    if (kind == Kind::Translucent)
        mTranslucentGeometry = id;
    rtcReleaseGeometry(geometry);
}

EmbreeScene::EmbreeScene(const Scene& scene, const std::string& config) {
    mDevice = rtcNewDevice(config.c_str());
    if (!mDevice)
        throw std::runtime_error(fmt::format("embree: cannot create a device with configuration "
                                             "'{}' ({})",
                                             config, errorName(rtcGetDeviceError(nullptr))));
    rtcSetDeviceErrorFunction(mDevice, onEmbreeError, &mError);
    rtcSetDeviceMemoryMonitorFunction(mDevice, allowAllocation, nullptr);
    try { // the destructor does not run for a constructor that throws
        build(scene);
    } catch (...) {
        release();
        throw;
    }
}

void EmbreeScene::build(const Scene& scene) {
    mScene = rtcNewScene(mDevice);
    throwIfFailed("creating the scene");
    rtcSetSceneBuildQuality(mScene, RTC_BUILD_QUALITY_HIGH);
    mTriangles = scene.triangleCount();
    std::vector<uint32_t> opaque, tested, translucent;
    for (size_t t = 0; t < mTriangles; ++t) {
        const uint32_t m = scene.vertices[scene.indices[3 * t]].material;
        const Material* material = m < scene.materials.size() ? &scene.materials[m] : nullptr;
        (material && material->translucent()   ? translucent
         : material && material->alphaTested() ? tested
                                               : opaque)
            .push_back(static_cast<uint32_t>(t));
    }
    addGeometry(scene, opaque, Kind::Opaque);
    addGeometry(scene, tested, Kind::AlphaTested);
    addGeometry(scene, translucent, Kind::Translucent);
    rtcCommitScene(mScene);
    throwIfFailed("building the scene");
}

EmbreeScene::~EmbreeScene() {
    release();
}

void EmbreeScene::release() noexcept {
    if (mScene)
        rtcReleaseScene(std::exchange(mScene, nullptr));
    if (mDevice)
        rtcReleaseDevice(std::exchange(mDevice, nullptr));
}

void EmbreeScene::throwIfFailed(const char* what) const {
    const RTCError code = rtcGetDeviceError(mDevice);
    if (code == RTC_ERROR_NONE && mError.empty())
        return;
    throw std::runtime_error(
        fmt::format("embree: {}: {}", what, mError.empty() ? errorName(code) : mError));
}

namespace {

RTCRay rayOf(const glm::vec3& origin, const glm::vec3& dir, float tnear, float tfar) {
    return {.org_x = origin.x,
            .org_y = origin.y,
            .org_z = origin.z,
            .tnear = tnear,
            .dir_x = dir.x,
            .dir_y = dir.y,
            .dir_z = dir.z,
            .time = 0.0f,
            .tfar = tfar,
            .mask = std::numeric_limits<unsigned>::max(),
            .id = 0,
            .flags = 0};
}

} // namespace

bool EmbreeScene::occluded(const glm::vec3& origin, const glm::vec3& dir, float tnear,
                           float tfar) const {
    TransmittanceContext context; // the translucent filter's: it stops where nothing is left
    rtcInitIntersectContext(&context.base);
    RTCRay ray = rayOf(origin, dir, tnear, tfar);
    rtcOccluded1(mScene, &context.base, &ray);
    return ray.tfar < 0.0f; // Embree sets tfar to -inf on a hit
}

glm::vec3 EmbreeScene::transmittance(const glm::vec3& origin, const glm::vec3& dir, float tnear,
                                     float tfar) const {
    TransmittanceContext context;
    rtcInitIntersectContext(&context.base);
    RTCRay ray = rayOf(origin, dir, tnear, tfar);
    rtcOccluded1(mScene, &context.base, &ray);
    return ray.tfar < 0.0f ? glm::vec3(0.0f) : context.through;
}

EmbreeScene::SurfacesAlong EmbreeScene::surfacesAlong(const glm::vec3& origin, const glm::vec3& dir,
                                                      float tnear, float tfar) const {
    SurfacesAlong out{.opaque = tfar};
    unsigned last = 0;           // the last translucent triangle met
    for (float from = tnear;;) { // peel: the nearest surface that keeps light back, then past it
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit hit{.ray = rayOf(origin, dir, from, tfar),
                      .hit = {.geomID = RTC_INVALID_GEOMETRY_ID}};
        rtcIntersect1(mScene, &context, &hit);
        if (hit.hit.geomID == RTC_INVALID_GEOMETRY_ID)
            return out;
        const float t = hit.ray.tfar;
        if (hit.hit.geomID != mTranslucentGeometry) {
            out.opaque = t;
            return out;
        }
        // The crossing the occlusion filter would count once (a shared edge or corner) is one.
        if (out.translucent.empty() ||
            !sameCrossing(t, mTranslucent.triangles[hit.hit.primID],
                          out.translucent.back().distance, mTranslucent.triangles[last]))
            out.translucent.push_back({.distance = t,
                                       .transmittance = transmittanceAt(
                                           mTranslucent, hit.hit.primID, hit.hit.u, hit.hit.v)});
        last = hit.hit.primID;
        from = std::nextafter(t, std::numeric_limits<float>::infinity()); // past this hit alone
    }
}

float EmbreeScene::hitDistance(const glm::vec3& origin, const glm::vec3& dir, float tnear,
                               float tfar) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit hit{.ray = rayOf(origin, dir, tnear, tfar),
                  .hit = {.geomID = RTC_INVALID_GEOMETRY_ID}};
    rtcIntersect1(mScene, &context, &hit);
    return hit.hit.geomID == RTC_INVALID_GEOMETRY_ID ? std::numeric_limits<float>::infinity()
                                                     : hit.ray.tfar;
}

glm::vec3 EmbreeScene::surfaceNormal(const glm::vec3& p, const glm::vec3& n, float reach) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    const glm::vec3 origin = p + n * reach;
    RTCRayHit hit{.ray = rayOf(origin, -n, 0.0f, 2.0f * reach),
                  .hit = {.geomID = RTC_INVALID_GEOMETRY_ID}};
    rtcIntersect1(mScene, &context, &hit);
    if (hit.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        return n;
    const glm::vec3 face(hit.hit.Ng_x, hit.hit.Ng_y, hit.hit.Ng_z);
    const float length = glm::length(face);
    if (!(length > 0.0f))
        return n;
    return glm::dot(face, n) < 0.0f ? -face / length : face / length;
}

} // namespace penumbra
