#pragma once
// An Embree device and scene built from exactly the triangles the rasterizer draws. Embree
// reports errors through a callback; they surface here as std::runtime_error("embree: ..."),
// never as a crash or a silent wrong answer. Alpha-tested triangles (glTF MASK) sit in a second
// geometry whose occlusion filter rejects hits in their holes, with the test the GPU makes;
// translucent ones (BLEND, transmission) in a third, whose filter multiplies a shadow ray's
// transmittance by each surface's (Scene::transmittance) and lets it go on until nothing is left.
// The Scene must outlive the EmbreeScene.
#include "penumbra/scene.h"

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace penumbra {

class EmbreeScene {
public:
    EmbreeScene(const Scene& scene, const std::string& config);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    // Whether anything blocks the open segment origin + t dir, tnear < t < tfar (translucent
    // surfaces block it where together they let nothing through).
    bool occluded(const glm::vec3& origin, const glm::vec3& dir, float tnear, float tfar) const;
    // The fraction of light (linear RGB) that crosses the segment: the product of the
    // transmittances of every translucent surface on it, 0 where an opaque one is.
    glm::vec3 transmittance(const glm::vec3& origin, const glm::vec3& dir, float tnear,
                            float tfar) const;
    // Whether the scene has translucent triangles (else transmittance is 0 or 1: occluded).
    bool translucent() const { return !mTranslucent.triangles.empty(); }
    // A ray's translucent surfaces up to the first opaque one: what an ideal (deep) shadow map
    // keeps along a texel's ray [Lokovic and Veach 2000], which the translucent techniques' maps
    // compress. Surfaces that let everything through are left out; a crossing of triangles with
    // a corner in common at one distance counts once, as in `transmittance`.
    struct CrossedSurface {
        float distance;
        glm::vec3 transmittance;
    };
    struct SurfacesAlong {
        std::vector<CrossedSurface> translucent; // nearest first
        float opaque;                            // the first opaque hit's distance, or tfar
    };
    SurfacesAlong surfacesAlong(const glm::vec3& origin, const glm::vec3& dir, float tnear,
                                float tfar) const;
    // The distance along the ray to its first hit in (tnear, tfar); infinity when there is none.
    float hitDistance(const glm::vec3& origin, const glm::vec3& dir, float tnear, float tfar) const;
    // The geometric normal of the triangle under `p` (the first hit of a ray from p + reach n
    // towards -n, within 2 reach), turned to n's side; n when no triangle is there.
    glm::vec3 surfaceNormal(const glm::vec3& p, const glm::vec3& n, float reach) const;
    size_t triangles() const { return mTriangles; }

private:
    void throwIfFailed(const char* what) const;
    void build(const Scene& scene);
    void release() noexcept;
    // One Embree geometry of the scene's triangles `triangles` (indices into Scene::indices / 3).
    enum class Kind { Opaque, AlphaTested, Translucent };
    void addGeometry(const Scene& scene, const std::vector<uint32_t>& triangles, Kind kind);
    RTCDevice mDevice = nullptr;
    RTCScene mScene = nullptr;
    size_t mTriangles = 0;
    std::string mError; // first message from Embree's error callback
public:
    // A triangle of the alpha-tested or the translucent geometry: what their filters read (its
    // material, and its corners' texture coordinates and vertex colours).
    struct FilteredTriangle {
        uint32_t material;
        glm::vec2 uv[3];
        glm::vec4 color[3];
        glm::vec3 corner[3]; // positions: whether two triangles have a corner in common
    };
    struct FilterData {
        const Scene* scene = nullptr;
        std::vector<FilteredTriangle> triangles;
    };

private:
    FilterData mFilter;
    FilterData mTranslucent;
    unsigned mTranslucentGeometry = RTC_INVALID_GEOMETRY_ID;
};

} // namespace penumbra
