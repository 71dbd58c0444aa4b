#include "scene/gltf_skin.h"

#include "penumbra/error.h"
#include "scene/gltf_accessors.h"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

namespace penumbra::gltf {
namespace {

bool unsignedByteOrShort(int componentType) {
    return componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
           componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
}

} // namespace

std::vector<Skin> readSkins(const std::filesystem::path& file, const tinygltf::Model& m) {
    const auto fail = [&](const std::string& path, const std::string& what) {
        throw InputError(file.string(), path + ": " + what);
    };
    std::vector<Skin> skins;
    for (size_t s = 0; s < m.skins.size(); ++s) {
        const tinygltf::Skin& source = m.skins[s];
        const std::string path = fmt::format("skins[{}]", s);
        Skin skin;
        for (size_t k = 0; k < source.joints.size(); ++k) {
            const int joint = source.joints[k];
            const std::string at = fmt::format("{}.joints[{}]", path, k);
            if (joint < 0 || static_cast<size_t>(joint) >= m.nodes.size())
                fail(at, fmt::format("index {} is out of range ({} nodes)", joint, m.nodes.size()));
            const auto same = std::find(skin.joints.begin(), skin.joints.end(), size_t(joint));
            if (same != skin.joints.end())
                fail(at, fmt::format("nodes[{}] is joints[{}] already", joint,
                                     same - skin.joints.begin()));
            skin.joints.push_back(static_cast<size_t>(joint));
        }
        if (skin.joints.empty())
            fail(path + ".joints", "no joints");
        if (source.skeleton >= 0 && static_cast<size_t>(source.skeleton) >= m.nodes.size())
            fail(path + ".skeleton", fmt::format("index {} is out of range ({} nodes)",
                                                 source.skeleton, m.nodes.size()));
        skin.inverseBind.assign(skin.joints.size(), glm::mat4(1.0f));
        if (const int i = source.inverseBindMatrices; i >= 0) {
            const std::string at = path + ".inverseBindMatrices";
            if (static_cast<size_t>(i) >= m.accessors.size())
                fail(at,
                     fmt::format("index {} is out of range ({} accessors)", i, m.accessors.size()));
            const tinygltf::Accessor& a = m.accessors[static_cast<size_t>(i)];
            if (a.type != TINYGLTF_TYPE_MAT4 || a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
                fail(at, fmt::format("accessors[{}] is not MAT4 floats", i));
            if (a.count < skin.joints.size())
                fail(at, fmt::format("accessors[{}] holds {} matrices for {} joints", i, a.count,
                                     skin.joints.size()));
            const std::vector<float> values = readFloats(m, i);
            for (size_t j = 0; j < skin.joints.size(); ++j)
                for (int c = 0; c < 16; ++c) {
                    const float v = values[16 * j + static_cast<size_t>(c)];
                    if (!std::isfinite(v))
                        fail(at, fmt::format("matrix {} is not finite", j));
                    skin.inverseBind[j][c / 4][c % 4] = v; // column-major, as glm
                }
        }
        skins.push_back(std::move(skin));
    }
    return skins;
}

std::vector<glm::mat4> nodeWorlds(const tinygltf::Model& m, const std::vector<NodePose>& poses) {
    std::vector<bool> child(m.nodes.size(), false);
    for (const tinygltf::Node& n : m.nodes)
        for (const int c : n.children)
            child[static_cast<size_t>(c)] = true;
    std::vector<glm::mat4> worlds(m.nodes.size(), glm::mat4(1.0f));
    std::vector<size_t> stack; // iterative: no recursion depth limit
    for (size_t i = 0; i < m.nodes.size(); ++i)
        if (!child[i]) {
            worlds[i] = poses[i].local();
            stack.push_back(i);
        }
    while (!stack.empty()) {
        const size_t i = stack.back();
        stack.pop_back();
        for (const int c : m.nodes[i].children) {
            const auto k = static_cast<size_t>(c);
            worlds[k] = worlds[i] * poses[k].local();
            stack.push_back(k);
        }
    }
    return worlds;
}

std::vector<glm::mat4> jointMatrices(const Skin& skin, const std::vector<glm::mat4>& worlds) {
    std::vector<glm::mat4> joints(skin.joints.size());
    for (size_t j = 0; j < joints.size(); ++j)
        joints[j] = worlds[skin.joints[j]] * skin.inverseBind[j];
    return joints;
}

PrimitiveInfluences skinInfluences(const std::filesystem::path& file, const tinygltf::Model& m,
                                   const tinygltf::Primitive& prim, const std::string& path,
                                   size_t node, const Skin& skin) {
    const auto fail = [&](const std::string& at, const std::string& what) {
        throw InputError(file.string(), at + ": " + what);
    };
    if (!prim.attributes.contains("JOINTS_0") || !prim.attributes.contains("WEIGHTS_0"))
        fail(fmt::format("nodes[{}]", node),
             fmt::format("skins[{}] needs JOINTS_0 and WEIGHTS_0 in {}", m.nodes[node].skin, path));
    const size_t count = m.accessors[static_cast<size_t>(prim.attributes.at("POSITION"))].count;
    // Every set's joints and weights, read and checked first.
    std::vector<std::vector<float>> indexSets, weightSets;
    std::vector<std::string> weightPaths;
    for (int set = 0;; ++set) {
        const auto jointsAt = prim.attributes.find(fmt::format("JOINTS_{}", set));
        const auto weightsAt = prim.attributes.find(fmt::format("WEIGHTS_{}", set));
        const bool hasJoints = jointsAt != prim.attributes.end(),
                   hasWeights = weightsAt != prim.attributes.end();
        if (hasJoints != hasWeights)
            fail(path + ".attributes",
                 fmt::format("JOINTS_{0} and WEIGHTS_{0} come in pairs; {1}_{0} is missing", set,
                             hasJoints ? "WEIGHTS" : "JOINTS"));
        if (!hasJoints)
            break;
        const std::string jointsPath = fmt::format("{}.attributes.JOINTS_{}", path, set);
        const std::string weightsPath = fmt::format("{}.attributes.WEIGHTS_{}", path, set);
        const tinygltf::Accessor& ja = m.accessors[static_cast<size_t>(jointsAt->second)];
        const tinygltf::Accessor& wa = m.accessors[static_cast<size_t>(weightsAt->second)];
        if (ja.type != TINYGLTF_TYPE_VEC4 || ja.normalized ||
            !unsignedByteOrShort(ja.componentType))
            fail(jointsPath, fmt::format("accessors[{}] is not VEC4 unsigned bytes or shorts",
                                         jointsAt->second));
        if (wa.type != TINYGLTF_TYPE_VEC4 ||
            !(wa.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
              (wa.normalized && unsignedByteOrShort(wa.componentType))))
            fail(weightsPath, fmt::format("accessors[{}] is not VEC4 floats or normalized "
                                          "unsigned bytes or shorts",
                                          weightsAt->second));
        std::vector<float> index = readFloats(m, jointsAt->second);
        std::vector<float> weight = readFloats(m, weightsAt->second);
        for (size_t v = 0; v < count; ++v)
            for (size_t k = 0; k < 4; ++k) {
                const auto j = static_cast<size_t>(index[4 * v + k]);
                if (j >= skin.joints.size())
                    fail(jointsPath, fmt::format("vertex {}'s joint {} is past skins[{}]'s {} "
                                                 "joints",
                                                 v, j, m.nodes[node].skin, skin.joints.size()));
                if (!(weight[4 * v + k] >= 0.0f))
                    fail(weightsPath, fmt::format("vertex {}'s weight {} is {}; weights are 0 or "
                                                  "more",
                                                  v, k, weight[4 * v + k]));
            }
        indexSets.push_back(std::move(index));
        weightSets.push_back(std::move(weight));
        weightPaths.push_back(weightsPath);
    }
    PrimitiveInfluences out;
    out.starts.reserve(count + 1);
    for (size_t v = 0; v < count; ++v) {
        // Summed in double: weights near the float's limit (3e38 twice) would overflow a float.
        double sum = 0.0;
        for (const std::vector<float>& weight : weightSets)
            for (size_t k = 0; k < 4; ++k)
                sum += double(weight[4 * v + k]);
        if (!(sum > 0.0))
            fail(weightPaths.front(), fmt::format("vertex {}'s weights sum to {}", v, sum));
        out.starts.push_back(static_cast<uint32_t>(out.influences.size()));
        // Weights should sum to 1; quantized ones miss by a little, and are scaled to.
        for (size_t set = 0; set < weightSets.size(); ++set)
            for (size_t k = 0; k < 4; ++k)
                if (const float w = weightSets[set][4 * v + k]; w > 0.0f)
                    out.influences.push_back(
                        {.joint = static_cast<uint32_t>(indexSets[set][4 * v + k]),
                         .weight = static_cast<float>(double(w) / sum)});
    }
    out.starts.push_back(static_cast<uint32_t>(out.influences.size()));
    return out;
}

} // namespace penumbra::gltf
