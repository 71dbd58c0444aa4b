// glTF 2.0 to Scene: the checked container and JSON (gltf_container), tinygltf under a locked
// file-system policy, the model validator (gltf_validate), then an iterative walk of the node
// hierarchy that flattens every triangle primitive into world space.
#include "scene/gltf_loader.h"

#include "penumbra/error.h"
#include "scene/first_picture.h"
#include "scene/gltf_accessors.h"
#include "scene/gltf_animation.h"
#include "scene/gltf_compression.h"
#include "scene/gltf_container.h"
#include "scene/gltf_images.h"
#include "scene/gltf_skin.h"
#include "scene/gltf_transmission.h"
#include "scene/gltf_validate.h"
#include "scene/interior.h"
#include "scene/sanitize.h"
#include "scene/skinning.h"

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <span>

namespace penumbra {
namespace {

using gltf::readFloats;
using gltf::readIndices;

struct FsPolicy {
    std::filesystem::path folder;
    uint64_t maxFileSize;
};

// No tilde or variable expansion, ever: a URI names a file in the asset's folder or nothing.
std::string noExpansion(const std::string& path, void*) {
    return path;
}

bool insideFolder(const std::string& path, const FsPolicy& policy) {
    const auto rel = std::filesystem::path(path).lexically_normal().lexically_relative(
        policy.folder.lexically_normal());
    return !rel.empty() && *rel.begin() != ".." && !rel.is_absolute();
}

bool fileExists(const std::string& path, void* user) {
    const auto& policy = *static_cast<const FsPolicy*>(user);
    std::error_code ec; // a name too long for the file system is a missing file, not a throw
    return insideFolder(path, policy) && std::filesystem::is_regular_file(path, ec);
}

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                   void* user) {
    const auto& policy = *static_cast<const FsPolicy*>(user);
    std::error_code ec;
    const uint64_t size = std::filesystem::file_size(path, ec);
    if (!insideFolder(path, policy) || ec) {
        *err = "cannot read '" + path + "'";
        return false;
    }
    if (size > policy.maxFileSize) {
        *err = fmt::format("'{}' is past the size cap of {} bytes", path, policy.maxFileSize);
        return false;
    }
    out->resize(size);
    std::ifstream in(path, std::ios::binary);
    return static_cast<bool>(
        in.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(size)));
}

bool writeNothing(std::string*, const std::string&, const std::vector<unsigned char>&, void*) {
    return false;
}

// Triangle-list indices for a primitive's mode; empty for points and lines.
std::vector<uint32_t> triangles(int mode, const std::vector<uint32_t>& idx) {
    std::vector<uint32_t> out;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        out.assign(idx.begin(), idx.begin() + static_cast<long>(idx.size() / 3 * 3));
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        for (size_t i = 2; i < idx.size(); ++i) // alternate winding keeps faces consistent
            out.insert(out.end(),
                       i % 2 ? std::initializer_list<uint32_t>{idx[i - 1], idx[i - 2], idx[i]}
                             : std::initializer_list<uint32_t>{idx[i - 2], idx[i - 1], idx[i]});
    } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        for (size_t i = 2; i < idx.size(); ++i)
            out.insert(out.end(), {idx[0], idx[i - 1], idx[i]});
    }
    return out;
}

double extraNumber(const tinygltf::Value& extras, const char* key, double fallback) {
    if (!extras.IsObject() || !extras.Has(key) || !extras.Get(key).IsNumber())
        return fallback;
    return extras.Get(key).GetNumberAsDouble();
}

// KHR_texture_transform on a textureInfo: uv' = T R S uv (offset, rotation counter-clockwise in
// radians, scale), as a 2x3 matrix, and the texture coordinate set it reads.
struct UvTransform {
    glm::vec2 u{1, 0}, v{0, 1}, offset{0, 0}; // uv' = u * uv.x + v * uv.y + offset
    int texCoord = 0;
    glm::vec2 apply(glm::vec2 uv) const { return u * uv.x + v * uv.y + offset; }
};

// The extension's numbers, each checked: `count` finite numbers at `key`, else the default.
std::vector<double> transformNumbers(const std::filesystem::path& file, const std::string& path,
                                     const tinygltf::Value& ext, const char* key, size_t count,
                                     std::vector<double> fallback) {
    if (!ext.Has(key))
        return fallback;
    const tinygltf::Value& v = ext.Get(key);
    std::vector<double> out;
    if (count == 1 && v.IsNumber())
        out.push_back(v.GetNumberAsDouble());
    else if (count > 1 && v.IsArray() && v.ArrayLen() == count)
        for (size_t i = 0; i < count; ++i)
            if (v.Get(static_cast<int>(i)).IsNumber())
                out.push_back(v.Get(static_cast<int>(i)).GetNumberAsDouble());
    if (out.size() != count || !std::all_of(out.begin(), out.end(), [](double x) {
            return std::isfinite(x) && std::abs(x) < 1e15;
        }))
        throw InputError(file.string(),
                         fmt::format("{}.{}: {} of magnitude below 1e15 expected", path, key,
                                     count == 1 ? "a number" : fmt::format("{} numbers", count)));
    return out;
}

UvTransform uvTransformOf(const std::filesystem::path& file, const std::string& path,
                          const tinygltf::TextureInfo& info) {
    UvTransform t{.texCoord = info.texCoord};
    const auto e = info.extensions.find("KHR_texture_transform");
    if (e == info.extensions.end())
        return t;
    const std::string at = path + ".extensions.KHR_texture_transform";
    if (!e->second.IsObject())
        throw InputError(file.string(), at + ": an object is expected");
    const std::vector<double> offset = transformNumbers(file, at, e->second, "offset", 2, {0, 0});
    const double rotation = transformNumbers(file, at, e->second, "rotation", 1, {0})[0];
    const std::vector<double> scale = transformNumbers(file, at, e->second, "scale", 2, {1, 1});
    if (e->second.Has("texCoord")) {
        const tinygltf::Value& c = e->second.Get("texCoord");
        if (!c.IsInt() || c.GetNumberAsInt() < 0)
            throw InputError(file.string(), at + ".texCoord: a non-negative integer expected");
        t.texCoord = c.GetNumberAsInt();
    }
    // The ratified matrix: rotating the coordinates counter-clockwise turns the image clockwise
    // (its example: offset (0, 1), a quarter turn and half scale read the lower-left quadrant).
    const double c = std::cos(rotation), s = std::sin(rotation);
    t.u = glm::vec2(glm::dvec2(c * scale[0], -s * scale[0]));
    t.v = glm::vec2(glm::dvec2(s * scale[1], c * scale[1]));
    t.offset = glm::vec2(glm::dvec2(offset[0], offset[1]));
    return t;
}

struct Flattener {
    const std::filesystem::path& file;
    const tinygltf::Model& m;
    Scene& scene;
    const GltfOptions& options;
    std::vector<UvTransform> uvTransform; // per material: its base-colour texture's set and
                                          // KHR_texture_transform
    uint32_t defaultMaterial = 0;         // for primitives without one
    size_t skippedPointsOrLines = 0;
    std::map<size_t, size_t> unusableByMesh; // mesh index -> triangles dropInvalidTriangles drops
    std::vector<gltf::NodePose> poses;       // per node: at rest, or at --time
    std::vector<glm::mat4> worlds;           // per node: its world transform in that pose
    std::vector<gltf::Skin> skins;
    std::vector<uint32_t> jointBase; // per skin: its first joint in scene.skinning.joints

    void warn(const std::string& w) const {
        if (options.warnings)
            options.warnings->push_back(file.string() + ": " + w);
    }

    // A primitive placed by `world`, or per vertex by its influences `skinned` (of skins[skin]),
    // its morph targets blended by `weights`.
    void primitive(const tinygltf::Primitive& p, const glm::mat4& world, size_t meshIndex,
                   std::span<const float> weights, const gltf::PrimitiveInfluences* skinned,
                   size_t skin) {
        if (!gltf::hasPositions(p))
            return; // validateModel said so
        if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            p.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
            warn(fmt::format("meshes[{}]: a primitive of points or lines is skipped", meshIndex));
            ++skippedPointsOrLines;
            return;
        }
        // The caps come first, from the accessors' counts: an accessor without a bufferView
        // costs a few bytes of JSON whatever its count, and reading it allocates them all.
        const size_t count = m.accessors[p.attributes.at("POSITION")].count;
        const size_t indexCount = p.indices >= 0 ? m.accessors[p.indices].count : count;
        const size_t newTriangles = p.mode == TINYGLTF_MODE_TRIANGLES ? indexCount / 3
                                    : indexCount < 3                  ? 0
                                                                      : indexCount - 2;
        if (scene.indices.size() / 3 + newTriangles > options.maxTriangles ||
            scene.vertices.size() + count > 3 * options.maxTriangles)
            throw InputError(file.string(),
                             fmt::format("meshes[{}]: the scene would have more than {} triangles "
                                         "after instancing (--max-triangles raises the cap)",
                                         meshIndex, options.maxTriangles));
        std::vector<float> pos = readFloats(m, p.attributes.at("POSITION"));
        // (validateModel refused non-finite attribute values.)
        std::vector<uint32_t> idx;
        if (p.indices >= 0) {
            idx = readIndices(m, p.indices);
            // The largest value of the index type restarts a strip elsewhere; glTF forbids it.
            const int size = tinygltf::GetComponentSizeInBytes(
                static_cast<uint32_t>(m.accessors[p.indices].componentType));
            const uint32_t restart = size >= 4 ? 0xFFFFFFFFu : (1u << (8 * size)) - 1u;
            for (uint32_t i : idx)
                if (i == restart)
                    throw InputError(file.string(),
                                     fmt::format("meshes[{}]: index {} is the primitive-restart "
                                                 "value, which glTF does not allow",
                                                 meshIndex, i));
            for (uint32_t i : idx)
                if (i >= count)
                    throw InputError(file.string(),
                                     fmt::format("meshes[{}]: index {} is past the {} "
                                                 "vertices",
                                                 meshIndex, i, count));
        } else {
            idx.resize(count);
            for (uint32_t i = 0; i < count; ++i)
                idx[i] = i;
        }
        std::vector<uint32_t> tri = triangles(p.mode, idx);
        std::vector<float> normals;
        if (const auto n = p.attributes.find("NORMAL"); n != p.attributes.end()) {
            normals = readFloats(m, n->second);
            if (normals.size() != pos.size())
                normals.clear();
        }
        blendMorphTargets(p, weights, pos, normals);
        if (skinned && normals.empty()) // area-weighted smooth normals in bind space, as wound
            normals = smoothNormals(pos, tri);
        // A mirroring transform flips the winding: a node's, the whole primitive; a skin's, each
        // triangle its first vertex's blend mirrors (so what faces out stays front-facing).
        if (skinned) {
            for (size_t t = 0; t + 2 < tri.size(); t += 3)
                if (glm::determinant(blendOf(*skinned, skin, tri[t])) < 0.0f)
                    std::swap(tri[t + 1], tri[t + 2]);
        } else if (glm::determinant(glm::mat3(world)) < 0.0f) {
            for (size_t t = 0; t + 2 < tri.size(); t += 3)
                std::swap(tri[t + 1], tri[t + 2]);
        }
        const uint32_t material =
            p.material >= 0 ? static_cast<uint32_t>(p.material) : defaultMaterial;
        const UvTransform& transform = uvTransform[material];
        // validateModel checked the texture's own set; KHR_texture_transform may name another.
        if (scene.materials[material].baseColorTexture >= 0 &&
            !p.attributes.contains(fmt::format("TEXCOORD_{}", transform.texCoord)))
            throw InputError(file.string(),
                             fmt::format("meshes[{}]: no TEXCOORD_{} for materials[{}]'s base "
                                         "colour texture (its KHR_texture_transform.texCoord)",
                                         meshIndex, transform.texCoord, material));
        const std::vector<float> uv =
            attribute(p, fmt::format("TEXCOORD_{}", transform.texCoord), count, 2);
        const int colorAccessor =
            p.attributes.contains("COLOR_0") ? p.attributes.at("COLOR_0") : -1;
        const size_t colorSize =
            colorAccessor >= 0 && m.accessors[colorAccessor].type == TINYGLTF_TYPE_VEC4 ? 4 : 3;
        const std::vector<float> color = attribute(p, "COLOR_0", count, colorSize);
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(world)));
        const uint32_t base = static_cast<uint32_t>(scene.vertices.size());
        const size_t firstSkinned = scene.skinning.vertices.size();
        for (size_t v = 0; v < count; ++v) {
            const glm::vec3 local(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2]);
            glm::vec3 n = normals.empty()
                              ? glm::vec3(0.0f)
                              : glm::vec3(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]);
            Vertex out{local, n, material}; // a skinned vertex: placed below
            if (skinned) {
                const uint32_t first = skinned->starts[v];
                scene.skinning.vertices.push_back(
                    {.vertex = base + static_cast<uint32_t>(v),
                     .firstInfluence = static_cast<uint32_t>(scene.skinning.influences.size()),
                     .influenceCount = skinned->starts[v + 1] - first,
                     .position = local,
                     .normal = n});
                for (uint32_t k = first; k < skinned->starts[v + 1]; ++k) {
                    SkinInfluence influence = skinned->influences[k];
                    influence.joint += jointBase[skin];
                    scene.skinning.influences.push_back(influence);
                }
            } else {
                out.position = glm::vec3(world * glm::vec4(local, 1.0f));
                out.normal = normalMatrix * n;
            }
            if (!uv.empty()) // affine, so transforming the corners transforms every point
                out.uv = transform.apply(glm::vec2(uv[2 * v], uv[2 * v + 1]));
            if (!color.empty())
                out.color = glm::vec4(color[colorSize * v], color[colorSize * v + 1],
                                      color[colorSize * v + 2],
                                      colorSize == 4 ? color[colorSize * v + 3] : 1.0f);
            scene.vertices.push_back(out);
        }
        placeSkinnedVertices(scene, firstSkinned, scene.skinning.vertices.size());
        if (normals.empty()) { // missing normals: area-weighted smooth normals of the primitive
            for (size_t t = 0; t + 2 < tri.size(); t += 3) {
                const glm::vec3 a = scene.vertices[base + tri[t]].position,
                                b = scene.vertices[base + tri[t + 1]].position,
                                c = scene.vertices[base + tri[t + 2]].position;
                const glm::vec3 face = glm::cross(b - a, c - a);
                for (int k = 0; k < 3; ++k)
                    scene.vertices[base + tri[t + k]].normal += face;
            }
        }
        for (size_t v = base; v < scene.vertices.size(); ++v) {
            const glm::vec3 n = scene.vertices[v].normal;
            scene.vertices[v].normal =
                glm::dot(n, n) > 0.0f ? glm::normalize(n) : glm::vec3(0, 1, 0);
        }
        for (size_t t = 0; t + 2 < tri.size(); t += 3)
            if (!triangleIsUsable(scene.vertices[base + tri[t]].position,
                                  scene.vertices[base + tri[t + 1]].position,
                                  scene.vertices[base + tri[t + 2]].position))
                ++unusableByMesh[meshIndex];
        for (uint32_t i : tri)
            scene.indices.push_back(base + i);
    }

    // The 3x3 part of vertex `v`'s blend of its joints' matrices in this pose (skins[skin]'s).
    glm::mat3 blendOf(const gltf::PrimitiveInfluences& skinned, size_t skin, uint32_t v) const {
        glm::mat3 blend(0.0f);
        for (uint32_t k = skinned.starts[v]; k < skinned.starts[v + 1]; ++k) {
            const SkinInfluence& influence = skinned.influences[k];
            blend += influence.weight *
                     glm::mat3(scene.skinning.joints[jointBase[skin] + influence.joint]);
        }
        return blend;
    }

    // Area-weighted smooth normals of the triangles `tri` over positions `pos` (3 floats each).
    static std::vector<float> smoothNormals(const std::vector<float>& pos,
                                            const std::vector<uint32_t>& tri) {
        std::vector<float> normals(pos.size(), 0.0f);
        const auto at = [&](uint32_t i) {
            return glm::vec3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
        };
        for (size_t t = 0; t + 2 < tri.size(); t += 3) {
            const glm::vec3 face =
                glm::cross(at(tri[t + 1]) - at(tri[t]), at(tri[t + 2]) - at(tri[t]));
            for (int k = 0; k < 3; ++k)
                for (int c = 0; c < 3; ++c)
                    normals[3 * tri[t + k] + c] += face[c];
        }
        return normals;
    }

    // Morph targets (the specification's 3.7.2.2): each target's POSITION and NORMAL
    // displacements added, times its weight. (validateModel checked their types and counts.)
    void blendMorphTargets(const tinygltf::Primitive& p, std::span<const float> weights,
                           std::vector<float>& pos, std::vector<float>& normals) const {
        for (size_t t = 0; t < p.targets.size() && t < weights.size(); ++t) {
            if (weights[t] == 0.0f)
                continue;
            for (const auto& [name, out] :
                 {std::pair<const char*, std::vector<float>*>{"POSITION", &pos},
                  std::pair<const char*, std::vector<float>*>{"NORMAL", &normals}}) {
                const auto a = p.targets[t].find(name);
                if (a == p.targets[t].end() || out->empty())
                    continue;
                const std::vector<float> delta = readFloats(m, a->second);
                for (size_t i = 0; i < out->size() && i < delta.size(); ++i)
                    (*out)[i] += weights[t] * delta[i];
            }
        }
    }

    // One line for every triangle the scene loses: how many, and the meshes most of them come
    // from (the three largest counts by name, then the rest summed).
    void warnUnusable() const {
        size_t total = 0;
        std::vector<std::pair<size_t, size_t>> meshes; // count, mesh index
        for (const auto& [mesh, n] : unusableByMesh) {
            total += n;
            meshes.emplace_back(n, mesh);
        }
        if (total == 0)
            return;
        std::stable_sort(meshes.begin(), meshes.end(),
                         [](const auto& a, const auto& b) { return a.first > b.first; });
        std::string where;
        for (size_t k = 0; k < meshes.size() && k < 3; ++k) {
            const auto [n, mesh] = meshes[k];
            const std::string& name = m.meshes[mesh].name;
            where += fmt::format("{}{} in meshes[{}]{}", k == 0 ? "" : ", ", n, mesh,
                                 name.empty() ? "" : fmt::format(" '{}'", name));
        }
        if (meshes.size() > 3) {
            size_t rest = 0;
            for (size_t k = 3; k < meshes.size(); ++k)
                rest += meshes[k].first;
            where += fmt::format(", {} in {} other meshes", rest, meshes.size() - 3);
        }
        warn(fmt::format("{} triangle{} without area (or past the coordinate limit) dropped: {}",
                         total, total == 1 ? "" : "s", where));
    }

    // A vertex attribute as count x size floats; empty when the primitive lacks it.
    std::vector<float> attribute(const tinygltf::Primitive& p, const std::string& name,
                                 size_t count, size_t size) const {
        const auto a = p.attributes.find(name);
        if (a == p.attributes.end())
            return {};
        std::vector<float> values = readFloats(m, a->second);
        return values.size() == count * size ? values : std::vector<float>{};
    }

    void node(size_t index, const glm::mat4& world) {
        const tinygltf::Node& n = m.nodes[index];
        if (n.mesh >= 0)
            for (size_t k = 0; k < m.meshes[n.mesh].primitives.size(); ++k) {
                const tinygltf::Primitive& p = m.meshes[n.mesh].primitives[k];
                gltf::PrimitiveInfluences skinned;
                const auto skin = static_cast<size_t>(std::max(n.skin, 0));
                if (n.skin >= 0 && gltf::hasPositions(p))
                    skinned = gltf::skinInfluences(
                        file, m, p, fmt::format("meshes[{}].primitives[{}]", n.mesh, k), index,
                        skins[skin]);
                primitive(p, world, static_cast<size_t>(n.mesh), poses[index].weights,
                          n.skin >= 0 ? &skinned : nullptr, skin);
            }
        if (n.camera >= 0)
            camera(index, m.cameras[n.camera], world);
        if (const auto e = n.extensions.find("KHR_lights_punctual"); e != n.extensions.end())
            if (e->second.Has("light") && e->second.Get("light").IsInt())
                light(index, e->second.Get("light").GetNumberAsInt(), world);
    }

    // Where a light or camera on node `index` sits, and where its local `axis` points. A node
    // scaled to zero (easy to reach with an animated scale) has no direction, and one placed
    // past the coordinate limit no place: both are refused, where the renderer and the
    // ray tracer would otherwise get NaN.
    glm::vec3 placeOf(size_t index, const glm::mat4& world, std::string_view what) const {
        const glm::vec3 place(world * glm::vec4(0, 0, 0, 1));
        for (int i = 0; i < 3; ++i)
            if (!std::isfinite(place[i]) || std::abs(place[i]) > kMaxCoordinate)
                throw InputError(file.string(), fmt::format("nodes[{}]: {} is placed past the "
                                                            "coordinate limit {:g}{}",
                                                            index, what, kMaxCoordinate, when()));
        return place;
    }
    glm::vec3 axisOf(size_t index, const glm::mat4& world, glm::vec3 axis,
                     std::string_view what) const {
        const glm::vec3 v(world * glm::vec4(axis, 0));
        const float length = glm::length(v);
        if (!(length > 0.0f) || !std::isfinite(length))
            throw InputError(file.string(),
                             fmt::format("nodes[{}]: {} has no direction: its node's transform "
                                         "is scaled to zero{}",
                                         index, what, when()));
        return v / length;
    }
    std::string when() const {
        return scene.time ? fmt::format(" at time {:g} s", *scene.time) : std::string();
    }

    void camera(size_t node, const tinygltf::Camera& c, const glm::mat4& world) {
        Camera cam{.name = c.name.empty() ? fmt::format("camera{}", scene.cameras.size()) : c.name};
        const std::string what = fmt::format("the camera '{}'", cam.name);
        cam.position = placeOf(node, world, what);
        cam.target = cam.position + axisOf(node, world, glm::vec3(0, 0, -1), what);
        cam.up = axisOf(node, world, glm::vec3(0, 1, 0), what);
        if (c.type == "orthographic") {
            cam.orthographic = true;
            cam.ymag = static_cast<float>(c.orthographic.ymag);
            cam.znear = static_cast<float>(c.orthographic.znear);
            cam.zfar = static_cast<float>(c.orthographic.zfar);
        } else {
            cam.yfov = static_cast<float>(c.perspective.yfov);
            cam.znear = static_cast<float>(c.perspective.znear);
            cam.zfar =
                c.perspective.zfar > 0 ? static_cast<float>(c.perspective.zfar) : cam.znear * 1e4f;
        }
        if (!(cam.znear > 0.0f) || !(cam.zfar > cam.znear) ||
            (!cam.orthographic && !(cam.yfov > 0.0f && cam.yfov < 3.1f)) ||
            (cam.orthographic && !(cam.ymag > 0.0f)))
            throw InputError(file.string(),
                             fmt::format("cameras: '{}' has invalid parameters", cam.name));
        scene.cameras.push_back(cam);
    }

    void light(size_t node, int index, const glm::mat4& world) {
        if (index < 0 || static_cast<size_t>(index) >= m.lights.size())
            throw InputError(file.string(),
                             fmt::format("KHR_lights_punctual: light {} is out of range", index));
        const tinygltf::Light& l = m.lights[index];
        Light out{.name = l.name.empty() ? fmt::format("light{}", index) : l.name};
        if (!lightTypeFromName(l.type, out.type))
            throw InputError(
                file.string(),
                fmt::format("KHR_lights_punctual.lights[{}].type: '{}' is not a light type", index,
                            l.type));
        const std::string what = fmt::format("KHR_lights_punctual.lights[{}]", index);
        out.position = placeOf(node, world, what);
        // A point light shines every way: its node may be scaled to zero.
        const glm::vec3 axis(world * glm::vec4(0, 0, -1, 0));
        out.direction = out.type == LightType::Point && !(glm::length(axis) > 0.0f)
                            ? glm::vec3(0, 0, -1)
                            : axisOf(node, world, glm::vec3(0, 0, -1), what);
        if (l.color.size() == 3)
            out.color = glm::vec3(l.color[0], l.color[1], l.color[2]);
        out.intensity = static_cast<float>(l.intensity);
        out.range = static_cast<float>(l.range);
        out.innerConeAngle = static_cast<float>(l.spot.innerConeAngle);
        out.outerConeAngle = static_cast<float>(l.spot.outerConeAngle);
        out.radius = static_cast<float>(extraNumber(l.extras, "radius", 0.0));
        out.angularDiameter = static_cast<float>(extraNumber(l.extras, "angularDiameter", 0.0));
        if (!std::isfinite(out.intensity) || out.intensity < 0 || !(out.radius >= 0) ||
            out.radius > kMaxCoordinate || out.angularDiameter < 0 || out.angularDiameter > 30)
            throw InputError(file.string(),
                             fmt::format("KHR_lights_punctual.lights[{}]: invalid intensity "
                                         "or size",
                                         index));
        // The extension: range > 0 where given; tinygltf reads an absent one as 0 (no range).
        if (!(out.range >= 0) || !std::isfinite(out.range))
            throw InputError(file.string(),
                             fmt::format("KHR_lights_punctual.lights[{}]: range {} is not above "
                                         "zero",
                                         index, l.range));
        scene.lights.push_back(out);
    }

    // The scene's nodes depth first, each placed by its posed world transform.
    void walk(const std::vector<int>& roots) {
        std::vector<int> stack(roots.rbegin(), roots.rend()); // iterative: no depth limit
        while (!stack.empty()) {
            const auto index = static_cast<size_t>(stack.back());
            stack.pop_back();
            node(index, worlds[index]);
            const std::vector<int>& children = m.nodes[index].children;
            stack.insert(stack.end(), children.rbegin(), children.rend());
        }
    }
};

// The nodes' poses: at rest, or `options.time` into the chosen animation. Every animation is
// checked either way: a malformed one is refused like any other glTF error.
void poseScene(const std::filesystem::path& file, const tinygltf::Model& model,
               const GltfOptions& options, Scene& scene, std::vector<gltf::NodePose>& poses) {
    const std::vector<gltf::Animation> animations =
        gltf::readAnimations(file, model, options.warnings);
    poses = gltf::restPoses(model);
    if (animations.empty()) {
        if (!options.animation.empty())
            gltf::chooseAnimation(file, animations,
                                  options.animation); // throws: none to choose
        return; // loadScene says that a --time changes nothing
    }
    const size_t chosen = gltf::chooseAnimation(file, animations, options.animation);
    scene.animation =
        animations[chosen].name.empty() ? fmt::format("{}", chosen) : animations[chosen].name;
    scene.animationDuration = animations[chosen].duration;
    if (!options.time) {
        if (options.warnings)
            options.warnings->push_back(fmt::format(
                "{}: animations: {} animation(s); the scene is drawn at rest "
                "(--time T poses it in animation '{}', {} s long)",
                file.string(), animations.size(), scene.animation, scene.animationDuration));
        return;
    }
    scene.time = *options.time;
    gltf::poseAt(animations[chosen], *options.time, poses);
}

} // namespace

Scene loadGltf(const std::filesystem::path& file, const GltfOptions& options) {
    const gltf::Container container = gltf::readContainer(file, options.maxFileSize);
    nlohmann::json json = gltf::checkJson(file, container, options.warnings);
    // Decoded geometry counts against the same cap as decoded images.
    const std::vector<gltf::MeshoptView> meshopt =
        gltf::prepareMeshopt(file, json, options.maxImageBytes);
    const std::vector<gltf::DetachedIndices> detached = gltf::detachViewlessIndices(json);
    gltf::ImageDecodePolicy images = gltf::baseColorImages(json);
    images.maxDecodedBytes = options.maxImageBytes;
    FsPolicy policy{.folder = std::filesystem::absolute(file).parent_path(),
                    .maxFileSize = options.maxFileSize};
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks(tinygltf::FsCallbacks{.FileExists = &fileExists,
                                                .ExpandFilePath = &noExpansion,
                                                .ReadWholeFile = &readWholeFile,
                                                .WriteWholeFile = &writeNothing,
                                                .user_data = &policy});
    loader.SetImageLoader(&gltf::decodeImage, &images);
    tinygltf::Model model;
    std::string err, warn;
    const std::string base = policy.folder.string();
    const std::vector<uint8_t> input = gltf::parserInput(container, json.dump());
    const bool ok = container.binary
                        ? loader.LoadBinaryFromMemory(&model, &err, &warn, input.data(),
                                                      static_cast<unsigned>(input.size()), base)
                        : loader.LoadASCIIFromString(&model, &err, &warn,
                                                     reinterpret_cast<const char*>(input.data()),
                                                     static_cast<unsigned>(input.size()), base);
    if (!ok) {
        const std::string first = err.substr(0, err.find('\n'));
        throw InputError(file.string(), first.empty() ? "cannot parse the asset" : first);
    }
    gltf::restoreIndices(model, detached);
    gltf::decodeMeshopt(file, model, meshopt);
    gltf::decodeDraco(file, model, options.maxImageBytes);
    gltf::validateModel(file, model, options.warnings);

    Scene scene;
    scene.name = file.stem().string();
    const std::vector<int32_t> textureOf =
        gltf::readTextures(file, model, images, scene, options.warnings);
    Flattener flat{file, model, scene, options};
    for (const auto& mat : model.materials) {
        const auto& f = mat.pbrMetallicRoughness.baseColorFactor;
        const auto& texture = mat.pbrMetallicRoughness.baseColorTexture;
        const AlphaMode mode = mat.alphaMode == "MASK"    ? AlphaMode::Mask
                               : mat.alphaMode == "BLEND" ? AlphaMode::Blend
                                                          : AlphaMode::Opaque;
        if (mode == AlphaMode::Blend)
            flat.warn(fmt::format("materials[{}]: alphaMode BLEND is drawn opaque in the image; "
                                  "its shadow lets 1 - alpha of the light through in the ground "
                                  "truth and with translucent.method=coloured or moments (a "
                                  "+translucent row), none otherwise",
                                  scene.materials.size()));
        scene.materials.push_back(
            {.name = mat.name,
             .baseColor = glm::vec4(f[0], f[1], f[2], f[3]),
             .baseColorTexture = texture.index >= 0 ? textureOf[texture.index] : -1,
             .alphaMode = mode,
             .alphaCutoff = static_cast<float>(mat.alphaCutoff),
             .doubleSided = mat.doubleSided});
        flat.uvTransform.push_back(
            uvTransformOf(file,
                          fmt::format("materials[{}].pbrMetallicRoughness.baseColorTexture",
                                      scene.materials.size() - 1),
                          texture));
        const size_t index = scene.materials.size() - 1;
        gltf::readTransmission(
            file, fmt::format("materials[{}]", index), json["materials"][index],
            {.sceneTextureOf = textureOf,
             .baseTexCoord = flat.uvTransform.back().texCoord,
             .baseTransformed = texture.extensions.contains("KHR_texture_transform")},
            scene.materials.back(), [&](const std::string& w) { flat.warn(w); });
    }
    // glTF's default material: white, opaque, single-sided.
    flat.defaultMaterial = static_cast<uint32_t>(scene.materials.size());
    scene.materials.push_back(
        {.name = "default", .baseColor = glm::vec4(1.0f), .doubleSided = false});
    flat.uvTransform.push_back(UvTransform{});
    poseScene(file, model, options, scene, flat.poses);
    flat.worlds = gltf::nodeWorlds(model, flat.poses);
    flat.skins = gltf::readSkins(file, model);
    for (const gltf::Skin& skin : flat.skins) { // every skin's joints in this pose, in one list
        flat.jointBase.push_back(static_cast<uint32_t>(scene.skinning.joints.size()));
        for (const glm::mat4& joint : gltf::jointMatrices(skin, flat.worlds))
            scene.skinning.joints.push_back(joint);
    }
    if (!model.scenes.empty())
        flat.walk(model.scenes[model.defaultScene >= 0 ? model.defaultScene : 0].nodes);
    flat.warnUnusable();
    const size_t beforeDrop = scene.triangleCount();
    dropInvalidTriangles(scene);
    if (scene.triangleCount() == 0)
        throw InputError(file.string(),
                         beforeDrop > 0
                             ? fmt::format("the default scene has no triangle with area: its {} "
                                           "{} without area or past the coordinate limit, so "
                                           "nothing in it would cast or receive a shadow",
                                           beforeDrop,
                                           beforeDrop == 1 ? "triangle is" : "triangles are")
                         : flat.skippedPointsOrLines
                             ? "the default scene has no triangles, only points or lines: "
                               "nothing in it would cast or receive a shadow"
                             : "the default scene has no triangles");
    // Stand-ins that suit interiors as well as objects (scene/interior.h has the rules).
    if (scene.lights.empty() || scene.cameras.empty()) {
        const Bounds subject = subjectBounds(scene);
        const ViewMeasure measure = measureView(scene, subject);
        if (scene.cameras.empty()) {
            Camera camera = measure.interior() ? interiorCamera(scene, measure, subject)
                                               : exteriorCamera(scene, subject);
            if (!measure.interior())
                camera.name = "auto (exterior)";
            // A level or an interior with lights of its own is seen from near them.
            const glm::vec3 extent = subject.extent();
            const bool level = extent.y <= 0.5f * std::max(extent.x, extent.z);
            if (!scene.lights.empty()) {
                if (auto near = cameraFromLights(scene, camera, level || measure.interior()))
                    camera = std::move(*near);
            } else if (measure.interior()) {
                if (auto turned = betterInteriorView(scene, camera))
                    camera = std::move(*turned);
            }
            scene.cameras.push_back(std::move(camera));
        }
        if (scene.lights.empty()) {
            scene.lights.push_back(
                defaultLightFor(scene, scene.cameras.front(), measure.interior()));
            scene.defaultLight = true;
        }
    }
    return scene;
}

} // namespace penumbra
