// The `sdf` technique on geometry real assets have: closed surfaces that hold the scene (a room
// drawn as a closed box around its light and camera, a tower's closed glass envelope around its
// floors), open glass panes, against the ray-traced truth: no acne, no leak. And the build's
// slabs and progress line.
#include "render/distance_field.h"
#include "scene/mesh_builder.h"
#include "truth_fixture.h"

#include <glm/gtc/matrix_transform.hpp>

using namespace penumbra;
using namespace penumbra::test;

namespace {

// A closed room (one box, wound as a solid's outside), a point light of radius 0.2 under its
// ceiling, a ball and a block on its floor, the camera inside.
Scene closedRoom() {
    Scene scene;
    MeshBuilder mb(scene);
    mb.box(glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0, 2, 0)), glm::vec3(8, 4, 8)),
           mb.material("walls", glm::vec3(0.7f)));
    const uint32_t grey = mb.material("grey", glm::vec3(0.5f));
    mb.sphere({-1.0f, 0.8f, 0.5f}, 0.8f, grey, 24, 12);
    mb.box(
        glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(1.5f, 0.5f, -1.0f)), glm::vec3(1.0f)),
        grey);
    scene.lights.push_back({.name = "bulb",
                            .type = LightType::Point,
                            .position = {0.3f, 3.4f, 0.2f},
                            .intensity = 20.0f,
                            .radius = 0.2f});
    scene.cameras.push_back({.position = {0.0f, 3.0f, 3.8f}, .target = {0.0f, 0.5f, -1.0f}});
    return scene;
}

// A tower: its closed glass envelope holds three floor slabs; open panes stand before it; a sun;
// the camera outside.
Scene glassTower() {
    Scene scene;
    MeshBuilder mb(scene);
    mb.quad({-12, 0, 12}, {12, 0, 12}, {12, 0, -12}, {-12, 0, -12},
            mb.material("ground", glm::vec3(0.7f)));
    const uint32_t glass = mb.material("glass", glm::vec3(0.5f, 0.6f, 0.7f));
    mb.box(glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0, 4, 0)), glm::vec3(3, 8, 3)),
           glass);
    const uint32_t slab = mb.material("slab", glm::vec3(0.6f));
    for (const float f : {0.0f, 1.0f, 2.0f})
        mb.box(glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0, 2.0f + 2.5f * f, 0)),
                          glm::vec3(2.6f, 0.2f, 2.6f)),
               slab);
    for (const float k : {0.0f, 1.0f, 2.0f}) // panes a little in front of the +z face
        mb.quad({-1.4f + k, 1.0f, 1.7f}, {-0.6f + k, 1.0f, 1.7f}, {-0.6f + k, 3.0f, 1.7f},
                {-1.4f + k, 3.0f, 1.7f}, glass);
    scene.lights.push_back({.name = "sun",
                            .type = LightType::Directional,
                            .direction = glm::normalize(glm::vec3(0.4f, -1.0f, -0.5f)),
                            .intensity = 2.0f,
                            .angularDiameter = 2.0f});
    scene.cameras.push_back({.position = {6.0f, 7.0f, 14.0f}, .target = {0.0f, 2.0f, 0.0f}});
    return scene;
}

} // namespace

// The room, signed as a solid, puts every receiver inside it: all shadowed (acne on every lit
// pixel, RMSE near 1); taken as a shell, it is right. The tower's envelope, seen and lit from
// outside, stays a solid (as a shell its thin walls let a third of its shadow through). Acne and
// leak beyond the blur band under 2% in both.
TEST_F(QualityTest, DistanceFieldOfClosedShellsHasNoAcne) {
    for (const auto& [name, scene] : {std::pair{"room", closedRoom()}, {"tower", glassTower()}}) {
        const Truth t = groundTruth(scene, {.width = 128, .height = 96, .samples = 16});
        const RenderResult r = renderRow(t, Technique::Sdf, {});
        const ErrorMetrics m = errorOf(t, r);
        std::printf("%s: rmse %.3f, acne %.2f%% (beyond blur %.2f%%), leak %.2f%% (%.2f%%)\n", name,
                    m.rmse, 100 * m.acne, 100 * m.acneBeyondBlur, 100 * m.leak,
                    100 * m.leakBeyondBlur);
        EXPECT_LT(m.acneBeyondBlur, 0.02) << name;
        EXPECT_LT(m.leakBeyondBlur, 0.02) << name;
        EXPECT_LT(m.rmse, 0.2) << name;
    }
}

// The build's submissions cover every voxel once per pass, in order; the progress line gives the
// share done and the time left at the rate so far.
TEST(FieldBuild, SlabsCoverTheFieldOncePerPass) {
    shadows::FieldLayout layout{.voxel = 1.0f, .size = {8, 40, 36}};
    const glm::uvec3 bricks = layout.bricks();
    std::vector<uint32_t> starts(size_t{bricks.x} * bricks.y * bricks.z + 1, 0);
    for (size_t b = 1; b < starts.size(); ++b)
        starts[b] = starts[b - 1] + (b % 3 == 0 ? 2 : 0);
    const std::vector<render::FieldSlab> slabs = render::fieldSlabs(layout, starts, 8);
    for (const std::string_view pass : {render::kSeed, render::kFlood, render::kResolve}) {
        uint32_t next = 0;
        size_t count = 0;
        for (const render::FieldSlab& s : slabs) {
            if (s.pass != pass)
                continue;
            ++count;
            EXPECT_EQ(s.first, next) << pass;
            EXPECT_EQ(s.first % FIELD_BRICK, 0u);
            EXPECT_GT(s.cost, 0.0);
            EXPECT_EQ(s.columns, pass == render::kResolve);
            next = s.first + s.count;
        }
        EXPECT_EQ(next, pass == render::kResolve ? layout.size.y : layout.size.z) << pass;
        EXPECT_EQ(count, 8u) << pass; // 10 and 9 bricks: 8 slabs
    }
    EXPECT_DOUBLE_EQ(render::fieldTimeLeft(0.25, 3.0), 9.0);
    EXPECT_DOUBLE_EQ(render::fieldTimeLeft(1.0, 3.0), 0.0);
    EXPECT_EQ(render::fieldProgressLine(0.25, 5.0, 8.2, "sdf_flood"),
              "distance field 25% (sdf_flood), 5.0 s, about 9 s left");
}
