#include "scene/generated.h"

#include "penumbra/error.h"
#include "scene/first_picture.h"
#include "scene/framing.h"
#include "scene/gen_families.h"

#include <fmt/format.h>
#include <glm/gtc/constants.hpp>

#include <charconv>
#include <cmath>
#include <optional>
#include <utility>

namespace penumbra {
namespace {

struct Family {
    std::string_view name;
    Scene (*make)(GenRandom&);
};
constexpr Family kFamilies[] = {
    {"plates", gen::plates},   {"spheres", gen::spheres}, {"leaves", gen::leaves},
    {"open", gen::open},       {"curved", gen::curved},   {"interior", gen::interior},
    {"grazing", gen::grazing}, {"long", gen::longView},   {"clutter", gen::clutter}};

constexpr int kCameraTries = 4; // cameras drawn round the content; the one showing most shadow

std::string familyList() {
    std::string names;
    for (const Family& f : kFamilies)
        names += (names.empty() ? "" : ", ") + std::string(f.name);
    return names;
}

// The whole scene `s` times larger: positions, light sizes and ranges, cameras; intensities of
// spot and point lights grow with the square, so the light on the content stays the same.
void scaleScene(Scene& scene, float s) {
    for (Vertex& v : scene.vertices)
        v.position *= s;
    for (Light& l : scene.lights) {
        l.position *= s;
        l.radius *= s;
        l.range *= s;
        if (l.type != LightType::Directional)
            l.intensity *= s * s;
    }
    for (Camera& c : scene.cameras) {
        c.position *= s, c.target *= s;
        c.ymag *= s, c.znear *= s, c.zfar *= s;
    }
}

} // namespace

float GenRandom::logUniform(float lo, float hi) {
    return lo * std::exp(std::log(hi / lo) * unit());
}

std::vector<std::string_view> generatedFamilies() {
    std::vector<std::string_view> names;
    for (const Family& f : kFamilies)
        names.push_back(f.name);
    return names;
}

GeneratedSpec parseGeneratedSpec(std::string_view spec) {
    const std::string where = "builtin:gen/" + std::string(spec);
    GeneratedSpec out;
    const size_t query = spec.find('?');
    out.family = std::string(spec.substr(0, query));
    bool known = false;
    for (const Family& f : kFamilies)
        known = known || f.name == out.family;
    if (!known)
        throw InputError(where, fmt::format("no such generated family '{}' (families: {})",
                                            out.family, familyList()));
    std::string_view rest = query == std::string_view::npos ? "" : spec.substr(query + 1);
    if (query != std::string_view::npos && rest.empty())
        throw InputError(where, "nothing after '?' (keys: seed, scale)");
    bool seedGiven = false, scaleGiven = false;
    for (bool more = !rest.empty(); more;) {
        const size_t amp = rest.find('&');
        const std::string_view pair = rest.substr(0, amp);
        more = amp != std::string_view::npos;
        rest = more ? rest.substr(amp + 1) : "";
        if (pair.empty()) // a stray '&': a pair left out or cut off
            throw InputError(where, "an empty key=value pair (keys: seed, scale)");
        const size_t eq = pair.find('=');
        const std::string_view key = pair.substr(0, eq);
        const std::string_view value = eq == std::string_view::npos ? "" : pair.substr(eq + 1);
        bool& given = key == "seed" ? seedGiven : scaleGiven;
        if ((key == "seed" || key == "scale") && std::exchange(given, true))
            throw InputError(where, fmt::format("'{}' given twice", key));
        if (key == "seed") {
            const auto [end, ec] =
                std::from_chars(value.data(), value.data() + value.size(), out.seed);
            if (value.empty() || ec != std::errc() || end != value.data() + value.size() ||
                out.seed >= (uint64_t{1} << 63))
                throw InputError(where, fmt::format("seed '{}' is not a whole number from 0 to "
                                                    "2^63 - 1",
                                                    value));
        } else if (key == "scale") {
            float s = 0.0f;
            const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), s);
            if (value.empty() || ec != std::errc() || end != value.data() + value.size() ||
                !(s >= kLeastGeneratedScale && s <= kMostGeneratedScale))
                throw InputError(where,
                                 fmt::format("scale '{}' is not a number from {:g} to {:g}", value,
                                             kLeastGeneratedScale, kMostGeneratedScale));
            out.scale = s;
        } else {
            throw InputError(where, fmt::format("unknown key '{}' (keys: seed, scale)", key));
        }
    }
    return out;
}

Scene generatedScene(std::string_view spec) {
    return generatedScene(parseGeneratedSpec(spec));
}

Scene generatedScene(const GeneratedSpec& spec) {
    for (const Family& f : kFamilies) {
        if (f.name != spec.family)
            continue;
        // The family's name in the stream: two families with one seed differ.
        uint64_t stream = spec.seed;
        for (char c : f.name)
            stream = stream * 131 + static_cast<uint8_t>(c);
        GenRandom random(stream);
        Scene scene = f.make(random);
        scene.name = fmt::format("gen/{}?seed={}", spec.family, spec.seed);
        if (spec.scale != 1.0f) {
            scene.name += fmt::format("&scale={:g}", spec.scale);
            scaleScene(scene, spec.scale);
        }
        return scene;
    }
    throw InputError("builtin:gen/" + spec.family,
                     fmt::format("no such generated family (families: {})", familyList()));
}

namespace gen {

Light drawLight(GenRandom& random, const Bounds& content, const LightChoice& choice) {
    std::vector<LightType> kinds;
    if (choice.sun)
        kinds.push_back(LightType::Directional);
    if (choice.spot)
        kinds.push_back(LightType::Spot);
    if (choice.point)
        kinds.push_back(LightType::Point);
    const LightType type = kinds[static_cast<size_t>(random.integer(0, int(kinds.size()) - 1))];
    const bool sized = !random.chance(0.2f);
    const float size = std::max(glm::length(content.extent()), 1e-3f);
    const float azimuth = random.uniform(0.0f, 2.0f * glm::pi<float>());
    Light l{.name = "generated " + std::string(lightTypeName(type)), .type = type};
    if (type == LightType::Directional) {
        const float up = glm::radians(random.uniform(choice.lowestSun, choice.highestSun));
        l.direction = -glm::vec3(std::cos(up) * std::cos(azimuth), std::sin(up),
                                 std::cos(up) * std::sin(azimuth));
        l.intensity = 2.0f;
        l.angularDiameter = sized ? random.logUniform(0.25f, 8.0f) : 0.0f;
        return l;
    }
    const float height = random.uniform(0.6f, 1.5f) * size;
    const float aside = random.uniform(0.0f, 0.6f) * size;
    l.position =
        content.center() + glm::vec3(aside * std::cos(azimuth), 0.0f, aside * std::sin(azimuth));
    l.position.y = content.max.y + height;
    const float distance = glm::length(content.center() - l.position);
    l.intensity = 2.0f * distance * distance;
    l.radius = sized ? random.logUniform(0.005f, 0.1f) * size : 0.0f;
    if (type == LightType::Spot) {
        l.direction = glm::normalize(content.center() - l.position);
        l.outerConeAngle = std::min(std::atan(0.6f * size / distance) + 0.1f, 1.45f);
        l.innerConeAngle = 0.8f * l.outerConeAngle;
    }
    return l;
}

Camera orbitCamera(GenRandom& random, const Scene& scene, const Bounds& content, float lowest,
                   float highest) {
    const TriangleBvh bvh(scene);
    std::optional<Camera> best;
    float shown = -1.0f;
    for (int tries = 0; tries < kCameraTries; ++tries) {
        const float azimuth = random.uniform(0.0f, 2.0f * glm::pi<float>());
        const float up = glm::radians(random.uniform(lowest, highest));
        const float yfov = random.uniform(0.6f, 1.0f);
        const float radius = 0.5f * glm::length(content.extent());
        // As near as keeps a sphere round the content inside the view's height (16:9: wider).
        const float distance = std::max(radius / std::sin(0.5f * yfov), 1e-3f);
        const glm::vec3 towards(std::cos(up) * std::cos(azimuth), std::sin(up),
                                std::cos(up) * std::sin(azimuth));
        Camera c{.name = "generated",
                 .position = content.center() + distance * towards,
                 .target = content.center(),
                 .yfov = yfov};
        const glm::vec2 depth = depthRangeFrom(scene, c.position);
        c.znear = depth.x, c.zfar = depth.y;
        const float s = scene.lights.empty()
                            ? 0.0f
                            : ViewProbe(scene, bvh, c).measure(scene.lights.front()).castShadow;
        if (s > shown)
            shown = s, best = c;
    }
    return *best;
}

uint32_t groundAnd(MeshBuilder& mb, GenRandom& random, float half, const std::string& objects) {
    const uint32_t ground = mb.material("ground", drawColor(random));
    mb.quad({-half, 0, half}, {half, 0, half}, {half, 0, -half}, {-half, 0, -half}, ground);
    return mb.material(objects, drawColor(random));
}

Bounds footprint(float half, float height) {
    return {.min = {-half, 0.0f, -half}, .max = {half, height, half}};
}

Bounds contentOf(const Scene& scene, Bounds around) {
    for (size_t v = kGroundVertices; v < scene.vertices.size(); ++v)
        around.grow(scene.vertices[v].position);
    return around;
}

glm::vec3 drawColor(GenRandom& random) {
    const float r = random.uniform(0.3f, 0.8f);
    const float g = random.uniform(0.3f, 0.8f);
    const float b = random.uniform(0.3f, 0.8f);
    return {r, g, b};
}

} // namespace gen
} // namespace penumbra
