#pragma once
// glTF animations read from a checked model (issue 59): every sampler and channel checked as the
// specification says, a refusal naming the file and the JSON path like every other glTF check,
// and the nodes' local transforms posed at a time. The flattener walks the posed nodes, so
// meshes, cameras and KHR_lights_punctual lights move with their animated nodes.
#include "scene/animation.h"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <tiny_gltf.h>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra::gltf {

struct AnimationChannel {
    size_t node = 0;
    scene::AnimatedPath path = scene::AnimatedPath::Translation;
    // The channel's sampler with its keyframes read; weights have one component per morph
    // target of the node's mesh.
    scene::AnimationSampler sampler;
};

struct Animation {
    std::string name; // as the file names it; may be empty
    std::vector<AnimationChannel> channels;
    float duration = 0.0f; // the last keyframe's time over all its channels, seconds
};

// Every animation of the model, checked: sampler and node references in range, keyframe times
// SCALAR floats, not negative and strictly increasing, outputs of the path's type (VEC3 floats
// for translation and scale; VEC4 floats or normalized integers for rotation; SCALAR for
// weights, one per morph target), value counts, interpolations, no node animated by a matrix, no
// target animated twice by one animation. Throws InputError(file, "animations[a]...: what").
// Channels without a node, or with a path of an extension, are skipped (said in `warnings`).
std::vector<Animation> readAnimations(const std::filesystem::path& file,
                                      const tinygltf::Model& model,
                                      std::vector<std::string>* warnings);

// The animation `choice` names: "" the first; a name; or an index. InputError("--animation", ...)
// listing the names otherwise.
size_t chooseAnimation(const std::filesystem::path& file, const std::vector<Animation>& animations,
                       std::string_view choice);

// A node's local transform: its matrix, or translation, rotation and scale (T * R * S).
struct NodePose {
    bool hasMatrix = false;
    glm::mat4 matrix{1.0f};
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f}; // w, x, y, z
    glm::vec3 scale{1.0f};
    std::vector<float> weights; // morph targets': the node's, else its mesh's
    glm::mat4 local() const;
};

// Every node's pose as the file stores it (the rest pose).
std::vector<NodePose> restPoses(const tinygltf::Model& model);
// The poses `animation` gives its targets at `time` seconds (ends held); others stay as they are.
void poseAt(const Animation& animation, double time, std::vector<NodePose>& poses);

} // namespace penumbra::gltf
