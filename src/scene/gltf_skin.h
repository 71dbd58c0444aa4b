#pragma once
// glTF skins (the specification's section 3.7.3) evaluated on the CPU when the scene is posed:
// each joint's matrix is its node's posed world transform times its inverse bind matrix, and a
// vertex moves by the weighted sum of its joints' matrices over every JOINTS_n/WEIGHTS_n set.
// The skinned mesh's own node transform is ignored, as the specification says. This is the
// reference evaluation that the vertex positions of issue 59 are checked against.
#include "scene/gltf_animation.h"

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include <filesystem>
#include <vector>

namespace penumbra::gltf {

struct Skin {
    std::vector<size_t> joints;         // node indices
    std::vector<glm::mat4> inverseBind; // one per joint (identity without the accessor)
};

// Every skin, checked: joints in range and each once, the skeleton in range, the inverse bind
// matrices MAT4 floats, at least one per joint. InputError(file, "skins[s]...: what").
std::vector<Skin> readSkins(const std::filesystem::path& file, const tinygltf::Model& model);

// Every node's world transform with `poses`: roots (nodes no node lists as a child) at the
// identity. (validateModel has refused cycles and second parents.)
std::vector<glm::mat4> nodeWorlds(const tinygltf::Model& model, const std::vector<NodePose>& poses);

// Per vertex of primitive `prim` (at JSON path `path`) of node `node`, which has `skin`: the
// matrix that places it, the weighted sum of its joints' (weights scaled to sum to 1).
// InputError naming the attribute: joints that are not VEC4 unsigned bytes or shorts, weights
// that are not VEC4 floats or normalized unsigned bytes or shorts, a joint past the skin's
// joints, a vertex whose weights sum to 0, a skinned primitive without JOINTS_0 and WEIGHTS_0.
std::vector<glm::mat4> skinMatrices(const std::filesystem::path& file, const tinygltf::Model& model,
                                    const tinygltf::Primitive& prim, const std::string& path,
                                    size_t node, const Skin& skin,
                                    const std::vector<glm::mat4>& worlds);

} // namespace penumbra::gltf
