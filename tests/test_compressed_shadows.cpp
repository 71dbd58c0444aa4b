// Compressed geometry casts the shadows of its original (issue 16): the same asset plain, through
// EXT_meshopt_compression and through KHR_draco_mesh_compression, rendered with every light type.
#include "gltf_compressed.h"
#include "gpu_fixture.h"
#include "scratch_dir.h"

#include <fmt/format.h>

namespace penumbra::test {
namespace {

Scene written(GltfBuilder b, const std::string& name) {
    const auto d = scratchDir("compressed-shadows", name);
    return loadScene(b.writeGlb(d / "a.glb").string());
}

TEST_F(ShadowTest, CompressedAssetsCastTheirOriginalsShadows) {
    const TestMesh mesh = bumpyGridAndSlab();
    const Scene plain = written(plainMesh(mesh), "plain");
    const Scene meshopt = written(meshoptMesh(mesh), "meshopt");
    const Scene draco = written(dracoMesh(mesh, 16), "draco");
    const std::vector<Light> lights = {{.name = "sun",
                                        .type = LightType::Directional,
                                        .direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.2f))},
                                       {.name = "spot",
                                        .type = LightType::Spot,
                                        .position = {0.5f, 6.0f, 1.0f},
                                        .direction = glm::vec3(0, -1, 0),
                                        .intensity = 30.0f,
                                        .outerConeAngle = 1.0f},
                                       {.name = "bulb",
                                        .type = LightType::Point,
                                        .position = {-0.5f, 3.5f, 0.5f},
                                        .intensity = 10.0f}};
    for (const Light& light : lights) {
        std::vector<RenderResult> results;
        for (Scene s : {plain, meshopt, draco}) {
            s.lights = {light};
            results.push_back(render(s, {.width = 160, .height = 120, .shadowMapSize = 1024}));
        }
        const auto& reference = results[0].visibility[0];
        size_t shadowed = 0, pixels = 0;
        for (float v : reference)
            if (std::isfinite(v))
                ++pixels, shadowed += v < 0.5f;
        EXPECT_GT(shadowed, pixels / 50) << light.name << ": the slab's shadow must be in view";
        for (size_t k = 1; k < results.size(); ++k) {
            size_t differ = 0;
            for (size_t i = 0; i < reference.size(); ++i)
                differ +=
                    std::isfinite(reference[i]) != std::isfinite(results[k].visibility[0][i]) ||
                    std::abs(reference[i] - results[k].visibility[0][i]) > 0.5f;
            // Draco's 16-bit positions and meshopt's 8-bit normals move an edge pixel at most.
            EXPECT_LE(differ, pixels / 500)
                << light.name << (k == 1 ? ", meshopt" : ", draco") << ": " << differ << " of "
                << pixels << " pixels differ";
        }
    }
}

} // namespace
} // namespace penumbra::test
