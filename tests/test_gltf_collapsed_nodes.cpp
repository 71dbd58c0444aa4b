// Lights and cameras on nodes whose transform collapses: scaled to zero (at rest or by an
// animation) they have no direction, placed past the coordinate limit no place. Both are
// refused with the node and the time, where the renderer and the ray tracer would get NaN. A
// point light needs no direction and is kept.
#include "gltf_builder.h"
#include "penumbra/error.h"
#include "penumbra/scene.h"
#include "posed_gltf.h"
#include "scratch_dir.h"

#include <gtest/gtest.h>

#include <functional>

using namespace penumbra;
using namespace penumbra::test;
namespace fs = std::filesystem;
using J = nlohmann::json;

namespace {

// A ground and one light of `type` (or a camera) on node 1 with `holder`'s fields; `more`
// adds to the asset.
fs::path withLight(const std::string& type, const J& holder, const std::string& name,
                   const std::function<void(GltfBuilder&)>& more = {}) {
    GltfBuilder b;
    b.ground();
    J node = holder;
    if (type == "camera") {
        b.j["cameras"] = {
            {{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
        node["camera"] = 0;
    } else {
        J light = {{"type", type}, {"intensity", 3.0}};
        if (type == "spot")
            light["spot"] = {{"outerConeAngle", 0.5}};
        b.j["extensions"] = {{"KHR_lights_punctual", {{"lights", {light}}}}};
        b.j["extensionsUsed"] = {"KHR_lights_punctual"};
        node["extensions"] = {{"KHR_lights_punctual", {{"light", 0}}}};
    }
    b.node(node);
    if (more)
        more(b);
    return b.writeGltf(scratchDir("collapsed", name + "-" + type, true) / "a.gltf");
}

std::string subjectOf(const std::string& type) {
    return type == "camera" ? "the camera 'camera0'" : "KHR_lights_punctual.lights[0]";
}

} // namespace

TEST(GltfCollapsedNodes, ADirectionScaledToZeroIsRefusedForSpotsSunsAndCameras) {
    for (const std::string type : {"directional", "spot", "camera"}) {
        for (const J& scale : {J{0, 0, 0}, J{1, 1, 0}}) {
            const fs::path f =
                withLight(type, {{"translation", {0, 2, 0}}, {"scale", scale}}, "zero");
            expectInputError([&] { loadAt(f, std::nullopt); }, f.string(),
                             "nodes[1]: " + subjectOf(type) +
                                 " has no direction: its node's transform is scaled to zero");
        }
        // Scaled, not collapsed: the direction is still a unit vector.
        const fs::path f =
            withLight(type, {{"translation", {0, 2, 0}}, {"scale", {3, 0.5, 2}}}, "scaled");
        const Scene s = loadAt(f, std::nullopt);
        if (type == "camera") {
            ASSERT_EQ(s.cameras.size(), 1u);
            EXPECT_NEAR(glm::length(s.cameras[0].target - s.cameras[0].position), 1.0f, 1e-6f);
            EXPECT_NEAR(glm::length(s.cameras[0].up), 1.0f, 1e-6f);
        } else {
            ASSERT_EQ(s.lights.size(), 1u);
            EXPECT_NEAR(glm::length(s.lights[0].direction), 1.0f, 1e-6f);
            EXPECT_NEAR(s.lights[0].direction.z, -1.0f, 1e-6f);
        }
    }
    // A camera whose up collapses is refused as well.
    const fs::path f = withLight("camera", {{"scale", {1, 0, 1}}}, "flat");
    expectInputError([&] { loadAt(f, std::nullopt); }, f.string(),
                     "nodes[1]: the camera 'camera0' has no direction");
}

TEST(GltfCollapsedNodes, APointLightScaledToZeroIsKeptWhereItIs) {
    const fs::path f =
        withLight("point", {{"translation", {1, 2, 3}}, {"scale", {0, 0, 0}}}, "zero");
    const Scene s = loadAt(f, std::nullopt);
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].position, glm::vec3(1, 2, 3));
    EXPECT_EQ(s.lights[0].direction, glm::vec3(0, 0, -1));
}

TEST(GltfCollapsedNodes, AnAnimatedScaleToZeroIsRefusedAtThatTime) {
    for (const std::string type : {"directional", "spot", "camera"}) {
        const fs::path f =
            withLight(type, {{"translation", {0, 2, 0}}}, "animated", [](GltfBuilder& b) {
                const int times = keyframeTimes(b, {0.0f, 1.0f});
                const int values = floatAccessor(b, {1, 1, 1, 0, 0, 0}, "VEC3", 3);
                const J channel = {{"sampler", 0}, {"target", {{"node", 1}, {"path", "scale"}}}};
                b.j["animations"] = {{{"channels", {channel}},
                                      {"samplers", {{{"input", times}, {"output", values}}}}}};
            });
        EXPECT_NO_THROW(loadAt(f, std::nullopt));
        EXPECT_NO_THROW(loadAt(f, 0.5));
        expectInputError([&] { loadAt(f, 1.0); }, f.string(),
                         "nodes[1]: " + subjectOf(type) +
                             " has no direction: its node's transform is scaled to zero at time "
                             "1 s");
    }
}

TEST(GltfCollapsedNodes, ALightOrCameraPastTheCoordinateLimitIsRefused) {
    for (const std::string type : {"directional", "spot", "point", "camera"}) {
        const fs::path f = withLight(type, {{"translation", {0, 2, -2e15}}}, "far");
        expectInputError([&] { loadAt(f, std::nullopt); }, f.string(),
                         "nodes[1]: " + subjectOf(type) +
                             " is placed past the coordinate limit 1e+15");
        // At the limit it is kept.
        const fs::path near = withLight(type, {{"translation", {0, 2, -1e14}}}, "near");
        EXPECT_NO_THROW(loadAt(near, std::nullopt)) << type;
    }
}
