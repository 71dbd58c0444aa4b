// Translucent casters (docs/translucency.md): Scene::transmittance's rule on hand-worked cases,
// KHR_materials_transmission and KHR_materials_volume read and refused, and the RGB ground truth
// against the closed form of builtin:sheets (the product of the sheets each ray crosses) under
// every light type, hard and soft. CPU only: the G-buffer is a synthetic grid.
#include "core/image_io.h"
#include "expect_refused.h"
#include "gltf_builder.h"
#include "penumbra/reference.h"
#include "plane_grid.h"
#include "reference/embree_scene.h"
#include "reference/sampling.h"
#include "scene/builtin_scenes.h"
#include "scene/mesh_builder.h"
#include "scratch_dir.h"
#include "segment_box.h"
#include "sweep/truth_cache.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <optional>

using namespace penumbra;
using namespace penumbra::test;
using J = nlohmann::json;

namespace {

void expectNear(glm::vec3 got, glm::vec3 want, float tolerance, const char* what) {
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], want[c], tolerance) << what << ", channel " << c;
}

// One material of each kind, and a 2x1 image: texel 0 (sRGB 188, 255, 10; alpha 0), texel 1
// (128, 64, 255; alpha 255), sampled nearest. sRGB 10 is on the curve's linear part.
Scene materials() {
    Scene s;
    s.images.push_back(
        {.name = "t", .width = 2, .height = 1, .rgba = {188, 255, 10, 0, 128, 64, 255, 255}});
    s.textures.push_back({.image = 0, .nearest = true});
    s.materials = {
        {.name = "opaque"},
        {.name = "mask", .baseColorTexture = 0, .alphaMode = AlphaMode::Mask},
        {.name = "blend", .baseColor = {0.2f, 0.4f, 0.6f, 0.3f}, .alphaMode = AlphaMode::Blend},
        {.name = "filter", .baseColor = {1.0f, 0.5f, 0.25f, 1.0f}, .transmission = 0.5f},
        {.name = "blend filter",
         .baseColor = {0.2f, 0.6f, 1.0f, 0.5f},
         .alphaMode = AlphaMode::Blend,
         .transmission = 1.0f},
        {.name = "volume",
         .baseColor = {0.81f, 1.0f, 1.0f, 1.0f},
         .transmission = 1.0f,
         .thickness = 1.0f,
         .attenuationDistance = 2.0f,
         .attenuationColor = {0.5f, 1.0f, 0.25f}},
        {.name = "textured filter",
         .baseColorTexture = 0,
         .transmission = 1.0f,
         .transmissionTexture = 0},
        {.name = "volume without a distance",
         .transmission = 1.0f,
         .thickness = 1.0f,
         .attenuationColor = {0.0f, 0.5f, 1.0f}},
    };
    s.materials[7].baseColor = glm::vec4(0.64f, 0.36f, 1.0f, 1.0f);
    s.materials[6].baseColor = glm::vec4(1.0f);
    return s;
}

} // namespace

TEST(Transmittance, EachMaterialKeepsWhatItsRuleSays) {
    const Scene s = materials();
    const glm::vec4 white(1.0f);
    expectNear(s.transmittance(0, {0.5f, 0.5f}, white), glm::vec3(0.0f), 0.0f, "opaque");
    expectNear(s.transmittance(1, {0.25f, 0.5f}, white), glm::vec3(1.0f), 0.0f, "mask hole");
    expectNear(s.transmittance(1, {0.75f, 0.5f}, white), glm::vec3(0.0f), 0.0f, "mask covered");
    // Blend: alpha is coverage (base alpha 0.3 x vertex alpha 0.5), and the rest passes grey.
    expectNear(s.transmittance(2, {0.5f, 0.5f}, {1.0f, 1.0f, 1.0f, 0.5f}), glm::vec3(0.85f), 1e-6f,
               "blend");
    // Transmission tinted by the base colour and the vertex colour.
    expectNear(s.transmittance(3, {0.5f, 0.5f}, {1.0f, 1.0f, 0.5f, 1.0f}),
               glm::vec3(0.5f, 0.25f, 0.0625f), 1e-6f, "filter");
    // Half covered by a filter: half passes as it is, half through the filter.
    expectNear(s.transmittance(4, {0.5f, 0.5f}, white), glm::vec3(0.6f, 0.8f, 1.0f), 1e-6f,
               "blend filter");
    // A volume's face: the square root of the tint and half the thickness's attenuation, which
    // keeps attenuationColor every attenuationDistance (1 / 2 of it here).
    expectNear(s.transmittance(5, {0.5f, 0.5f}, white),
               glm::vec3(0.9f * std::pow(0.5f, 0.25f), 1.0f, std::pow(0.25f, 0.25f)), 1e-6f,
               "volume face");
    // Textures: transmission from the red channel as stored, the tint decoded from sRGB.
    const float decoded = std::pow((188.0f / 255.0f + 0.055f) / 1.055f, 2.4f);
    expectNear(s.transmittance(6, {0.25f, 0.5f}, white),
               glm::vec3(decoded, 1.0f, 10.0f / 255.0f / 12.92f) * 188.0f / 255.0f, 1e-6f,
               "textured filter");
    // Without a distance nothing attenuates, whatever the colour says (no 0 x infinity).
    expectNear(s.transmittance(7, {0.5f, 0.5f}, white), glm::vec3(0.8f, 0.6f, 1.0f), 1e-6f,
               "volume without a distance");
    // A tint past 1 (a vertex colour of 4) lets all the light through, no more.
    expectNear(s.transmittance(3, {0.5f, 0.5f}, {4.0f, 1.0f, 1.0f, 1.0f}),
               glm::vec3(1.0f, 0.25f, 0.125f), 1e-6f, "filter, bright vertex");
    expectNear(s.transmittance(99, {0.5f, 0.5f}, white), glm::vec3(0.0f), 0.0f, "no material");
    EXPECT_FALSE(s.materials[0].translucent());
    EXPECT_FALSE(s.materials[1].translucent());
    // Rec. 709's weights, summing to 1.
    EXPECT_DOUBLE_EQ(luminance(1.0, 0.0, 0.0), 0.2126);
    EXPECT_DOUBLE_EQ(luminance(0.0, 1.0, 0.0), 0.7152);
    EXPECT_DOUBLE_EQ(luminance(0.0, 0.0, 1.0), 0.0722);
    EXPECT_TRUE(s.materials[2].translucent());
    EXPECT_TRUE(s.materials[3].translucent());
}

namespace {

glm::dvec3 sheetFactor(const builtin::SheetSpec& sheet) {
    if (sheet.transmission > 0.0f)
        return glm::dvec3(sheet.transmission) * glm::dvec3(sheet.colour);
    return glm::dvec3(1.0 - sheet.alpha);
}

// The post of builtin:sheets, as an axis-aligned box grown by `grow`.
bool segmentMeetsPost(glm::dvec3 p, glm::dvec3 d, double length, double grow) {
    const glm::dvec3 centre(2.6, 0.9, 1.8), half = glm::dvec3(0.15, 0.9, 0.15) + grow;
    return segmentMeetsBox(p, d, length, centre - half, centre + half);
}

// The closed form at ground point p for rays along `d` (unit, upwards) within `length`: the
// product of the sheets crossed, none when a ray of the cone (half-angle `alpha` about d) passes
// within reach of a sheet's edge or the post (then not every ray crosses the same ones).
std::optional<glm::dvec3> closedForm(glm::dvec3 p, glm::dvec3 d, double length, double alpha,
                                     int* layers) {
    glm::dvec3 through(1.0);
    *layers = 0;
    for (const builtin::SheetSpec& sheet : builtin::kSheets) {
        const double t = (sheet.height - p.y) / d.y;
        if (t >= length)
            continue;
        // The cone's footprint on the sheet's plane: well within this of q (small alpha).
        const double reach = 1.5 * t * std::tan(alpha) / (d.y * d.y) + 1e-4;
        const glm::dvec3 q = p + t * d;
        const double dx = std::abs(q.x - sheet.centre.x) - sheet.halfSize.x;
        const double dz = std::abs(q.z - sheet.centre.y) - sheet.halfSize.y;
        if (std::abs(dx) < reach || std::abs(dz) < reach)
            return std::nullopt;
        if (dx < 0.0 && dz < 0.0) {
            through *= sheetFactor(sheet);
            ++*layers;
        }
    }
    // The cone's radius as far as the post's far corner.
    const double reach =
        1.5 * (glm::length(p - glm::dvec3(2.6, 0.9, 1.8)) + 1.0) * std::tan(alpha) + 1e-4;
    const bool meets = segmentMeetsPost(p, d, length, reach);
    if (meets != segmentMeetsPost(p, d, length, -reach))
        return std::nullopt;
    return meets ? glm::dvec3(0.0) : through;
}

constexpr uint32_t kGrid = 128;

// The ground around the sheets' shadows, x in [-2, 4] and z in [-2.5, 3.5].
RenderResult groundGrid() {
    return planeGrid(1.0f, 0.5f, 6.0f, kGrid);
}

struct Agreement {
    size_t compared = 0, stacked = 0; // points compared; under two sheets or more
    double worst = 0.0;               // largest difference in any channel
    double luminanceWorst = 0.0;      // visibility against the transmittance's luminance
};

Agreement againstClosedForm(const Light& light) {
    Scene scene = builtin::sheets();
    scene.lights = {light};
    const RenderResult g = groundGrid();
    const ReferenceResult truth = computeReference(scene, g, {.samples = 64});
    Agreement a;
    EXPECT_EQ(truth.transmittance.size(), 1u);
    if (truth.transmittance.size() != 1)
        return a;
    for (size_t i = 0; i < size_t{kGrid} * kGrid; ++i) {
        const glm::dvec3 p(g.position[3 * i], 0.0, g.position[3 * i + 2]);
        const LightCone cone = coneTowards(light, p);
        const double alpha = cone.single ? 0.0 : std::acos(1.0 - cone.oneMinusCosAlpha);
        int layers = 0;
        const std::optional<glm::dvec3> want =
            closedForm(p, cone.axis, distanceToLight(cone, p, cone.axis), alpha, &layers);
        const glm::dvec3 got(truth.transmittance[0][3 * i], truth.transmittance[0][3 * i + 1],
                             truth.transmittance[0][3 * i + 2]);
        a.luminanceWorst = std::max(
            a.luminanceWorst, std::abs(truth.visibility[0][i] - luminance(got.x, got.y, got.z)));
        if (!want)
            continue;
        ++a.compared;
        a.stacked += layers >= 2;
        for (int c = 0; c < 3; ++c)
            a.worst = std::max(a.worst, std::abs(got[c] - (*want)[c]));
    }
    return a;
}

} // namespace

// Every ray from a ground point crosses the same sheets (and its cone clears their edges): the
// truth is their product, per channel, to float rounding. For each light type, hard and soft.
TEST(TranslucentTruth, StackedSheetsKeepTheProductOfTheirTransmittances) {
    const glm::vec3 down = glm::normalize(builtin::kSheetsSunDirection);
    const Light lights[] = {
        {.name = "sun", .type = LightType::Directional, .direction = down},
        {.name = "wide sun",
         .type = LightType::Directional,
         .direction = down,
         .angularDiameter = 3.0f},
        {.name = "spot",
         .type = LightType::Spot,
         .position = {-2.5f, 7.0f, -1.0f},
         .direction = glm::normalize(glm::vec3(3.0f, -7.0f, 1.5f)),
         .outerConeAngle = 1.2f},
        {.name = "wide spot",
         .type = LightType::Spot,
         .position = {-2.5f, 7.0f, -1.0f},
         .direction = glm::normalize(glm::vec3(3.0f, -7.0f, 1.5f)),
         .outerConeAngle = 1.2f,
         .radius = 0.3f},
        {.name = "point", .type = LightType::Point, .position = {-1.5f, 6.0f, 0.5f}},
        {.name = "wide point",
         .type = LightType::Point,
         .position = {-1.5f, 6.0f, 0.5f},
         .radius = 0.3f},
    };
    for (const Light& light : lights) {
        const Agreement a = againstClosedForm(light);
        std::printf("%s: %zu points compared, %zu under two sheets or more, worst %.2e\n",
                    light.name.c_str(), a.compared, a.stacked, a.worst);
        EXPECT_GT(a.compared, 3000u) << light.name;
        EXPECT_GT(a.stacked, 800u) << light.name;
        EXPECT_LT(a.worst, 1e-5) << light.name;
        EXPECT_LT(a.luminanceWorst, 1e-6) << light.name;
    }
}

// A closed glass box (KHR_materials_volume) is crossed in and out: the ground under it keeps its
// tint and the attenuation over its thickness once, whatever the box's faces are split into.
TEST(TranslucentTruth, AClosedVolumeKeepsItsTintAndAttenuationOnce) {
    Scene scene;
    MeshBuilder mb(scene);
    mb.quad({-9, 0, 9}, {9, 0, 9}, {9, 0, -9}, {-9, 0, -9}, mb.material("ground", glm::vec3(0.7f)));
    const uint32_t glass = mb.material("glass", {0.9f, 0.8f, 0.7f});
    scene.materials[glass].transmission = 0.9f;
    scene.materials[glass].thickness = 1.0f;
    scene.materials[glass].attenuationDistance = 0.5f;
    scene.materials[glass].attenuationColor = {0.8f, 0.6f, 0.9f};
    mb.box(glm::scale(glm::translate(glm::mat4(1.0f), {0.0f, 2.0f, 0.0f}), glm::vec3(2.0f)), glass);
    scene.lights = {{.type = LightType::Directional, .direction = {0.0f, -1.0f, 0.0f}}};
    RenderResult g{.width = 1, .height = 1, .position = {0.1f, 0.0f, 0.2f}, .normal = {0, 1, 0}};
    const ReferenceResult truth = computeReference(scene, g, {.samples = 1});
    ASSERT_EQ(truth.transmittance.size(), 1u);
    const glm::vec3 want =
        0.9f * glm::vec3(0.9f, 0.8f, 0.7f) * glm::pow(glm::vec3(0.8f, 0.6f, 0.9f), glm::vec3(2.0f));
    expectNear({truth.transmittance[0][0], truth.transmittance[0][1], truth.transmittance[0][2]},
               want, 1e-5f, "under the glass box");
}

// A BLEND sheet where alpha is 0 is no occluder; where it is 1/2, it is, at its height; the
// yes-or-no occlusion query agrees with the transmittance; a receiver inside a sphere light is lit.
TEST(TranslucentTruth, AClearSheetIsNoOccluderAndAHalfCoveredOneIs) {
    for (const float alpha : {0.0f, 0.5f}) {
        Scene scene;
        MeshBuilder mb(scene);
        mb.quad({-9, 0, 9}, {9, 0, 9}, {9, 0, -9}, {-9, 0, -9},
                mb.material("ground", glm::vec3(0.7f)));
        const uint32_t sheet = mb.material("sheet", glm::vec3(0.5f));
        scene.materials[sheet].alphaMode = AlphaMode::Blend;
        scene.materials[sheet].baseColor.w = alpha;
        mb.quad({-2, 2, 2}, {2, 2, 2}, {2, 2, -2}, {-2, 2, -2}, sheet);
        scene.lights = {{.type = LightType::Directional, .direction = {0.0f, -1.0f, 0.0f}},
                        {.type = LightType::Point, .position = {5.0f, 0.1f, 0.0f}, .radius = 0.3f}};
        RenderResult g{.width = 2,
                       .height = 1,
                       .position = {0.1f, 0.0f, 0.2f, 5.0f, 0.0f, 0.0f},
                       .normal = {0, 1, 0, 0, 1, 0}};
        const ReferenceResult truth = computeReference(scene, g, {.samples = 16});
        ASSERT_EQ(truth.transmittance.size(), 2u);
        EXPECT_EQ(truth.occluderDistance[0][0],
                  alpha > 0.0f ? 2.0f : std::numeric_limits<float>::infinity());
        expectNear(
            {truth.transmittance[0][0], truth.transmittance[0][1], truth.transmittance[0][2]},
            glm::vec3(1.0f - alpha), 1e-6f, "under the sheet");
        expectNear(
            {truth.transmittance[1][3], truth.transmittance[1][4], truth.transmittance[1][5]},
            glm::vec3(1.0f), 0.0f, "inside the light");
        const EmbreeScene embree(scene, "");
        EXPECT_FALSE(embree.occluded({0.1f, 0.01f, 0.2f}, {0.0f, 1.0f, 0.0f}, 0.0f, 100.0f));
    }
    const EmbreeScene sheets(builtin::sheets(), "");
    EXPECT_TRUE(sheets.translucent());
    // Up through the post: occluded; up through the red filter alone: not.
    EXPECT_TRUE(sheets.occluded({2.6f, 0.01f, 1.8f}, {0.0f, 1.0f, 0.0f}, 0.0f, 100.0f));
    EXPECT_FALSE(sheets.occluded({-1.5f, 0.01f, -1.2f}, {0.0f, 1.0f, 0.0f}, 0.0f, 100.0f));
}

// A pure red filter under a grey one keeps red alone: the ray goes on while any channel is left.
TEST(TranslucentTruth, APureFilterKeepsItsOneChannel) {
    Scene scene;
    MeshBuilder mb(scene);
    mb.quad({-9, 0, 9}, {9, 0, 9}, {9, 0, -9}, {-9, 0, -9}, mb.material("ground", glm::vec3(0.7f)));
    for (const auto& [height, colour] :
         {std::pair{1.0f, glm::vec3(1.0f, 0.0f, 0.0f)}, std::pair{2.0f, glm::vec3(0.5f)}}) {
        const uint32_t filter = mb.material("filter", colour);
        scene.materials[filter].transmission = 1.0f;
        mb.quad({-2, height, 2}, {2, height, 2}, {2, height, -2}, {-2, height, -2}, filter);
    }
    const EmbreeScene embree(scene, "");
    for (const float x : {-1.0f, 0.3f, 1.2f})
        expectNear(embree.transmittance({x, 0.01f, 0.2f}, {0.0f, 1.0f, 0.0f}, 0.0f, 100.0f),
                   {0.5f, 0.0f, 0.0f}, 1e-6f, "under both");
    EXPECT_FALSE(embree.occluded({0.3f, 0.01f, 0.2f}, {0.0f, 1.0f, 0.0f}, 0.0f, 100.0f));
    // The red filter keeps green and blue back: the nearest occluder, not the grey one above.
    EXPECT_FLOAT_EQ(embree.hitDistance({0.3f, 0.0f, 0.2f}, {0.0f, 1.0f, 0.0f}, 0.0f, 100.0f), 1.0f);
}

// One large filter triangle over a dense field of small boxes, where Embree's build may split a
// triangle between leaves (spatial splits) and so report it twice to one ray: each ray still
// keeps its tint once. (No ray here has been seen to meet a triangle twice: the dedupe's
// mutant survives it; the guard stays, as Embree's documentation allows the case.)
TEST(TranslucentTruth, ALargeFilterOverManySmallCastersCountsOnce) {
    Scene scene;
    MeshBuilder mb(scene);
    const uint32_t grey = mb.material("box", glm::vec3(0.5f));
    for (int i = 0; i < 40; ++i)
        for (int j = 0; j < 40; ++j)
            mb.box(glm::scale(
                       glm::translate(glm::mat4(1.0f), {-9.8f + 0.5f * float(i),
                                                        0.5f + 0.05f * float((i * 7 + j * 3) % 11),
                                                        -9.8f + 0.5f * float(j)}),
                       glm::vec3(0.08f)),
                   grey);
    const uint32_t filter = mb.material("filter", {0.9f, 0.6f, 0.3f});
    scene.materials[filter].transmission = 1.0f;
    const auto first = static_cast<uint32_t>(scene.vertices.size());
    for (const glm::vec3 corner :
         {glm::vec3(-40, 3, -40), glm::vec3(80, 3, -40), glm::vec3(-40, 3, 80)})
        scene.vertices.push_back({.position = corner, .normal = {0, 1, 0}, .material = filter});
    scene.indices.insert(scene.indices.end(), {first, first + 1, first + 2});
    const EmbreeScene embree(scene, "");
    size_t rays = 0;
    for (int i = 0; i < 60; ++i)
        for (int j = 0; j < 60; ++j) {
            // Up between the boxes' columns, through the filter alone.
            const glm::vec3 from(-9.55f + 0.5f * float(i % 40), 2.0f + 0.01f * float(j),
                                 -9.55f + 0.5f * float(j % 40));
            const glm::vec3 through = embree.transmittance(from, {0.0f, 1.0f, 0.0f}, 0.0f, 100.0f);
            EXPECT_NEAR(through.x, 0.9f, 1e-6f) << from.x << " " << from.z;
            EXPECT_NEAR(through.z, 0.3f, 1e-6f) << from.x << " " << from.z;
            ++rays;
            if (::testing::Test::HasFailure())
                return;
        }
    EXPECT_EQ(rays, 3600u);
}

// A filter whose corners are red, green and blue: a ray through it keeps the colour its corners'
// weights there make (Embree's barycentrics u and v weigh the second and third corners).
TEST(TranslucentTruth, AFilterBlendsItsCornersColours) {
    Scene scene;
    MeshBuilder mb(scene);
    mb.quad({-9, 0, 9}, {9, 0, 9}, {9, 0, -9}, {-9, 0, -9}, mb.material("ground", glm::vec3(0.7f)));
    const uint32_t filter = mb.material("filter", glm::vec3(1.0f));
    scene.materials[filter].transmission = 1.0f;
    const glm::vec3 a{-2.0f, 1.0f, -2.0f}, b{2.0f, 1.0f, -2.0f}, c{-2.0f, 1.0f, 2.0f};
    const glm::vec4 colours[] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}};
    const glm::vec3 corners[] = {a, b, c};
    const auto first = static_cast<uint32_t>(scene.vertices.size());
    for (int k = 0; k < 3; ++k)
        scene.vertices.push_back(
            {.position = corners[k], .normal = {0, 1, 0}, .material = filter, .color = colours[k]});
    scene.indices.insert(scene.indices.end(), {first, first + 1, first + 2});
    const EmbreeScene embree(scene, "");
    const glm::vec3 p = a + 0.2f * (b - a) + 0.5f * (c - a); // weights 0.3, 0.2, 0.5
    expectNear(embree.transmittance({p.x, 0.01f, p.z}, {0.0f, 1.0f, 0.0f}, 0.0f, 100.0f),
               {0.3f, 0.2f, 0.5f}, 1e-5f, "the corners' colours blended");
}

namespace {

// A hexagonal fan of six triangles around (0, height, 0), `radius` wide, facing up.
void addFan(Scene& s, float height, float radius, uint32_t material) {
    const auto first = static_cast<uint32_t>(s.vertices.size());
    s.vertices.push_back(
        {.position = {0.0f, height, 0.0f}, .normal = {0, 1, 0}, .material = material});
    for (int k = 0; k < 6; ++k) {
        const float angle = 2.0f * glm::pi<float>() * static_cast<float>(k) / 6.0f;
        s.vertices.push_back(
            {.position = {radius * std::cos(angle), height, radius * std::sin(angle)},
             .normal = {0, 1, 0},
             .material = material});
    }
    for (uint32_t k = 0; k < 6; ++k)
        s.indices.insert(s.indices.end(), {first, first + 1 + k, first + 1 + (k + 1) % 6});
}

// A quad of `material` through four corners.
void addQuad(Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, uint32_t material,
             glm::vec4 colour = glm::vec4(1.0f)) {
    const auto first = static_cast<uint32_t>(s.vertices.size());
    for (const glm::vec3& p : {a, b, c, d})
        s.vertices.push_back(
            {.position = p, .normal = {0, 1, 0}, .material = material, .color = colour});
    s.indices.insert(s.indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
}

Scene filters() {
    Scene s;
    s.materials.push_back(
        {.name = "filter", .baseColor = {1.0f, 0.5f, 0.25f, 1.0f}, .transmission = 1.0f});
    s.materials.push_back(
        {.name = "blue filter", .baseColor = {0.5f, 0.5f, 1.0f, 1.0f}, .transmission = 1.0f});
    s.materials.push_back({.name = "opaque"});
    s.materials.push_back(
        {.name = "clear", .baseColor = {1, 1, 1, 0}, .alphaMode = AlphaMode::Blend});
    return s;
}

constexpr float kFar = std::numeric_limits<float>::infinity();
const glm::vec3 kUp(0.0f, 1.0f, 0.0f);

} // namespace

// A ray through a fan's centre meets all six of its triangles at one point, and one through a
// spoke two of them: the surface counts once there, as at any other point of it; near and a
// thousand units away (the distances compared are relative), and behind another filter (the
// fan's crossings are remembered after the first layer's).
TEST(TranslucentTruth, ARayThroughTrianglesCommonCornerCrossesTheSurfaceOnce) {
    for (const float height : {1.0f, 1000.0f}) {
        Scene s = filters();
        addFan(s, height, 1.0f, 0);
        const EmbreeScene embree(s, "threads=1");
        const glm::vec3 want(1.0f, 0.5f, 0.25f);
        EXPECT_EQ(embree.transmittance({0.0f, 0.0f, 0.0f}, kUp, 0.0f, kFar), want) << height;
        EXPECT_EQ(embree.transmittance({0.5f, 0.0f, 0.0f}, kUp, 0.0f, kFar), want) << height;
        EXPECT_EQ(embree.transmittance({0.4f, 0.0f, 0.2f}, kUp, 0.0f, kFar), want) << height;
        for (const glm::vec3 p :
             {glm::vec3(0.0f), glm::vec3(0.5f, 0.0f, 0.0f), glm::vec3(-0.25f, 0.0f, 0.4330127f)}) {
            const EmbreeScene::SurfacesAlong along = embree.surfacesAlong(p, kUp, 0.0f, kFar);
            ASSERT_EQ(along.translucent.size(), 1u) << height << ", " << p.x;
            EXPECT_EQ(along.translucent[0].transmittance, want);
        }
    }
    for (const float height : {1.0f, 1000.0f}) { // a fan tilted: its triangles' planes round apart
        Scene s = filters();
        addFan(s, height, 1.0f, 0);
        for (Vertex& v : s.vertices)
            v.position.y += 0.37f * v.position.x + 0.21f * v.position.z;
        const EmbreeScene embree(s, "threads=1");
        for (const glm::vec3 p : {glm::vec3(0.0f), glm::vec3(0.5f, 0.0f, 0.0f)})
            EXPECT_EQ(embree.surfacesAlong(p, kUp, 0.0f, kFar).translucent.size(), 1u)
                << "tilted, " << height << ", " << p.x;
    }
    Scene s = filters();
    addFan(s, 2.0f, 1.0f, 0);
    addQuad(s, {-2, 1, 2}, {2, 1, 2}, {2, 1, -1.5f}, {-2, 1, -1.5f}, 1); // off its own diagonal
    const EmbreeScene embree(s, "threads=1");
    EXPECT_EQ(embree.transmittance({0.0f, 0.0f, 0.0f}, kUp, 0.0f, kFar),
              glm::vec3(0.5f, 0.25f, 0.25f));
}

// Separate layers are counted each: two filters crossing in an X, a ray through the line they
// cross at; clear hits take no place among the 64 remembered (two hundred clear cards around a
// fan, rays through its centre and a spoke); and the ideal map's list names an opaque surface a
// hair behind a filter and reads a triangle's colours where the truth does.
TEST(TranslucentTruth, SeparateLayersCountEachAndClearOnesNone) {
    {
        Scene s = filters();
        addQuad(s, {-1, 0.5f, -1}, {1, 1.5f, -1}, {1, 1.5f, 1}, {-1, 0.5f, 1}, 0);
        addQuad(s, {-1, 1.5f, -1}, {1, 0.5f, -1}, {1, 0.5f, 1.3f}, {-1, 1.5f, 1.3f}, 1);
        const EmbreeScene embree(s, "threads=1");
        EXPECT_EQ(embree.transmittance({0.0f, 0.0f, 0.1f}, kUp, 0.0f, kFar),
                  glm::vec3(0.5f, 0.25f, 0.25f));
    }
    {
        Scene s = filters();
        addFan(s, 100.5f, 1.0f, 0); // among them
        for (int k = 0; k < 200; ++k) {
            const float y = 1.0f + static_cast<float>(k);
            addQuad(s, {-2, y, 2}, {2, y, 2}, {2, y, -1.7f}, {-2, y, -1.7f}, 3);
        }
        const EmbreeScene embree(s, "threads=1");
        EXPECT_EQ(embree.transmittance({0.0f, 0.0f, 0.0f}, kUp, 0.0f, kFar),
                  glm::vec3(1.0f, 0.5f, 0.25f));
        EXPECT_EQ(embree.transmittance({0.5f, 0.0f, 0.0f}, kUp, 0.0f, kFar),
                  glm::vec3(1.0f, 0.5f, 0.25f));
    }
    {
        Scene s = filters();
        addQuad(s, {-1, 1, 1}, {1, 1, 1}, {1, 1, -1.3f}, {-1, 1, -1.3f}, 0);
        addQuad(s, {-1, 1.000005f, 1}, {1, 1.000005f, 1}, {1, 1.000005f, -1.3f},
                {-1, 1.000005f, -1.3f}, 2);
        addQuad(s, {-1, 3, 1}, {1, 3, 1}, {1, 3, -1.3f}, {-1, 3, -1.3f}, 1,
                {1.0f, 0.2f, 0.6f, 1.0f});
        const EmbreeScene embree(s, "threads=1");
        const EmbreeScene::SurfacesAlong along =
            embree.surfacesAlong({0.1f, 0.0f, 0.2f}, kUp, 0.0f, kFar);
        EXPECT_EQ(along.translucent.size(), 1u);
        EXPECT_NEAR(along.opaque, 1.000005f, 1e-6f);
        Scene coloured = filters();
        coloured.vertices = s.vertices;
        coloured.indices.assign(s.indices.begin() + 12, s.indices.end()); // the upper filter
        for (size_t k = 8; k < 12; ++k) // its corners' colours differ
            coloured.vertices[k].color =
                glm::vec4(0.2f * static_cast<float>(k - 7), 1.0f, 0.5f, 1.0f);
        const EmbreeScene upper(coloured, "threads=1");
        const glm::vec3 p(0.3f, 0.0f, -0.6f);
        const EmbreeScene::SurfacesAlong one = upper.surfacesAlong(p, kUp, 0.0f, kFar);
        ASSERT_EQ(one.translucent.size(), 1u);
        EXPECT_EQ(one.translucent[0].transmittance, upper.transmittance(p, kUp, 0.0f, kFar));
    }
}

// A scene without translucent casters keeps its one-channel truth.
TEST(TranslucentTruth, AnOpaqueSceneHasNoColouredTruth) {
    Scene scene = builtin::sheets();
    for (Material& m : scene.materials)
        m.transmission = 0.0f, m.alphaMode = AlphaMode::Opaque;
    EXPECT_FALSE(scene.hasTranslucentCasters());
    EXPECT_TRUE(builtin::sheets().hasTranslucentCasters());
    const ReferenceResult truth = computeReference(scene, groundGrid(), {.samples = 4});
    EXPECT_TRUE(truth.transmittance.empty());
}

// A translucent surface's colours tint the truth, an opaque one's do not: only the first change
// the key.
TEST(TruthCache, ATranslucentSurfacesColoursChangeTheKey) {
    const Scene base = builtin::sheets();
    const std::string key = sweep::truthKey(base, "", 64, 48, 16);
    const auto keyWith = [](const std::function<void(Scene&)>& edit) {
        Scene s = builtin::sheets();
        edit(s);
        return sweep::truthKey(s, "", 64, 48, 16);
    };
    const auto firstVertexOf = [](Scene& s, uint32_t material) -> Vertex& {
        return *std::find_if(s.vertices.begin(), s.vertices.end(),
                             [material](const Vertex& v) { return v.material == material; });
    };
    EXPECT_NE(keyWith([](Scene& s) { s.materials[1].baseColor.y = 0.5f; }), key) << "filter";
    EXPECT_NE(keyWith([&](Scene& s) { firstVertexOf(s, 1).color.y = 0.5f; }), key)
        << "a filter's vertex";
    EXPECT_EQ(keyWith([](Scene& s) { s.materials[0].baseColor.y = 0.5f; }), key) << "ground";
    EXPECT_EQ(keyWith([&](Scene& s) { firstVertexOf(s, 0).color.y = 0.5f; }), key)
        << "a ground vertex";
}

TEST(TruthCache, KeepsAColouredTruth) {
    const std::filesystem::path dir = scratchDir("translucent", "cache");
    const sweep::TruthCache cache(dir);
    ReferenceResult truth{.width = 2,
                          .height = 1,
                          .visibility = {{0.5f, 1.0f}},
                          .transmittance = {{0.1f, 0.2f, 0.3f, 1.0f, 1.0f, 1.0f}},
                          .occluderDistance = {{2.0f, INFINITY}}};
    cache.store("k", truth);
    const std::optional<ReferenceResult> back = cache.load("k");
    ASSERT_TRUE(back);
    EXPECT_EQ(back->transmittance, truth.transmittance);
    EXPECT_EQ(back->visibility, truth.visibility);
    truth.transmittance.clear();
    cache.store("grey", truth);
    ASSERT_TRUE(cache.load("grey"));
    EXPECT_TRUE(cache.load("grey")->transmittance.empty());
}

namespace {

// A quad at y = 2 over the ground, material 0 carrying `extensions`.
GltfBuilder sheetWith(const J& extensions) {
    GltfBuilder b;
    b.ground();
    const int p = b.positions({-1, 2, -1, 1, 2, -1, 1, 2, 1, -1, 2, 1});
    const int idx = b.accessor(b.view(std::vector<uint16_t>{0, 1, 2, 0, 2, 3}), 5123, 6, "SCALAR");
    const int mesh = b.mesh(p, idx);
    b.j["meshes"][mesh]["primitives"][0]["material"] = 0;
    b.node({{"mesh", mesh}});
    b.j["materials"] =
        J::array({{{"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 0.5, 0.25, 1.0}}}},
                   {"extensions", extensions}}});
    b.j["extensionsUsed"] = {"KHR_materials_transmission", "KHR_materials_volume"};
    return b;
}

std::filesystem::path written(GltfBuilder b, const std::string& name) {
    return b.writeGltf(scratchDir("translucent", name) / "a.gltf");
}

} // namespace

TEST(GltfTransmission, TransmissionAndVolumeAreRead) {
    const J ext = {{"KHR_materials_transmission", {{"transmissionFactor", 0.75}}},
                   {"KHR_materials_volume",
                    {{"thicknessFactor", 0.5},
                     {"attenuationDistance", 2.0},
                     {"attenuationColor", {0.5, 0.25, 0.75}}}}};
    std::vector<std::string> warnings;
    const Scene s = loadScene(written(sheetWith(ext), "read").string(), {.warnings = &warnings});
    const Material& m = s.materials[0];
    EXPECT_FLOAT_EQ(m.transmission, 0.75f);
    EXPECT_FLOAT_EQ(m.thickness, 0.5f);
    EXPECT_FLOAT_EQ(m.attenuationDistance, 2.0f);
    EXPECT_EQ(m.attenuationColor, glm::vec3(0.5f, 0.25f, 0.75f));
    EXPECT_TRUE(s.hasTranslucentCasters());
    EXPECT_TRUE(warnings.empty()) << warnings.front(); // neither is an unused extension
    for (const J& empty : {J::object(), J{{"KHR_materials_transmission", J::object()},
                                          {"KHR_materials_volume", {{"thicknessFactor", 0}}}}}) {
        const Scene bare = loadScene(written(sheetWith(empty), "bare").string());
        EXPECT_EQ(bare.materials[0].transmission, 0.0f) << empty;
        EXPECT_EQ(bare.materials[0].thickness, 0.0f) << empty;
        EXPECT_TRUE(std::isinf(bare.materials[0].attenuationDistance)) << empty;
        EXPECT_EQ(bare.materials[0].attenuationColor, glm::vec3(1.0f)) << empty;
        EXPECT_FALSE(bare.hasTranslucentCasters()) << empty;
    }
}

// The transmission texture's image is decoded and read with the base colour's coordinates; one
// read with other coordinates is left out with a warning.
TEST(GltfTransmission, TheTransmissionTextureIsDecodedWhereItCanBeRead) {
    for (const int64_t texCoord : {int64_t{0}, int64_t{1}, int64_t{1} << 32}) {
        GltfBuilder b =
            sheetWith({{"KHR_materials_transmission",
                        {{"transmissionFactor", 1.0},
                         {"transmissionTexture", {{"index", 0}, {"texCoord", texCoord}}}}}});
        const int uv =
            b.accessor(b.view(std::vector<float>{0, 0, 1, 0, 1, 1, 0, 1}), 5126, 4, "VEC2");
        b.j["meshes"][1]["primitives"][0]["attributes"]["TEXCOORD_0"] = uv;
        b.j["meshes"][1]["primitives"][0]["attributes"]["TEXCOORD_1"] = uv;
        const std::vector<uint8_t> texel = {128, 0, 0, 255};
        const std::vector<uint8_t> image = encodePng(1, 1, 4, texel);
        b.j["images"] = J::array({{{"bufferView", b.view(image)}, {"mimeType", "image/png"}}});
        b.j["textures"] = J::array({{{"source", 0}}});
        std::vector<std::string> warnings;
        const Scene s = loadScene(written(b, "texture" + std::to_string(texCoord)).string(),
                                  {.warnings = &warnings});
        EXPECT_EQ(s.images.size(), 1u) << "decoded: the truth reads it";
        if (texCoord == 0) {
            EXPECT_EQ(s.materials[0].transmissionTexture, 0);
            EXPECT_TRUE(warnings.empty());
            EXPECT_NEAR(s.transmittance(0, {0.5f, 0.5f}, glm::vec4(1.0f)).x, 128.0f / 255.0f,
                        1e-6f);
        } else {
            EXPECT_EQ(s.materials[0].transmissionTexture, -1);
            ASSERT_EQ(warnings.size(), 1u);
            EXPECT_NE(warnings[0].find("transmissionTexture: read with coordinates other than the "
                                       "base colour's"),
                      std::string::npos)
                << warnings[0];
        }
    }
}

TEST(GltfTransmission, ValuesOutsideTheExtensionsRangesAreRefused) {
    const std::pair<J, std::string> cases[] = {
        {{{"KHR_materials_transmission", {{"transmissionFactor", 1.5}}}},
         "materials[0].extensions.KHR_materials_transmission.transmissionFactor: 1.5 is not a "
         "number in [0, 1]"},
        {{{"KHR_materials_transmission", {{"transmissionFactor", "half"}}}},
         "transmissionFactor: \"half\" is not a number in [0, 1]"},
        {{{"KHR_materials_transmission", 3}}, "KHR_materials_transmission: wrong JSON type"},
        {{{"KHR_materials_transmission", {{"transmissionTexture", {{"index", 4}}}}}},
         "transmissionTexture.index"},
        {{{"KHR_materials_volume", {{"thicknessFactor", -1.0}}}},
         "KHR_materials_volume.thicknessFactor: -1 is not 0 or a number in [1e-30, 1e30]"},
        {{{"KHR_materials_volume", {{"thicknessFactor", 1e-300}}}},
         "thicknessFactor: 1e-300 is not 0 or a number in [1e-30, 1e30]"},
        {{{"KHR_materials_volume", {{"attenuationDistance", 0.0}}}},
         "attenuationDistance: 0 is not a number in [1e-30, 1e30]"},
        {{{"KHR_materials_volume", {{"attenuationDistance", 1e-40}}}},
         "attenuationDistance: 1e-40 is not a number in [1e-30, 1e30]"},
        {{{"KHR_materials_volume", {{"thicknessTexture", {{"index", 9}}}}}},
         "KHR_materials_volume.thicknessTexture.index"},
        {{{"KHR_materials_volume", {{"attenuationColor", {0.5, 2.0, 0.5}}}}},
         "attenuationColor[1]: 2 is not a number in [0, 1]"},
        {{{"KHR_materials_volume", {{"attenuationColor", {0.5, 0.5}}}}},
         "attenuationColor: needs 3 numbers"},
    };
    int n = 0;
    for (const auto& [ext, expected] : cases)
        expectRefused(written(sheetWith(ext), "bad" + std::to_string(n++)), expected);
}
