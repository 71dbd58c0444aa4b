#pragma once
// Rays against a scene's triangles on the CPU, for the rules that measure a scene once per load
// (the framing, interior or exterior, the first picture's shadow): a few thousand rays, on
// scenes of up to millions of triangles, without Embree (which sits a layer above the scene).
#include "penumbra/scene.h"

#include <optional>
#include <span>
#include <vector>

namespace penumbra {

// The nearest triangle along a ray and whether the ray meets its front (counter-clockwise, by
// winding only: exporters mark closed models double-sided as often as not); nullopt for a miss.
struct RayHit {
    float distance = 0.0f;
    bool front = false;
    uint32_t triangle = 0;
};
struct Ray {
    glm::vec3 origin{0.0f}, direction{0.0f, -1.0f, 0.0f};
};

// Where `ray` meets triangle `t` (Moller-Trumbore, edges inclusive to 1e-5 of the barycentric
// range so that a ray through a quad's diagonal hits it), at a distance above 0.
std::optional<RayHit> hitTriangle(const Scene& scene, uint32_t t, const Ray& ray);

// A bounding volume hierarchy over the triangles (median splits, up to 4 triangles a leaf).
// firstHit returns what testing every triangle in order would: the nearest, and of hits at the
// same distance the lowest triangle index. The Scene must outlive it.
class TriangleBvh {
public:
    explicit TriangleBvh(const Scene& scene);
    std::optional<RayHit>
    firstHit(const Ray& ray, float maxDistance = std::numeric_limits<float>::infinity()) const;
    // Whether any triangle lies along the ray closer than maxDistance.
    bool occluded(const Ray& ray, float maxDistance) const;
    // How many triangle tests the rays so far took: what the hierarchy saves is tested.
    size_t trianglesTested() const { return mTested; }

private:
    struct Node {
        Bounds box;
        uint32_t first = 0; // a leaf's first entry of mOrder; an inner node's children are
        uint32_t count = 0; // first - 1 and first; count: triangles in a leaf, 0 inside
    };
    template <typename Visit>
    void traverse(const Ray& ray, float& limit, Visit&& visit) const;
    const Scene& mScene;
    std::vector<Node> mNodes;
    std::vector<uint32_t> mOrder; // triangle indices, leaf by leaf
    mutable size_t mTested = 0;
};

// Brute force over every triangle for a batch of rays (the reference the hierarchy is tested
// against); firstHits on more than a few rays builds a hierarchy and gives the same answers.
std::vector<std::optional<RayHit>> firstHitsBruteForce(const Scene& scene,
                                                       std::span<const Ray> rays);
std::vector<std::optional<RayHit>> firstHits(const Scene& scene, std::span<const Ray> rays);
std::optional<RayHit> firstHit(const Scene& scene, const glm::vec3& origin, const glm::vec3& dir);

} // namespace penumbra
