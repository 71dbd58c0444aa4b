// Culling (src/render/culling.h): clusters never straddle a batch, a cluster is dropped only when
// a frustum plane has it wholly outside, and the survivors merge into as few draws as can be.
#include "render/culling.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <vector>

namespace penumbra::render {
namespace {

// One triangle per unit of x at x = 0, 1, 2, ... along a row, each its own 3 vertices.
struct Row {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
    explicit Row(uint32_t triangles) {
        for (uint32_t t = 0; t < triangles; ++t) {
            const float x = static_cast<float>(t);
            for (const glm::vec3& p :
                 {glm::vec3(x, 0, 0), glm::vec3(x + 0.5f, 0, 0), glm::vec3(x, 0.5f, 0)}) {
                indices.push_back(static_cast<uint32_t>(positions.size()));
                positions.push_back(p);
            }
        }
    }
};

// An orthographic view of x in [lo, hi], y in [-1, 1], looking down -z from z = 5, depth 1..9.
glm::mat4 window(float lo, float hi) {
    glm::mat4 proj = glm::orthoRH_ZO(lo, hi, -1.0f, 1.0f, 1.0f, 9.0f);
    return proj * glm::lookAt(glm::vec3(0, 0, 5), glm::vec3(0, 0, 0), glm::vec3(0, 1, 0));
}

} // namespace

TEST(Culling, ClustersHoldTheirTrianglesAndStopAtBatches) {
    const Row row(3 * kClusterTriangles);
    const uint32_t batch = 3 * (kClusterTriangles + 10); // a batch starts mid-way
    const std::vector<Cluster> clusters = makeClusters(row.positions, row.indices, {{0, batch}});
    ASSERT_EQ(clusters.size(), 4u);
    EXPECT_EQ(clusters[0].indexCount, 3 * kClusterTriangles);
    EXPECT_EQ(clusters[1].firstIndex + clusters[1].indexCount, batch);
    EXPECT_EQ(clusters[2].firstIndex, batch);
    uint32_t next = 0;
    for (const Cluster& c : clusters) {
        EXPECT_EQ(c.firstIndex, next);
        next += c.indexCount;
        const float first = static_cast<float>(c.firstIndex / 3);
        const float last = static_cast<float>((c.firstIndex + c.indexCount) / 3 - 1);
        EXPECT_EQ(c.lo, glm::vec3(first, 0, 0));
        EXPECT_EQ(c.hi, glm::vec3(last + 0.5f, 0.5f, 0));
    }
    EXPECT_EQ(next, row.indices.size());
}

TEST(Culling, DropsOnlyClustersWhollyOutsideAndMergesTheRest) {
    const Row row(4 * kClusterTriangles);
    const std::vector<Cluster> clusters = makeClusters(row.positions, row.indices, {{0}});
    ASSERT_EQ(clusters.size(), 4u);
    const uint32_t all = static_cast<uint32_t>(row.indices.size());
    const float n = static_cast<float>(kClusterTriangles);
    // Reaching a hair into the second cluster keeps it; the last two lie outside.
    auto ranges = visibleRanges(clusters, 0, all, window(-1.0f, n + 0.01f), false);
    ASSERT_EQ(ranges.size(), 1u);
    EXPECT_EQ(ranges[0].first, 0u);
    EXPECT_EQ(ranges[0].count, 2 * 3 * kClusterTriangles);
    // A window over the third cluster only.
    ranges = visibleRanges(clusters, 0, all, window(2 * n + 0.2f, 3 * n - 1.5f), false);
    ASSERT_EQ(ranges.size(), 1u);
    EXPECT_EQ(ranges[0].first, clusters[2].firstIndex);
    EXPECT_EQ(ranges[0].count, clusters[2].indexCount);
    // Only the clusters inside the asked range are drawn.
    ranges = visibleRanges(clusters, clusters[1].firstIndex, 2 * clusters[1].indexCount,
                           window(-1.0f, 5 * n), false);
    ASSERT_EQ(ranges.size(), 1u);
    EXPECT_EQ(ranges[0].first, clusters[1].firstIndex);
    EXPECT_EQ(ranges[0].count, 2 * clusters[1].indexCount);
}

TEST(Culling, DepthClampedViewsKeepCastersBeforeTheirNearPlane) {
    Row row(kClusterTriangles);
    for (glm::vec3& p : row.positions)
        p.z = 5.5f; // behind the eye at z = 5: before the near plane, inside the window
    const std::vector<Cluster> clusters = makeClusters(row.positions, row.indices, {{0}});
    const uint32_t all = static_cast<uint32_t>(row.indices.size());
    const glm::mat4 view = window(-1.0f, 2.0f * static_cast<float>(kClusterTriangles));
    EXPECT_TRUE(visibleRanges(clusters, 0, all, view, false).empty());
    EXPECT_EQ(visibleRanges(clusters, 0, all, view, true).size(), 1u);
    for (glm::vec3& p : row.positions)
        p.z = -4.5f; // past the far plane at z = -4
    const std::vector<Cluster> beyond = makeClusters(row.positions, row.indices, {{0}});
    EXPECT_TRUE(visibleRanges(beyond, 0, all, view, false).empty());
    EXPECT_EQ(visibleRanges(beyond, 0, all, view, true).size(), 1u);
}

// A virtual map's static layer draws the clusters no pose moved, the moving casters' pass the
// others: a cluster is dynamic when any of its triangles moved, found through the index
// buffer's order; the two sets never merge across each other and together are all.
TEST(Culling, DynamicClustersAreThoseWithAMovedTriangleAndTheSetsSplitTheDraws) {
    const Row row(4 * kClusterTriangles);
    std::vector<Cluster> clusters = makeClusters(row.positions, row.indices, {});
    ASSERT_EQ(clusters.size(), 4u);
    // The index buffer's triangle t is the scene's triangle (t + 7) % count: reordered.
    const uint32_t count = 4 * kClusterTriangles;
    std::vector<uint32_t> triangleOf(count);
    for (uint32_t t = 0; t < count; ++t)
        triangleOf[t] = (t + 7) % count;
    std::vector<uint8_t> moved(count, 0);
    moved[(kClusterTriangles - 1 + 7) % count] = 1; // the first cluster's last triangle
    moved[(2 * kClusterTriangles + 7) % count] = 1; // the third's first
    markDynamicClusters(clusters, triangleOf, moved);
    EXPECT_TRUE(clusters[0].dynamic);
    EXPECT_FALSE(clusters[1].dynamic);
    EXPECT_TRUE(clusters[2].dynamic);
    EXPECT_FALSE(clusters[3].dynamic);
    const glm::mat4 all = window(-1.0f, float(count) + 1.0f);
    const uint32_t indices = 3 * count, cluster = 3 * kClusterTriangles;
    const std::vector<IndexRange> everything = visibleRanges(clusters, 0, indices, all, true);
    ASSERT_EQ(everything.size(), 1u);
    EXPECT_EQ(everything[0].count, indices);
    const std::vector<IndexRange> still =
        visibleRanges(clusters, 0, indices, all, true, CasterSet::Static);
    ASSERT_EQ(still.size(), 2u);
    EXPECT_EQ(still[0].first, cluster);
    EXPECT_EQ(still[0].count, cluster);
    EXPECT_EQ(still[1].first, 3 * cluster);
    const std::vector<IndexRange> moving =
        visibleRanges(clusters, 0, indices, all, true, CasterSet::Dynamic);
    ASSERT_EQ(moving.size(), 2u);
    EXPECT_EQ(moving[0].first, 0u);
    EXPECT_EQ(moving[0].count, cluster);
    EXPECT_EQ(moving[1].first, 2 * cluster);
    // Culling still applies within a set: a window over the first cluster alone.
    const std::vector<IndexRange> near =
        visibleRanges(clusters, 0, indices, window(-0.5f, float(kClusterTriangles) - 1.5f), true,
                      CasterSet::Static);
    EXPECT_TRUE(near.empty());
    // The scene's last triangle alone (index-buffer triangle count - 8): the last cluster.
    std::vector<uint8_t> last(count, 0);
    last[count - 1] = 1;
    markDynamicClusters(clusters, triangleOf, last);
    for (size_t c = 0; c < clusters.size(); ++c)
        EXPECT_EQ(clusters[c].dynamic, c == 3) << c;
    // A flag past the scene's triangles, or none moved: nothing dynamic.
    markDynamicClusters(clusters, triangleOf, std::vector<uint8_t>(3, 0));
    for (const Cluster& c : clusters)
        EXPECT_FALSE(c.dynamic);
}

} // namespace penumbra::render
