// The lit image (image.png) for every light type, against the composite's contract computed on
// the CPU from the G-buffer's positions and normals: ambient + sum over lights of
// 2^EV x colour x intensity x max(N.L, 0) x attenuation x (1 - shadowIntensity x (1 - v)), with
// v per channel where the translucent layer tints the light,
// the exponential tone curve 1 - exp(-albedo x light), sRGB. Attenuation: glTF
// KHR_lights_punctual's inverse square with the range window (1 - (d/range)^4)^2 for spot and
// point lights; the spot cone's smoothstep from cos(outer) to cos(inner) (docs/architecture.md).
// Written from those formulas, not from shaders/composite.comp.
#include "bindings.h"
#include "gpu_fixture.h"
#include "scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

using namespace penumbra;
using namespace penumbra::test;

namespace {

constexpr glm::vec3 kGroundColour{0.6f, 0.45f, 0.3f};
constexpr glm::vec3 kSlabColour{0.3f, 0.5f, 0.7f};

struct CompositeKnobs {
    double ambient = 0.12, shadowIntensity = 1.0, exposureEv = 0.0;
};

constexpr glm::vec3 kSlabCentre{-0.5f, 1.6f, 0.5f}, kSlabSize{3.0f, 0.6f, 2.4f};

// A 20 x 20 ground at y = 0 under a floating slab (its shadow), seen from above at an angle.
Scene groundUnderSlab(std::vector<Light> lights) {
    Scene scene;
    scene.name = "lighting";
    MeshBuilder mb(scene);
    const uint32_t ground = mb.material("ground", kGroundColour);
    mb.quad({-10, 0, 10}, {10, 0, 10}, {10, 0, -10}, {-10, 0, -10}, ground);
    const glm::mat4 slab = glm::scale(glm::translate(glm::mat4(1.0f), kSlabCentre), kSlabSize);
    mb.box(slab, mb.material("slab", kSlabColour));
    scene.lights = std::move(lights);
    scene.cameras.push_back({.name = "above",
                             .position = {0.0f, 12.0f, 9.0f},
                             .target = {0.0f, 0.0f, -0.5f},
                             .yfov = 1.15f,
                             .znear = 0.1f,
                             .zfar = 100.0f});
    return scene;
}

double smoothstep(double e0, double e1, double x) {
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// Distance and cone attenuation of `light` at `p` (1 for a directional light).
double attenuation(const Light& light, const glm::dvec3& p) {
    if (light.type == LightType::Directional)
        return 1.0;
    const double d = glm::length(glm::dvec3(light.position) - p);
    double window = 1.0;
    if (light.range > 0.0f) {
        const double x = d / light.range;
        window = std::clamp(1.0 - x * x * x * x, 0.0, 1.0);
    }
    double a = window * window / (d * d);
    if (light.type == LightType::Spot) {
        const double along = glm::dot(glm::normalize(p - glm::dvec3(light.position)),
                                      glm::normalize(glm::dvec3(light.direction)));
        a *= smoothstep(std::cos(light.outerConeAngle), std::cos(light.innerConeAngle), along);
    }
    return a;
}

glm::dvec3 towardsLight(const Light& light, const glm::dvec3& p) {
    return light.type == LightType::Directional ? -glm::normalize(glm::dvec3(light.direction))
                                                : glm::normalize(glm::dvec3(light.position) - p);
}

double srgbEncode(double c) {
    c = std::clamp(c, 0.0, 1.0);
    return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

// The outward normal of the ground or the slab at p, from the geometry (not the G-buffer).
glm::dvec3 trueNormal(const glm::dvec3& p, bool ground) {
    if (ground)
        return {0, 1, 0};
    const glm::dvec3 d = (p - glm::dvec3(kSlabCentre)) / glm::dvec3(kSlabSize); // faces at +-1/2
    const glm::dvec3 a = glm::abs(d);
    const int axis = a.x >= a.y && a.x >= a.z ? 0 : a.y >= a.z ? 1 : 2;
    glm::dvec3 n(0.0);
    n[axis] = d[axis] > 0 ? 1.0 : -1.0;
    return n;
}

struct ImageCheck {
    size_t pixels = 0, ground = 0, facingAway = 0, offByMoreThanOne = 0, wrongNormals = 0;
    int worst = 0;
};

// Compares every pixel of r.image that shows the ground or the slab with the contract's value.
ImageCheck checkImage(const Scene& scene, const RenderResult& r, const CompositeKnobs& k) {
    // The G-buffer stores the base colour in 8 bits.
    auto stored = [](glm::vec3 c) { return glm::round(glm::dvec3(c) * 255.0) / 255.0; };
    const double exposure = std::exp2(k.exposureEv);
    ImageCheck c;
    for (size_t i = 0; i < size_t{r.width} * r.height; ++i) {
        const glm::dvec3 p = pixelVec(r.position, i);
        if (!std::isfinite(p.x))
            continue;
        const bool ground = std::abs(p.y) < 1e-3;
        const glm::dvec3 n = trueNormal(p, ground);
        c.wrongNormals += glm::length(glm::dvec3(pixelVec(r.normal, i)) - n) > 1e-3;
        c.ground += ground;
        const glm::dvec3 albedo = stored(ground ? kGroundColour : kSlabColour);
        glm::dvec3 light(k.ambient);
        for (const LightShadow& s : r.lights) {
            const Light& l = scene.lights[s.sceneLight];
            const double v = s.visibilityIndex >= 0 ? r.visibility[s.visibilityIndex][i] : 1.0;
            // Per channel where the translucent layer ran (its light through, tint and all).
            const glm::dvec3 through =
                s.visibilityIndex >= 0 && !r.transmittance.empty()
                    ? glm::dvec3(pixelVec(r.transmittance[s.visibilityIndex], i))
                    : glm::dvec3(v);
            const double nDotL = glm::dot(n, towardsLight(l, p));
            c.facingAway += nDotL < -0.1;
            const double lambert = std::max(nDotL, 0.0);
            light += exposure * glm::dvec3(l.color) * double(l.intensity) * lambert *
                     attenuation(l, p) * (1.0 - k.shadowIntensity * (1.0 - through));
        }
        ++c.pixels;
        for (int ch = 0; ch < 3; ++ch) {
            const double expected = 255.0 * srgbEncode(1.0 - std::exp(-albedo[ch] * light[ch]));
            const int diff =
                static_cast<int>(std::lround(std::abs(expected - r.image[4 * i + ch])));
            c.worst = std::max(c.worst, diff);
            c.offByMoreThanOne += diff > 1;
        }
    }
    return c;
}

RenderResult renderWith(const Scene& scene, const CompositeKnobs& k,
                        const std::vector<std::string>& extra = {}) {
    RenderOptions o{.width = 320, .height = 240, .frames = 1};
    for (const std::string& setting : extra)
        o.parameters.assign(setting);
    o.parameters.set("composite.ambient", std::to_string(k.ambient));
    o.parameters.set("composite.shadowIntensity", std::to_string(k.shadowIntensity));
    o.parameters.set("composite.exposure", std::to_string(k.exposureEv));
    return sharedRenderer().render(scene, o);
}

// `facingAway`: how many pixels must face away from a light (Lambert's clamp at work).
void expectImageFollowsTheContract(const Scene& scene, const RenderResult& r,
                                   const CompositeKnobs& k, const char* what,
                                   size_t facingAway = 0) {
    const ImageCheck c = checkImage(scene, r, k);
    std::printf("%s: %zu pixels (%zu ground, %zu facing away from a light), worst channel "
                "difference %d/255, %zu channels off by more than 1\n",
                what, c.pixels, c.ground, c.facingAway, c.worst, c.offByMoreThanOne);
    ASSERT_GT(c.ground, 320u * 240u / 3) << what;
    EXPECT_GE(c.facingAway, facingAway) << what << ": the slab's unlit sides must be in view";
    EXPECT_LE(c.worst, 2) << what;
    EXPECT_LE(c.offByMoreThanOne, c.pixels / 1000) << what;
    EXPECT_EQ(c.wrongNormals, 0u) << what << ": normals in the G-buffer";
}

// Fractions of ground pixels with attenuation-factor `f` equal to 0, strictly between, and 1.
struct Spread {
    double none = 0, partial = 0, full = 0, shadowed = 0;
};

template <typename Factor>
Spread spreadOf(const RenderResult& r, Factor factor) {
    Spread s;
    size_t n = 0;
    for (size_t i = 0; i < size_t{r.width} * r.height; ++i) {
        if (!onGround(r, i))
            continue;
        ++n;
        const double f = factor(glm::dvec3(pixelVec(r.position, i)));
        (f <= 0.0 ? s.none : f >= 1.0 ? s.full : s.partial) += 1;
        if (!r.visibility.empty() && r.visibility[0][i] < 0.5f)
            s.shadowed += 1;
    }
    for (double* x : {&s.none, &s.partial, &s.full, &s.shadowed})
        *x /= static_cast<double>(std::max<size_t>(n, 1));
    return s;
}

Light spotLight() {
    return {.name = "spot",
            .type = LightType::Spot,
            .position = {-0.5f, 6.0f, 1.5f},
            .direction = glm::normalize(glm::vec3(0.5f, -6.0f, -2.0f)),
            .color = {1.0f, 0.9f, 0.8f},
            .intensity = 55.0f,
            .innerConeAngle = 0.45f,
            .outerConeAngle = 0.7f};
}

Light pointLight() {
    return {.name = "bulb",
            .type = LightType::Point,
            .position = {2.0f, 2.5f, -1.5f},
            .color = {0.8f, 0.9f, 1.0f},
            .intensity = 14.0f,
            .range = 7.5f};
}

Light sunLight() {
    return {.name = "sun",
            .type = LightType::Directional,
            .direction = glm::normalize(glm::vec3(0.5f, -1.0f, 0.6f)),
            .color = {1.0f, 0.95f, 0.9f},
            .intensity = 1.4f};
}

// A shadowing spot, point light and sun (visibility layers 0, 1 and 2) and a point light that
// casts no shadow (no visibility layer: fully lit).
Scene everyKindOfLight() {
    Light fill = pointLight();
    fill.castsShadow = false;
    fill.position += glm::vec3(1.5f, 0.5f, -1.0f);
    return groundUnderSlab({spotLight(), pointLight(), sunLight(), fill});
}
constexpr CompositeKnobs kEveryKindKnobs{
    .ambient = 0.1, .shadowIntensity = 0.8, .exposureEv = -1.0};

} // namespace

TEST_F(LightingTest, SunLightsTheGroundByLambertAndShadowIntensity) {
    const Scene scene = groundUnderSlab({sunLight()});
    const CompositeKnobs k{.ambient = 0.2, .shadowIntensity = 0.6, .exposureEv = -0.5};
    const RenderResult r = renderWith(scene, k);
    expectImageFollowsTheContract(scene, r, k, "sun, shadow intensity 0.6, EV -0.5", 150);
    const Spread s = spreadOf(r, [](const glm::dvec3&) { return 1.0; });
    EXPECT_GT(s.shadowed, 0.02) << "the slab's shadow must be in view";
}

TEST_F(LightingTest, SpotConeFadesFromInnerToOuterAngle) {
    const Scene scene = groundUnderSlab({spotLight()});
    const CompositeKnobs k{};
    const RenderResult r = renderWith(scene, k);
    expectImageFollowsTheContract(scene, r, k, "spot");
    const Light spot = scene.lights[0];
    const Spread s = spreadOf(r, [&](const glm::dvec3& p) {
        const double along =
            glm::dot(glm::normalize(p - glm::dvec3(spot.position)), glm::dvec3(spot.direction));
        return smoothstep(std::cos(spot.outerConeAngle), std::cos(spot.innerConeAngle), along);
    });
    std::printf("spot: outside the cone %.2f, in its rim %.2f, inside %.2f, shadowed %.3f\n",
                s.none, s.partial, s.full, s.shadowed);
    EXPECT_GT(s.none, 0.2) << "ground outside the cone must be in view";
    EXPECT_GT(s.partial, 0.03) << "the cone's rim must be in view";
    EXPECT_GT(s.full, 0.03) << "the cone's core must be in view";
    EXPECT_GT(s.shadowed, 0.01) << "the slab's shadow must be in view";
}

TEST_F(LightingTest, PointLightFallsOffWithDistanceAndRange) {
    const Scene scene = groundUnderSlab({pointLight()});
    const CompositeKnobs k{.ambient = 0.05, .shadowIntensity = 1.0, .exposureEv = 1.0};
    const RenderResult r = renderWith(scene, k);
    expectImageFollowsTheContract(scene, r, k, "point, range 7.5, EV +1");
    const Light bulb = scene.lights[0];
    const Spread s = spreadOf(r, [&](const glm::dvec3& p) {
        const double x = glm::length(p - glm::dvec3(bulb.position)) / bulb.range;
        return x >= 1.0 ? 0.0 : 0.5; // beyond the range, or inside it
    });
    std::printf("point: beyond its range %.2f, within %.2f\n", s.none, s.partial);
    EXPECT_GT(s.none, 0.1) << "ground beyond the range must be in view";
    EXPECT_GT(s.partial, 0.2);
}

TEST_F(LightingTest, LightsOfEveryTypeAddUp) {
    const Scene scene = everyKindOfLight();
    const CompositeKnobs k = kEveryKindKnobs;
    const RenderResult r = renderWith(scene, k);
    ASSERT_EQ(r.visibility.size(), 3u);
    ASSERT_EQ(r.lights.size(), 4u);
    EXPECT_EQ(r.lights[1].visibilityIndex, 1);
    EXPECT_EQ(r.lights[3].visibilityIndex, -1);
    expectImageFollowsTheContract(scene, r, k, "spot + point + sun", 300);
}

// The last shadowed light's visibility dispatch shades the pixel (composite.fused, the default);
// composite.comp does it on its own when asked, or when no light has a shadow map. Both follow
// the contract, and they agree pixel for pixel.
TEST_F(LightingTest, SeparateCompositeMatchesTheFusedOne) {
    const Scene scene = everyKindOfLight();
    const CompositeKnobs k = kEveryKindKnobs;
    const RenderResult fused = renderWith(scene, k);
    const RenderResult separate = renderWith(scene, k, {"composite.fused=0"});
    expectImageFollowsTheContract(scene, separate, k, "separate composite", 300);
    ASSERT_EQ(fused.image.size(), separate.image.size());
    size_t differ = 0;
    int worst = 0;
    for (size_t i = 0; i < fused.image.size(); ++i) {
        const int d = std::abs(int(fused.image[i]) - int(separate.image[i]));
        differ += d != 0, worst = std::max(worst, d);
    }
    EXPECT_LE(worst, 1);
    EXPECT_LE(differ, fused.image.size() / 1000);
    ASSERT_EQ(fused.visibility.size(), separate.visibility.size());
    for (size_t l = 0; l < fused.visibility.size(); ++l)
        for (size_t i = 0; i < fused.visibility[l].size(); ++i)
            ASSERT_TRUE(
                fused.visibility[l][i] == separate.visibility[l][i] ||
                (std::isnan(fused.visibility[l][i]) && std::isnan(separate.visibility[l][i])))
                << "light " << l << ", pixel " << i;

    Scene unshadowed = scene; // composite.comp alone: no visibility dispatch at all
    for (Light& l : unshadowed.lights)
        l.castsShadow = false;
    expectImageFollowsTheContract(unshadowed, renderWith(unshadowed, k), k, "no shadow maps", 300);
}

// Past MAX_SPECIALIZED_LIGHTS the shading loop reads the lights' count and kinds at run time.
TEST_F(LightingTest, LightsBeyondTheSpecialisedCountAddUp) {
    std::vector<Light> lights{spotLight(), sunLight()};
    for (int i = 0; lights.size() <= MAX_SPECIALIZED_LIGHTS; ++i) {
        Light l = i % 2 ? spotLight() : pointLight();
        const float angle = 0.7f * static_cast<float>(i);
        l.position += glm::vec3(std::cos(angle), 0.2f * static_cast<float>(i % 3), std::sin(angle));
        l.intensity *= 0.15f;
        l.castsShadow = false;
        lights.push_back(l);
    }
    const Scene scene = groundUnderSlab(lights);
    ASSERT_GT(scene.lights.size(), MAX_SPECIALIZED_LIGHTS);
    const CompositeKnobs k{.ambient = 0.05, .shadowIntensity = 0.9, .exposureEv = -1.5};
    const RenderResult r = renderWith(scene, k);
    ASSERT_EQ(r.visibility.size(), 2u);
    expectImageFollowsTheContract(scene, r, k, "18 lights", 150);
}

// A translucent slab (bluish glass: KHR_materials_transmission) under a spot, a point light and a
// sun: the composite shades each channel with the translucent layer's light per channel (read
// back as RenderResult::transmittance), whose luminance is the light's visibility after every
// layer, the contact layer's too (it runs before); and the tint shows, its blue above its red
// where light passes the slab.
TEST_F(LightingTest, TranslucentCastersTintEachLightInTheImage) {
    Scene scene = everyKindOfLight();
    Material& slab = scene.materials.back();
    ASSERT_EQ(slab.name, "slab");
    slab.transmission = 0.9f; // tinted by its base colour (a BLEND surface alone casts grey)
    scene.lights.resize(3);   // the unshadowed fill adds nothing the others test
    const CompositeKnobs k = kEveryKindKnobs;
    for (const char* contact : {"contact.length=0", "contact.length=2"}) {
        const RenderResult r = renderWith(scene, k, {"translucent.method=coloured", contact});
        ASSERT_EQ(r.transmittance.size(), 3u);
        for (size_t l = 0; l < r.transmittance.size(); ++l) {
            size_t tinted = 0, ground = 0;
            double gap = 0.0;
            for (size_t i = 0; i < size_t{r.width} * r.height; ++i) {
                const glm::dvec3 t(pixelVec(r.transmittance[l], i));
                if (std::isnan(r.visibility[l][i]))
                    continue;
                gap = std::max(
                    gap, std::abs(0.2126 * t.x + 0.7152 * t.y + 0.0722 * t.z - r.visibility[l][i]));
                if (onGround(r, i)) {
                    ++ground;
                    tinted += t.z > t.x + 0.05;
                }
            }
            std::printf("%s, light %zu: %.1f%% of the ground tinted, worst luminance gap %.2g\n",
                        contact, l, 100.0 * double(tinted) / double(ground), gap);
            EXPECT_LT(gap, 1e-5) << contact << ", light " << l;
            if (contact == std::string("contact.length=0")) { // contact shades the slab's shadow
                EXPECT_GT(tinted, ground / 100) << "light " << l;
            }
        }
        expectImageFollowsTheContract(scene, r, k, contact, 300);
    }
}
