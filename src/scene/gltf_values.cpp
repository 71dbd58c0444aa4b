// The glTF schema's enumerations and ranges for the values Penumbra reads or could be misled by
// (the glTF-Validator's VALUE_NOT_IN_LIST, VALUE_NOT_IN_RANGE, ACCESSOR_NORMALIZED_INVALID,
// SCENE_NON_ROOT_NODE, ...): refused by JSON path where the value is used, a warning where it
// lies in an object nothing uses (a camera no node carries).
#include "penumbra/error.h"
#include "scene/gltf_validate.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace penumbra::gltf {
namespace {

struct ValueChecker {
    const std::filesystem::path& file;
    const tinygltf::Model& m;
    OnceWarnings& once;

    [[noreturn]] void fail(const std::string& path, const std::string& what) const {
        throw InputError(file.string(), path + ": " + what);
    }
    void unit(const std::string& path, double v) const {
        if (!(v >= 0.0 && v <= 1.0))
            fail(path, fmt::format("{} is outside [0, 1]", v));
    }

    void samplers() const {
        for (size_t i = 0; i < m.samplers.size(); ++i) {
            const auto& s = m.samplers[i];
            const std::string path = fmt::format("samplers[{}]", i);
            const auto oneOf = [&](const char* key, int v, std::initializer_list<int> allowed,
                                   bool optional) {
                if ((optional && v == -1) ||
                    std::find(allowed.begin(), allowed.end(), v) != allowed.end())
                    return;
                fail(path + "." + key, fmt::format("{} is not a glTF {} value", v, key));
            };
            oneOf("magFilter", s.magFilter, {9728, 9729}, true);
            oneOf("minFilter", s.minFilter, {9728, 9729, 9984, 9985, 9986, 9987}, true);
            oneOf("wrapS", s.wrapS, {33071, 33648, 10497}, false);
            oneOf("wrapT", s.wrapT, {33071, 33648, 10497}, false);
        }
    }

    void materials() const {
        for (size_t i = 0; i < m.materials.size(); ++i) {
            const auto& mat = m.materials[i];
            const std::string path = fmt::format("materials[{}]", i);
            unit(path + ".pbrMetallicRoughness.metallicFactor",
                 mat.pbrMetallicRoughness.metallicFactor);
            unit(path + ".pbrMetallicRoughness.roughnessFactor",
                 mat.pbrMetallicRoughness.roughnessFactor);
            if (!mat.emissiveFactor.empty() && mat.emissiveFactor.size() != 3)
                fail(path + ".emissiveFactor", "needs 3 numbers");
            for (double f : mat.emissiveFactor)
                unit(path + ".emissiveFactor", f);
            unit(path + ".occlusionTexture.strength", mat.occlusionTexture.strength);
        }
    }

    void accessors() const {
        for (size_t i = 0; i < m.accessors.size(); ++i) {
            const auto& a = m.accessors[i];
            if (a.normalized && (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                                 a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
                fail(fmt::format("accessors[{}].normalized", i),
                     "only byte and short components can be normalized");
        }
    }

    void lights() const {
        for (size_t i = 0; i < m.lights.size(); ++i) {
            const std::string path = fmt::format("extensions.KHR_lights_punctual.lights[{}]", i);
            for (double c : m.lights[i].color)
                unit(path + ".color", c);
            if (m.lights[i].color.size() != 3 && !m.lights[i].color.empty())
                fail(path + ".color", "needs 3 numbers");
        }
    }

    // A camera no node carries is an unused object: a warning; a used one is refused.
    void cameras() const {
        std::set<int> carried;
        for (const auto& n : m.nodes)
            carried.insert(n.camera);
        for (size_t i = 0; i < m.cameras.size(); ++i) {
            const auto& c = m.cameras[i];
            const std::string path = fmt::format("cameras[{}]", i);
            std::string what;
            if (c.type == "perspective") {
                const auto& p = c.perspective;
                if (!(p.yfov > 0.0) || !(p.znear > 0.0) || p.aspectRatio < 0.0 ||
                    (p.zfar != 0.0 && !(p.zfar > p.znear)))
                    what = "perspective: yfov and znear must be positive, zfar past znear";
            } else if (c.type == "orthographic") {
                const auto& o = c.orthographic;
                if (o.xmag == 0.0 || o.ymag == 0.0 || o.znear < 0.0 || !(o.zfar > o.znear))
                    what = "orthographic: xmag and ymag must not be 0, zfar past znear >= 0";
            } else {
                what = fmt::format("type '{}' is not perspective or orthographic", c.type);
            }
            if (what.empty())
                continue;
            if (carried.contains(static_cast<int>(i)))
                fail(path, what);
            once.add("unused camera", path, what + "; the camera is not used");
        }
    }

    // A scene lists root nodes, each once: a child listed again would be drawn twice.
    void sceneRoots() const {
        std::vector<int> parent(m.nodes.size(), -1);
        for (size_t i = 0; i < m.nodes.size(); ++i)
            for (int c : m.nodes[i].children)
                if (c >= 0 && static_cast<size_t>(c) < m.nodes.size())
                    parent[c] = static_cast<int>(i);
        for (size_t s = 0; s < m.scenes.size(); ++s) {
            std::set<int> seen;
            for (size_t k = 0; k < m.scenes[s].nodes.size(); ++k) {
                const int n = m.scenes[s].nodes[k];
                const std::string path = fmt::format("scenes[{}].nodes[{}]", s, k);
                if (n < 0 || static_cast<size_t>(n) >= m.nodes.size())
                    continue; // validateModel's index check names it
                if (parent[n] >= 0)
                    fail(path, fmt::format("node {} is not a root (its parent is node {})", n,
                                           parent[n]));
                if (!seen.insert(n).second)
                    fail(path, fmt::format("node {} is listed twice", n));
            }
        }
    }
};

} // namespace

void checkSchemaValues(const std::filesystem::path& file, const tinygltf::Model& model,
                       OnceWarnings& once) {
    const ValueChecker c{file, model, once};
    c.samplers();
    c.materials();
    c.accessors();
    c.lights();
    c.cameras();
    c.sceneRoots();
}

} // namespace penumbra::gltf
