// The translucent layer's maps read a material as Scene::transmittance does (docs/translucency.md,
// "Which surfaces let light through"): vertex colours and vertex alpha on a BLEND surface; a
// textured MASK surface with transmission, whose holes let everything through and whose covered
// part lets its tinted light through; a transmission texture, its bytes stored linear; and a
// leaf of two triangles back to back, which a shadow ray crosses once. Against
// the coloured truth, per channel, under a sun and a point light: one surface a texel, which both
// methods hold exactly but for the half floats and the bilinear mix of the texels at the pixel.
#include "render/scene_upload.h"
#include "scene/mesh_builder.h"
#include "truth_fixture.h"

#include <algorithm>
#include <array>
#include <cmath>

using namespace penumbra;
using namespace penumbra::test;

namespace {

// Over a 12 x 12 ground: a BLEND sheet of white glass whose four corners carry red, green, blue
// and yellow vertex colours (the last at alpha 0.5), and beside it a MASK sheet of violet glass
// whose texture's columns alternate covered and clear (nearest, so its holes have sharp edges).
Scene vertexColouredAndMaskedSheets() {
    Scene scene;
    scene.name = "translucent-materials";
    MeshBuilder mb(scene);
    mb.quad({-6, 0, 6}, {6, 0, 6}, {6, 0, -6}, {-6, 0, -6}, mb.material("ground", glm::vec3(0.7f)));

    const uint32_t glass = mb.material("white glass", glm::vec3(1.0f));
    scene.materials[glass].alphaMode = AlphaMode::Blend;
    scene.materials[glass].baseColor.w = 0.8f;
    scene.materials[glass].transmission = 0.9f;
    const size_t first = scene.vertices.size();
    mb.quad({-3.5f, 1.5f, 1.5f}, {-0.5f, 1.5f, 1.5f}, {-0.5f, 1.5f, -1.5f}, {-3.5f, 1.5f, -1.5f},
            glass);
    const std::array<glm::vec4, 4> corners{
        glm::vec4(1.0f, 0.2f, 0.2f, 1.0f), glm::vec4(0.2f, 1.0f, 0.2f, 1.0f),
        glm::vec4(0.2f, 0.2f, 1.0f, 1.0f), glm::vec4(1.0f, 1.0f, 0.2f, 0.5f)};
    for (size_t v = first; v < scene.vertices.size(); ++v) // the quad's corners, in order
        scene.vertices[v].color = corners.at(v - first);

    TextureImage stripes{.name = "stripes", .width = 8, .height = 1};
    for (uint32_t x = 0; x < stripes.width; ++x)
        stripes.rgba.insert(stripes.rgba.end(),
                            {200, 255, 160, static_cast<uint8_t>(x % 2 ? 0 : 255)});
    const uint32_t masked = mb.texturedMaterial(
        "violet stripes", stripes,
        {.wrapS = TextureWrap::ClampToEdge, .wrapT = TextureWrap::ClampToEdge, .nearest = true},
        AlphaMode::Mask);
    scene.materials[masked].baseColor = {0.7f, 0.3f, 1.0f, 1.0f};
    scene.materials[masked].transmission = 0.8f;
    mb.quad({0.5f, 2.0f, 1.5f}, {3.5f, 2.0f, 1.5f}, {3.5f, 2.0f, -1.5f}, {0.5f, 2.0f, -1.5f},
            masked);

    // Behind them, clear glass whose transmission texture's columns let 100%, 50%, 16% and 78%
    // of the light through (its red bytes, stored linear: 255, 128, 40, 200).
    scene.images.push_back({.name = "transmission", .width = 4, .height = 1});
    for (const uint8_t red : std::array<uint8_t, 4>{255, 128, 40, 200})
        scene.images.back().rgba.insert(scene.images.back().rgba.end(),
                                        {red, uint8_t{0}, uint8_t{0}, uint8_t{255}});
    scene.textures.push_back({.image = static_cast<uint32_t>(scene.images.size() - 1),
                              .wrapS = TextureWrap::ClampToEdge,
                              .wrapT = TextureWrap::ClampToEdge,
                              .nearest = true});
    const uint32_t clear = mb.material("clear glass", {0.9f, 0.9f, 0.5f});
    scene.materials[clear].transmission = 1.0f;
    scene.materials[clear].transmissionTexture = static_cast<int32_t>(scene.textures.size() - 1);
    mb.quad({-2.0f, 1.0f, -2.0f}, {2.0f, 1.0f, -2.0f}, {2.0f, 1.0f, -4.5f}, {-2.0f, 1.0f, -4.5f},
            clear);

    // Above the camera's side, a green leaf modelled as two quads back to back, each culled from
    // behind: a shadow ray crosses it once (the truth's rule), so the layer's maps draw it once.
    const uint32_t leaf = mb.material("leaf", {0.3f, 0.9f, 0.3f});
    scene.materials[leaf].alphaMode = AlphaMode::Blend;
    scene.materials[leaf].baseColor.w = 0.6f;
    scene.materials[leaf].transmission = 0.7f;
    scene.materials[leaf].doubleSided = false;
    const glm::vec3 a{-1.0f, 3.0f, 4.0f}, b{1.0f, 3.0f, 4.0f}, c{1.0f, 3.0f, 2.5f},
        d{-1.0f, 3.0f, 2.5f};
    mb.quad(a, b, c, d, leaf); // facing up: triangles abc, acd
    mb.quad(a, d, c, b, leaf); // facing down: adc, acb, on the same corners

    scene.cameras.push_back({.name = "above",
                             .position = {0.0f, 9.0f, 6.0f},
                             .target = {0.0f, 0.0f, -0.5f},
                             .yfov = 1.0f,
                             .znear = 0.1f,
                             .zfar = 60.0f});
    return scene;
}

// Pixels the metrics count whose truth is strictly between dark and lit and changes by at most
// 0.1 (luminance) within two pixels: inside the sheets' shadows, off their edges and the
// stripes' (the truth is one ray a pixel there).
std::vector<size_t> insideTheTint(const Truth& t) {
    const std::vector<float>& truth = t.reference.visibility[0];
    const auto w = static_cast<int>(t.setup.width), h = static_cast<int>(t.setup.height);
    std::vector<size_t> inside;
    for (size_t i = 0; i < truth.size(); ++i) {
        if (!t.mask[i] || !(truth[i] > 0.02f && truth[i] < 0.98f))
            continue;
        const int x = static_cast<int>(i) % w, y = static_cast<int>(i) / w;
        bool flat = true;
        for (int v = std::max(0, y - 2); flat && v <= std::min(h - 1, y + 2); ++v)
            for (int u = std::max(0, x - 2); flat && u <= std::min(w - 1, x + 2); ++u)
                flat = std::abs(truth[size_t(v * w + u)] - truth[i]) <= 0.1f;
        if (flat)
            inside.push_back(i);
    }
    return inside;
}

// The worst channel's RMSE of `rgb` (3 floats a pixel) against the truth's over `pixels`.
double worstChannelRmse(const std::vector<float>& rgb, const std::vector<float>& truth,
                        const std::vector<size_t>& pixels) {
    std::array<double, 3> sum{};
    for (size_t i : pixels)
        for (size_t c = 0; c < 3; ++c)
            sum[c] += std::pow(double{rgb[3 * i + c]} - truth[3 * i + c], 2.0);
    double worst = 0.0;
    for (double s : sum)
        worst =
            std::max(worst, std::sqrt(s / static_cast<double>(std::max<size_t>(pixels.size(), 1))));
    return worst;
}

} // namespace

TEST_F(LayerTest, TranslucentLayerReadsVertexColoursAndMaskedTransmission) {
    Scene scene = vertexColouredAndMaskedSheets();
    const Light sun{.name = "sun",
                    .type = LightType::Directional,
                    .direction = glm::normalize(glm::vec3(0.15f, -1.0f, 0.1f))};
    const Light point{.name = "point", .type = LightType::Point, .position = {0.0f, 6.0f, 0.5f}};
    for (const Light& light : {sun, point}) {
        scene.lights = {light};
        const Truth t =
            groundTruth(scene, {.width = 256, .height = 192, .shadowMapSize = 1024, .samples = 1});
        const std::vector<size_t> pixels = insideTheTint(t);
        const std::vector<float>& truth = t.reference.transmittance.at(0);
        // The sheets cast opaque: their grey visibility (0) in every channel.
        std::vector<float> grey(3 * t.reference.visibility[0].size());
        const RenderResult opaque = renderRow(t, Technique::Hard, {});
        for (size_t i = 0; i < opaque.visibility[0].size(); ++i)
            std::fill_n(grey.begin() + static_cast<long>(3 * i), 3, opaque.visibility[0][i]);
        const double opaqueError = worstChannelRmse(grey, truth, pixels);
        for (const char* method : {"coloured", "moments"}) {
            const RenderResult r = renderRow(t, Technique::Hard, {{"translucent.method", method}});
            const double error = worstChannelRmse(r.transmittance.at(0), truth, pixels);
            std::printf("%s, %s: %zu tinted pixels, worst channel RMSE %.4f (cast opaque %.4f)\n",
                        light.name.c_str(), method, pixels.size(), error, opaqueError);
            EXPECT_GT(pixels.size(), 500u) << light.name;
            EXPECT_LT(error, 0.01) << light.name << ", " << method;
            EXPECT_GT(opaqueError, 0.3) << light.name;
        }
    }
}

// A sheet that lets nothing through (BLEND at alpha 1, no transmission) filters as pcf's bilinear
// 4-tap filters it cast opaque: the layer's pass reads the 2x2 texels around the receiver with
// the same weights, texel centres at half-integers, for a sun, a spot and a point light. Ground
// pixels only (the sheet's own surface takes each method's bias), no normal offset, receiver
// plane nor cascade blend on pcf's side.
TEST_F(LayerTest, TranslucentLayerMixesTexelsAsBilinearPcfDoes) {
    Scene scene = vertexColouredAndMaskedSheets();
    scene.materials.resize(1); // the ground's; every sheet becomes the opaque blend below
    const uint32_t dark = static_cast<uint32_t>(scene.materials.size());
    scene.materials.push_back({.name = "dark", .alphaMode = AlphaMode::Blend});
    for (Vertex& v : scene.vertices)
        if (v.material != 0)
            v.material = dark, v.color = glm::vec4(1.0f); // no vertex alpha either
    const std::vector<Light> lights{
        {.name = "sun",
         .type = LightType::Directional,
         .direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f))},
        {.name = "spot",
         .type = LightType::Spot,
         .position = {0.5f, 6.0f, 1.0f},
         .direction = glm::normalize(glm::vec3(-0.1f, -1.0f, -0.2f)),
         .outerConeAngle = 1.0f},
        {.name = "point", .type = LightType::Point, .position = {0.0f, 6.0f, 0.5f}}};
    for (const Light& light : lights) {
        scene.lights = {light};
        RenderOptions o{.width = 160, .height = 120, .shadowMapSize = 256, .frames = 1};
        o.parameters.set("bias.normal", "0");
        o.parameters.set("bias.receiver", "off");
        o.parameters.set("csm.blend", "0"); // the layer's pass picks one cascade
        for (const char* method : {"coloured", "moments"}) {
            o.technique = Technique::Hard;
            o.parameters.set("translucent.method", method);
            const RenderResult layer = render(scene, o);
            o.technique = Technique::Pcf;
            o.parameters.set("pcf.filter", "bilinear");
            o.parameters.set("translucent.method", "off");
            const RenderResult pcf = render(scene, o);
            size_t ground = 0, partial = 0, off = 0;
            float worst = 0.0f;
            for (size_t i = 0; i < pcf.visibility[0].size(); ++i) {
                if (!onGround(pcf, i))
                    continue;
                ++ground;
                partial += pcf.visibility[0][i] > 0.02f && pcf.visibility[0][i] < 0.98f;
                const float gap = std::abs(layer.visibility[0][i] - pcf.visibility[0][i]);
                worst = std::max(worst, gap);
                off += gap > 1e-3f;
            }
            std::printf("%s, %s: %zu ground pixels, %zu on filtered edges, %zu off by more than "
                        "1e-3, worst gap %.2g\n",
                        light.name.c_str(), method, ground, partial, off, worst);
            EXPECT_GT(partial, 140u) << light.name;
            // A sun's pixel may straddle a cascade's border, where pcf's taps past it read lit
            // and the layer's pass the border's texels (measured: one pixel, 0.025 off).
            EXPECT_LE(off, 2u) << light.name << ", " << method;
            EXPECT_LT(worst, 0.05f) << light.name << ", " << method;
        }
    }
}

// What a volume's face keeps on the GPU (render::translucentConstants, Scene::transmittance's
// rule): half the path's Beer-Lambert attenuation over the thickness, each channel c^(t / 2d);
// without an attenuation distance (infinite: glTF's default) nothing, even where the colour is 0.
TEST_F(LayerTest, TranslucentVolumeAttenuatesOnlyOverAFiniteDistance) {
    Material glass{.name = "glass", .transmission = 1.0f, .thickness = 1.0f};
    glass.attenuationColor = {0.0f, 0.5f, 1.0f};
    const glm::vec4 none = render::translucentConstants(glass).attenuation;
    EXPECT_EQ(glm::vec3(none), glm::vec3(1.0f)) << none.x << " " << none.y << " " << none.z;
    glass.attenuationDistance = 2.0f;
    const glm::vec4 some = render::translucentConstants(glass).attenuation;
    EXPECT_EQ(some.x, 0.0f);
    EXPECT_NEAR(some.y, std::pow(0.5f, 0.25f), 1e-6f);
    EXPECT_NEAR(some.z, 1.0f, 1e-6f);
    EXPECT_NE(render::translucentConstants(glass).flags.x & TRANSLUCENT_VOLUME, 0u);
}

// A surface that lets everything through (a card that is all hole, as a leaf card's clear border
// is) is no surface to the coloured map: its fragments are dropped, or the card would take the
// nearest depth and push the two real sheets below it into the nearest's and the product's
// places. On the lower sheet's own top, between the two, the truth is the upper sheet's tint.
TEST_F(LayerTest, TranslucentLayerDropsWhatLetsEverythingThrough) {
    Scene scene;
    scene.name = "clear-card";
    MeshBuilder mb(scene);
    mb.quad({-6, 0, 6}, {6, 0, 6}, {6, 0, -6}, {-6, 0, -6}, mb.material("ground", glm::vec3(0.7f)));
    const auto sheet = [&](const char* name, glm::vec3 colour, float y, float half) {
        const uint32_t m = mb.material(name, colour);
        scene.materials[m].transmission = 1.0f;
        mb.quad({-half, y, half}, {half, y, half}, {half, y, -half}, {-half, y, -half}, m);
        return m;
    };
    // All hole (MASK at alpha 0, translucent by its transmission): the camera sees through it too.
    const uint32_t card = sheet("clear card", glm::vec3(1.0f), 3.0f, 3.0f);
    scene.materials[card].alphaMode = AlphaMode::Mask;
    scene.materials[card].baseColor.w = 0.0f;
    sheet("red", {1.0f, 0.3f, 0.3f}, 2.0f, 1.5f);
    sheet("green", {0.3f, 1.0f, 0.3f}, 1.0f, 2.5f);
    scene.cameras.push_back({.name = "above",
                             .position = {0.0f, 9.0f, 6.0f},
                             .target = {0.0f, 0.0f, 0.0f},
                             .yfov = 0.9f,
                             .znear = 0.1f,
                             .zfar = 60.0f});
    scene.lights = {{.name = "sun",
                     .type = LightType::Directional,
                     .direction = glm::normalize(glm::vec3(0.0f, -1.0f, 0.8f))}};
    const Truth t =
        groundTruth(scene, {.width = 192, .height = 144, .shadowMapSize = 1024, .samples = 1});
    // The green sheet's top under the red one, off the edges.
    std::vector<size_t> onGreen;
    for (size_t i : insideTheTint(t))
        if (std::abs(pixelVec(t.gbuffer.position, i).y - 1.0f) < 1e-3f)
            onGreen.push_back(i);
    const RenderResult r = renderRow(t, Technique::Hard, {{"translucent.method", "coloured"}});
    const double error =
        worstChannelRmse(r.transmittance.at(0), t.reference.transmittance.at(0), onGreen);
    std::printf("%zu pixels on the green sheet under the red one: worst channel RMSE %.4f\n",
                onGreen.size(), error);
    EXPECT_GT(onGreen.size(), 500u);
    EXPECT_LT(error, 0.01);
}
