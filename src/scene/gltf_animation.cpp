#include "scene/gltf_animation.h"

#include "penumbra/error.h"
#include "scene/gltf_accessors.h"

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <charconv>
#include <set>

namespace penumbra::gltf {
namespace {

using scene::AnimatedPath;

const char* typeName(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR:
        return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
        return "VEC2";
    case TINYGLTF_TYPE_VEC3:
        return "VEC3";
    case TINYGLTF_TYPE_VEC4:
        return "VEC4";
    default:
        return "a matrix";
    }
}

bool isFloat(const tinygltf::Accessor& a) {
    return a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
}

// Byte or short components scaled to [0,1] or [-1,1]: allowed for rotations and weights.
bool isNormalizedInteger(const tinygltf::Accessor& a) {
    return a.normalized && (a.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
                            a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                            a.componentType == TINYGLTF_COMPONENT_TYPE_SHORT ||
                            a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
}

struct Reader {
    const std::filesystem::path& file;
    const tinygltf::Model& m;

    [[noreturn]] void fail(const std::string& path, const std::string& what) const {
        throw InputError(file.string(), path + ": " + what);
    }

    const tinygltf::Accessor& accessor(const std::string& path, int index) const {
        if (index < 0 || static_cast<size_t>(index) >= m.accessors.size())
            fail(path,
                 fmt::format("index {} is out of range ({} accessors)", index, m.accessors.size()));
        return m.accessors[static_cast<size_t>(index)];
    }

    // The morph targets of the node's mesh (its first primitive's; the spec wants them equal).
    size_t morphTargets(size_t node) const {
        const int mesh = m.nodes[node].mesh;
        if (mesh < 0 || m.meshes[static_cast<size_t>(mesh)].primitives.empty())
            return 0;
        return m.meshes[static_cast<size_t>(mesh)].primitives.front().targets.size();
    }

    scene::AnimationSampler sampler(const std::string& path, const tinygltf::AnimationSampler& s,
                                    AnimatedPath target, size_t node) const {
        const tinygltf::Accessor& in = accessor(path + ".input", s.input);
        if (in.type != TINYGLTF_TYPE_SCALAR || !isFloat(in))
            fail(path + ".input",
                 fmt::format("accessors[{}] is {}{}; keyframe times are SCALAR "
                             "floats",
                             s.input, typeName(in.type), isFloat(in) ? "" : " of integers"));
        const tinygltf::Accessor& out = accessor(path + ".output", s.output);
        const bool vector = target != AnimatedPath::Weights;
        const bool rotation = target == AnimatedPath::Rotation;
        const int wantedType = rotation ? TINYGLTF_TYPE_VEC4
                               : vector ? TINYGLTF_TYPE_VEC3
                                        : TINYGLTF_TYPE_SCALAR;
        const bool componentsAllowed =
            isFloat(out) || (target != AnimatedPath::Translation && target != AnimatedPath::Scale &&
                             isNormalizedInteger(out));
        if (out.type != wantedType || !componentsAllowed)
            fail(path + ".output",
                 fmt::format("accessors[{}] is {}{}; a {} takes {} {}", s.output,
                             typeName(out.type), isFloat(out) ? " of floats" : " of integers",
                             scene::animatedPathName(target), typeName(wantedType),
                             vector && !rotation ? "floats" : "floats or normalized integers"));
        scene::AnimationSampler read;
        if (s.interpolation == "LINEAR") // tinygltf reads an absent one as the default, LINEAR
            read.interpolation = scene::Interpolation::Linear;
        else if (s.interpolation == "STEP")
            read.interpolation = scene::Interpolation::Step;
        else if (s.interpolation == "CUBICSPLINE")
            read.interpolation = scene::Interpolation::CubicSpline;
        else
            fail(path + ".interpolation",
                 fmt::format("'{}' is not LINEAR, STEP or CUBICSPLINE", s.interpolation));
        read.components = rotation ? 4 : vector ? 3 : static_cast<uint32_t>(morphTargets(node));
        if (read.components == 0)
            fail(path, fmt::format("animates the weights of nodes[{}], which has no morph targets",
                                   node));
        read.times = readFloats(m, s.input);
        read.values = readFloats(m, s.output);
        if (const std::string problem = samplerProblem(read, target); !problem.empty())
            fail(path, problem);
        return read;
    }
};

} // namespace

std::vector<Animation> readAnimations(const std::filesystem::path& file, const tinygltf::Model& m,
                                      std::vector<std::string>* warnings) {
    const Reader reader{file, m};
    std::vector<Animation> animations;
    for (size_t a = 0; a < m.animations.size(); ++a) {
        const tinygltf::Animation& source = m.animations[a];
        Animation animation{.name = source.name};
        // The schema asks for at least one of each: an animation without moves nothing.
        for (const auto& [list, count] : {std::pair{"channels", source.channels.size()},
                                          std::pair{"samplers", source.samplers.size()}})
            if (count == 0)
                reader.fail(fmt::format("animations[{}].{}", a, list),
                            "empty; an animation has at least one");
        std::set<std::pair<size_t, AnimatedPath>> targets;
        for (size_t c = 0; c < source.channels.size(); ++c) {
            const tinygltf::AnimationChannel& channel = source.channels[c];
            const std::string path = fmt::format("animations[{}].channels[{}]", a, c);
            if (channel.sampler < 0 ||
                static_cast<size_t>(channel.sampler) >= source.samplers.size())
                reader.fail(path + ".sampler",
                            fmt::format("index {} is out of range ({} samplers)", channel.sampler,
                                        source.samplers.size()));
            if (channel.target_node >= 0 &&
                static_cast<size_t>(channel.target_node) >= m.nodes.size())
                reader.fail(path + ".target.node",
                            fmt::format("index {} is out of range ({} nodes)", channel.target_node,
                                        m.nodes.size()));
            AnimatedPath target{};
            if (!scene::animatedPathFromName(channel.target_path, target)) {
                if (warnings)
                    warnings->push_back(fmt::format("{}: {}.target.path: '{}' is not animated "
                                                    "here (only translation, rotation, scale "
                                                    "and weights); the channel is skipped",
                                                    file.string(), path, channel.target_path));
                continue;
            }
            if (channel.target_node < 0) // the spec: a channel without a node is ignored
                continue;
            const auto node = static_cast<size_t>(channel.target_node);
            if (!m.nodes[node].matrix.empty())
                reader.fail(path + ".target.node",
                            fmt::format("nodes[{}] has a matrix; an animated node has "
                                        "translation, rotation and scale instead",
                                        node));
            if (!targets.emplace(node, target).second)
                reader.fail(path + ".target",
                            fmt::format("nodes[{}]'s {} is animated twice by this animation", node,
                                        channel.target_path));
            const std::string samplerPath =
                fmt::format("animations[{}].samplers[{}]", a, channel.sampler);
            AnimationChannel read{
                .node = node,
                .path = target,
                .sampler = reader.sampler(samplerPath,
                                          source.samplers[static_cast<size_t>(channel.sampler)],
                                          target, node)};
            animation.duration = std::max(animation.duration, read.sampler.times.back());
            animation.channels.push_back(std::move(read));
        }
        animations.push_back(std::move(animation));
    }
    return animations;
}

size_t chooseAnimation(const std::filesystem::path& file, const std::vector<Animation>& animations,
                       std::string_view choice) {
    if (animations.empty())
        throw InputError("--animation", fmt::format("'{}' has no animations", file.string()));
    if (choice.empty())
        return 0;
    for (size_t a = 0; a < animations.size(); ++a)
        if (animations[a].name == choice)
            return a;
    size_t index = 0;
    const auto [end, error] = std::from_chars(choice.data(), choice.data() + choice.size(), index);
    if (error == std::errc{} && end == choice.data() + choice.size() && index < animations.size())
        return index;
    std::string names;
    for (size_t a = 0; a < animations.size(); ++a)
        names += fmt::format("{}{} '{}'", a == 0 ? "" : ", ", a, animations[a].name);
    throw InputError("--animation", fmt::format("'{}' is neither a name nor an index of the "
                                                "animations in '{}' ({})",
                                                choice, file.string(), names));
}

glm::mat4 NodePose::local() const {
    if (hasMatrix)
        return matrix;
    return glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(rotation) *
           glm::scale(glm::mat4(1.0f), scale);
}

std::vector<NodePose> restPoses(const tinygltf::Model& m) {
    std::vector<NodePose> poses(m.nodes.size());
    for (size_t i = 0; i < m.nodes.size(); ++i) {
        const tinygltf::Node& n = m.nodes[i];
        NodePose& p = poses[i];
        if (n.matrix.size() == 16) {
            p.hasMatrix = true;
            for (int k = 0; k < 16; ++k)
                p.matrix[k / 4][k % 4] = static_cast<float>(n.matrix[static_cast<size_t>(k)]);
        }
        if (n.translation.size() == 3)
            p.translation = glm::vec3(n.translation[0], n.translation[1], n.translation[2]);
        if (n.rotation.size() == 4)
            p.rotation =
                glm::quat(static_cast<float>(n.rotation[3]), static_cast<float>(n.rotation[0]),
                          static_cast<float>(n.rotation[1]), static_cast<float>(n.rotation[2]));
        if (n.scale.size() == 3)
            p.scale = glm::vec3(n.scale[0], n.scale[1], n.scale[2]);
        const std::vector<double>& weights = !n.weights.empty() || n.mesh < 0
                                                 ? n.weights
                                                 : m.meshes[static_cast<size_t>(n.mesh)].weights;
        p.weights.assign(weights.begin(), weights.end());
    }
    return poses;
}

void poseAt(const Animation& animation, double time, std::vector<NodePose>& poses) {
    for (const AnimationChannel& c : animation.channels) {
        NodePose& p = poses[c.node];
        float v[4];
        switch (c.path) {
        case AnimatedPath::Translation:
            scene::sampleInto(c.sampler, c.path, time, std::span<float>(v, 3));
            p.translation = glm::vec3(v[0], v[1], v[2]);
            break;
        case AnimatedPath::Rotation:
            scene::sampleInto(c.sampler, c.path, time, std::span<float>(v, 4));
            p.rotation = glm::quat(v[3], v[0], v[1], v[2]);
            break;
        case AnimatedPath::Scale:
            scene::sampleInto(c.sampler, c.path, time, std::span<float>(v, 3));
            p.scale = glm::vec3(v[0], v[1], v[2]);
            break;
        case AnimatedPath::Weights:
            p.weights.resize(c.sampler.components);
            scene::sampleInto(c.sampler, c.path, time, p.weights);
            break;
        }
    }
}

} // namespace penumbra::gltf
