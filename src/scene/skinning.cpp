// The host's placement of skinned vertices (penumbra/scene.h, placeSkinnedVertices): the
// reference the GPU's `skin` pass (shaders/skin.comp) is checked against, written apart from it
// (in double, the normal through an inverse rather than cofactors) so that one mistake is not
// made in both.
#include "scene/skinning.h"

#include "penumbra/error.h"

#include <fmt/format.h>

#include <cmath>

namespace penumbra {

void checkSkinning(const Scene& scene) {
    const Skinning& skin = scene.skinning;
    std::vector<bool> listed(scene.vertices.size(), false);
    for (size_t s = 0; s < skin.vertices.size(); ++s) {
        const SkinnedVertex& sv = skin.vertices[s];
        const auto fail = [&](const std::string& what) {
            throw InputError(scene.name, fmt::format("skinned vertex {}: {}", s, what));
        };
        if (sv.vertex >= scene.vertices.size())
            fail(
                fmt::format("vertex {} is past the {} vertices", sv.vertex, scene.vertices.size()));
        if (listed[sv.vertex])
            fail(fmt::format("vertex {} is skinned twice", sv.vertex));
        listed[sv.vertex] = true;
        if (sv.influenceCount == 0 || sv.firstInfluence > skin.influences.size() ||
            sv.influenceCount > skin.influences.size() - sv.firstInfluence)
            fail(fmt::format("influences [{}, {}) are not within the {} there are",
                             sv.firstInfluence, uint64_t{sv.firstInfluence} + sv.influenceCount,
                             skin.influences.size()));
        double total = 0.0;
        for (uint32_t k = sv.firstInfluence; k < sv.firstInfluence + sv.influenceCount; ++k) {
            if (skin.influences[k].joint >= skin.joints.size())
                fail(fmt::format("joint {} is past the {} joints", skin.influences[k].joint,
                                 skin.joints.size()));
            total += double(skin.influences[k].weight);
        }
        if (!(total > 0.0))
            fail(fmt::format("its weights sum to {}", total));
    }
}

void placeSkinnedVertices(Scene& scene) {
    checkSkinning(scene);
    placeSkinnedVertices(scene, 0, scene.skinning.vertices.size());
}

void placeSkinnedVertices(Scene& scene, size_t first, size_t end) {
    const Skinning& skin = scene.skinning;
    for (size_t s = first; s < end; ++s) {
        const SkinnedVertex& sv = skin.vertices[s];
        glm::dmat4 sum(0.0);
        double total = 0.0;
        for (uint32_t k = sv.firstInfluence; k < sv.firstInfluence + sv.influenceCount; ++k) {
            const SkinInfluence& influence = skin.influences[k];
            sum += double(influence.weight) * glm::dmat4(skin.joints[influence.joint]);
            total += double(influence.weight);
        }
        const glm::dmat4 m = sum / total;
        Vertex& v = scene.vertices[sv.vertex];
        v.position = glm::vec3(m * glm::dvec4(glm::dvec3(sv.position), 1.0));
        const glm::dvec3 n = glm::transpose(glm::inverse(glm::dmat3(m))) * glm::dvec3(sv.normal);
        const double length = glm::length(n);
        v.normal = length > 0.0 && std::isfinite(length) ? glm::vec3(n / length)
                                                         : glm::vec3(0.0f, 1.0f, 0.0f);
    }
}

} // namespace penumbra
