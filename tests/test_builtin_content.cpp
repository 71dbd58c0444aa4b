// What each built-in scene holds, pinned (docs/testing.md, "Built-in scenes"): its triangles,
// their area and where it lies, the materials' colours and light paths weighted by area, its
// textures, lights and cameras. The stored figures, the docs' measurements and the users'
// comparisons all rest on these scenes, and most of their numbers (a floor's albedo, a lead
// bar's width, a post's foot) reach no shadow test: a change to a scene is a decision, made here
// by pasting the row the failure prints.
#include "penumbra/scene.h"

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>

using namespace penumbra;

namespace {

constexpr const char* kFigureNames[] = {"area",   "centre.x",    "centre.y", "centre.z",
                                        "spread", "albedo.r",    "albedo.g", "albedo.b",
                                        "alpha",  "translucent", "masked",   "transmission",
                                        "volume", "texels",      "lights",   "cameras"};
constexpr size_t kFigures = std::size(kFigureNames);
using Figures = std::array<double, kFigures>;

struct Content {
    std::string_view scene;
    size_t triangles = 0, vertices = 0;
    Figures figures{};
};

double weighted(glm::dvec3 v, double a, double b, double c) {
    return a * v.x + b * v.y + c * v.z;
}

// The figures of `scene`; triangles take their first vertex's material.
Content measure(std::string_view name, const Scene& scene) {
    Content out{
        .scene = name, .triangles = scene.triangleCount(), .vertices = scene.vertices.size()};
    double area = 0.0, spread = 0.0, alpha = 0.0, translucent = 0.0, masked = 0.0;
    double transmission = 0.0, volume = 0.0;
    glm::dvec3 centre(0.0), albedo(0.0);
    for (size_t t = 0; t + 2 < scene.indices.size(); t += 3) {
        const Vertex* v[3];
        for (int k = 0; k < 3; ++k)
            v[k] = &scene.vertices.at(scene.indices[t + size_t(k)]);
        const glm::dvec3 p0(v[0]->position), p1(v[1]->position), p2(v[2]->position);
        const double a = 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
        const glm::dvec3 c = (p0 + p1 + p2) / 3.0;
        const glm::dvec4 colour =
            (glm::dvec4(v[0]->color) + glm::dvec4(v[1]->color) + glm::dvec4(v[2]->color)) / 3.0;
        const Material& m = scene.materials.at(v[0]->material);
        area += a;
        centre += a * c;
        spread += a * glm::dot(c, c);
        albedo += a * glm::dvec3(m.baseColor) * glm::dvec3(colour);
        alpha += a * m.baseColor.w * colour.w;
        translucent += m.translucent() ? a : 0.0;
        masked += m.alphaTested() ? a * m.alphaCutoff : 0.0;
        transmission += a * (m.transmission + (m.transmissionTexture >= 0 ? 1.0 : 0.0));
        const double absorbs =
            std::isfinite(m.attenuationDistance)
                ? weighted(glm::dvec3(m.attenuationColor), 1, 2, 3) / m.attenuationDistance
                : 0.0;
        volume += a * (m.thickness + absorbs);
    }
    double texels = 0.0;
    for (const TextureImage& image : scene.images) {
        double sum = 0.0;
        for (const uint8_t byte : image.rgba)
            sum += byte;
        texels += image.width + 2.0 * image.height + (image.rgba.empty() ? 0.0 : sum / 255.0);
    }
    double lights = 0.0, cameras = 0.0;
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& l = scene.lights[i];
        lights += double(i + 1) *
                  (weighted(l.position, 1, 2, 3) + weighted(l.direction, 4, 5, 6) +
                   weighted(l.color, 7, 8, 9) + l.intensity + 2.0 * l.range +
                   3.0 * l.innerConeAngle + 4.0 * l.outerConeAngle + 5.0 * l.radius +
                   6.0 * l.angularDiameter + 7.0 * double(l.type) + (l.castsShadow ? 8.0 : 0.0));
    }
    for (size_t i = 0; i < scene.cameras.size(); ++i) {
        const Camera& c = scene.cameras[i];
        cameras += double(i + 1) * (weighted(c.position, 1, 2, 3) + weighted(c.target, 4, 5, 6) +
                                    weighted(c.up, 7, 8, 9) + c.yfov + 2.0 * c.ymag +
                                    3.0 * c.znear + 4.0 * c.zfar + (c.orthographic ? 5.0 : 0.0));
    }
    const double per = area > 0.0 ? 1.0 / area : 0.0;
    out.figures = {area,         centre.x * per, centre.y * per, centre.z * per,
                   spread * per, albedo.x * per, albedo.y * per, albedo.z * per,
                   alpha * per,  translucent,    masked,         transmission * per,
                   volume * per, texels,         lights,         cameras};
    return out;
}

// Measured with this file's code; paste what a failure prints to store a scene's change.
const Content kStored[] = {
#include "builtin_content.inc"
};

std::string row(const Content& c) {
    std::string s = "    {\"" + std::string(c.scene) + "\", " + std::to_string(c.triangles) + ", " +
                    std::to_string(c.vertices) + ", {";
    for (size_t i = 0; i < kFigures; ++i) {
        char number[32];
        std::snprintf(number, sizeof number, "%.9g", c.figures[i]);
        s += (i ? ", " : "") + std::string(number);
    }
    return s + "}},";
}

} // namespace

// Each built-in scene (the animated ones at time 0) against its stored row. Figures are sums in
// double of the scene's floats, which the builders compute in float: 1e-6 of a figure (or of 1)
// covers a compiler's rounding, and any change to a scene's numbers moves a figure far more.
TEST(BuiltinContent, EachSceneHoldsWhatItsRowStores) {
    size_t checked = 0;
    for (const std::string_view name : builtinSceneNames()) {
        const Content got = measure(name, loadScene("builtin:" + std::string(name)));
        const Content* stored = nullptr;
        for (const Content& c : kStored)
            if (c.scene == name)
                stored = &c;
        if (!stored) {
            ADD_FAILURE() << "builtin:" << name << " has no stored row; add\n" << row(got);
            continue;
        }
        ++checked;
        bool same = got.triangles == stored->triangles && got.vertices == stored->vertices;
        std::string moved;
        for (size_t i = 0; i < kFigures; ++i) {
            const double want = stored->figures[i];
            if (std::abs(got.figures[i] - want) > 1e-6 * std::max(1.0, std::abs(want))) {
                same = false;
                moved += " " + std::string(kFigureNames[i]);
            }
        }
        EXPECT_TRUE(same) << "builtin:" << name << " changed (" << got.triangles << " triangles, "
                          << got.vertices << " vertices; moved:" << moved << "); if meant, store\n"
                          << row(got);
    }
    EXPECT_EQ(checked, std::size(kStored)) << "a stored row names no built-in scene";
}

// The figures see what the scenes' builders set: one number of one material, one light and one
// camera each move their figure (and only the test's own copy of the scene is touched).
TEST(BuiltinContent, FiguresSeeEachNumberAScenesBuilderSets) {
    const Scene base = loadScene("builtin:glass");
    const Figures before = measure("glass", base).figures;
    const auto movedBy = [&](auto edit) {
        Scene s = base;
        edit(s);
        const Figures after = measure("glass", s).figures;
        std::string moved;
        for (size_t i = 0; i < kFigures; ++i)
            if (after[i] != before[i])
                moved += std::string(moved.empty() ? "" : " ") + kFigureNames[i];
        return moved;
    };
    EXPECT_EQ(movedBy([](Scene& s) { s.materials[0].baseColor.z *= 0.5f; }), "albedo.b");
    EXPECT_EQ(movedBy([](Scene& s) { s.vertices[0].color.w = 0.5f; }), "alpha");
    EXPECT_EQ(movedBy([](Scene& s) { s.lights[0].color.y = 0.5f; }), "lights");
    EXPECT_EQ(movedBy([](Scene& s) { s.cameras[0].yfov *= 2.0f; }), "cameras");
    EXPECT_NE(movedBy([](Scene& s) { s.vertices[s.indices[0]].position.y += 0.25f; }), "");
}
