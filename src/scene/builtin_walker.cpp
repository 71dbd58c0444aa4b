// builtin:walker — an animated, skinned built-in (issue 59): a figure walking a circle on a
// floor under a sun and a bulb. It is built once standing straight (its bind pose), and every
// vertex is then placed by linear blend skinning, as a glTF skin places it (gltf_skin.h): the
// weighted sum of its joints' matrices, each the joint's posed world transform times its
// inverse bind transform. Near a knee or an elbow a vertex blends the two joints' matrices, so
// the limb bends smoothly, and its shadow with it. Legs and arms swing once a stride
// (kWalkerStrideSeconds), one lap takes kWalkerLapSeconds (animation 'walk'), and the lower
// foot always touches the floor: a moving contact. The tests pose it from kWalker* alone.
#include "scene/builtin_scenes.h"

#include "scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace penumbra::builtin {
namespace {

// The skeleton in its bind pose (standing, facing +z, feet at y = 0), parents first.
enum Joint { Pelvis, Chest, HipL, KneeL, HipR, KneeR, ShoulderL, ElbowL, ShoulderR, ElbowR };
constexpr size_t kJoints = 10;
struct JointDef {
    int parent;
    glm::vec3 bind; // the joint's place at rest (its inverse bind transform is its negation)
};
constexpr std::array<JointDef, kJoints> kSkeleton{{{-1, {0.0f, 1.0f, 0.0f}},
                                                   {Pelvis, {0.0f, 1.3f, 0.0f}},
                                                   {Pelvis, {-0.14f, 0.95f, 0.0f}},
                                                   {HipL, {-0.14f, 0.52f, 0.0f}},
                                                   {Pelvis, {0.14f, 0.95f, 0.0f}},
                                                   {HipR, {0.14f, 0.52f, 0.0f}},
                                                   {Chest, {-0.31f, 1.5f, 0.0f}},
                                                   {ShoulderL, {-0.31f, 1.22f, 0.0f}},
                                                   {Chest, {0.31f, 1.5f, 0.0f}},
                                                   {ShoulderR, {0.31f, 1.22f, 0.0f}}}};
constexpr float kAnkleHeight = 0.09f, kFootRadius = 0.09f, kHandHeight = 0.95f;
constexpr float kFootForward = 0.03f; // the foot's centre, ahead of the ankle
constexpr float kBlend = 0.07f;       // half the height over which a knee or elbow blends

// The angle of a turn every `period` seconds at `time`, in [0, 2 pi): the time reduced by the
// period in double first, so that a pose late in a long run is as fine as an early one.
double turned(double time, double period) {
    const double turns = time / period;
    return 2.0 * std::numbers::pi * (turns - std::floor(turns));
}

// The joints' bends at `time` about their local x axis (positive: the lower end goes back).
std::array<float, kJoints> jointAngles(double time) {
    const float phase = static_cast<float>(turned(time, kWalkerStrideSeconds));
    const float swing = 0.45f * std::sin(phase); // the left leg forward, the right back
    std::array<float, kJoints> a{};
    a[HipL] = -swing;
    a[HipR] = swing;
    a[KneeL] = 0.9f * std::max(0.0f, std::cos(phase)); // bent while it swings forward
    a[KneeR] = 0.9f * std::max(0.0f, -std::cos(phase));
    a[ShoulderL] = 0.6f * swing; // arms against the legs
    a[ShoulderR] = -0.6f * swing;
    a[ElbowL] = a[ElbowR] = -0.35f; // forearms a little forward
    a[Chest] = 0.05f;               // a slight lean into the walk
    return a;
}

// Each joint's skinning matrix at `time`: posed world transform times inverse bind transform.
std::array<glm::mat4, kJoints> skinMatrices(double time) {
    const std::array<float, kJoints> angles = jointAngles(time);
    const float heading = static_cast<float>(turned(time, kWalkerLapSeconds));
    // Counter-clockwise seen from above, facing along the circle: +z turns to the tangent.
    const glm::vec3 place(kWalkerCircleRadius * std::cos(heading), 0.0f,
                          kWalkerCircleRadius * std::sin(heading));
    std::array<glm::mat4, kJoints> world{};
    for (size_t j = 0; j < kJoints; ++j) {
        const JointDef& d = kSkeleton[j];
        const glm::mat4 parent = d.parent < 0 ? glm::rotate(glm::translate(glm::mat4(1.0f), place),
                                                            -heading, glm::vec3(0, 1, 0))
                                              : world[size_t(d.parent)];
        const glm::vec3 offset = d.parent < 0 ? d.bind : d.bind - kSkeleton[size_t(d.parent)].bind;
        world[j] = glm::rotate(glm::translate(parent, offset), angles[j], glm::vec3(1, 0, 0));
    }
    // Lift (or lower) the whole figure so that the lower foot's sole touches the floor.
    float sole = INFINITY;
    for (const Joint knee : {KneeL, KneeR}) {
        const glm::vec3 foot(kSkeleton[knee].bind.x, kAnkleHeight, kFootForward);
        const glm::vec4 posed = world[knee] * glm::vec4(foot - kSkeleton[knee].bind, 1.0f);
        sole = std::min(sole, posed.y - kFootRadius);
    }
    std::array<glm::mat4, kJoints> skin{};
    for (size_t j = 0; j < kJoints; ++j)
        skin[j] = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -sole, 0.0f)) * world[j] *
                  glm::translate(glm::mat4(1.0f), -kSkeleton[j].bind);
    return skin;
}

// A vertex's two joints and the lower one's weight: limbs blend across their middle joint.
struct Weights {
    Joint upper, lower;
    float lowerWeight;
};

Weights limbWeights(Joint upper, Joint lower, float y) {
    const float middle = kSkeleton[lower].bind.y;
    return {upper, lower, std::clamp((middle + kBlend - y) / (2.0f * kBlend), 0.0f, 1.0f)};
}

} // namespace

Scene walker(double time) {
    Scene scene;
    scene.name = "walker";
    scene.animation = "walk";
    scene.animationDuration = static_cast<float>(kWalkerLapSeconds);
    MeshBuilder mb(scene);
    const float g = kWalkerFloorHalfSize;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g},
            mb.material("floor", {0.5f, 0.5f, 0.48f}));
    const uint32_t body = mb.material("figure", {0.75f, 0.55f, 0.42f});
    const uint32_t cloth = mb.material("clothes", {0.25f, 0.35f, 0.6f});
    const size_t figureStart = scene.vertices.size();
    std::vector<Weights> weights;
    // The vertices added since the last call follow joint j alone.
    const auto rigid = [&](Joint j) {
        weights.resize(scene.vertices.size() - figureStart, {j, j, 0.0f});
    };
    // A limb from its upper joint down to `bottom`, in short tubes so that it bends smoothly.
    const auto limb = [&](Joint upper, Joint lower, float bottom, float radius, uint32_t material) {
        const glm::vec3 top = kSkeleton[upper].bind;
        const int pieces = 10;
        for (int k = 0; k < pieces; ++k) {
            const float y0 = top.y + (bottom - top.y) * float(k) / pieces;
            const float y1 = top.y + (bottom - top.y) * float(k + 1) / pieces;
            mb.tube({top.x, y0, 0.0f}, {top.x, y1, 0.0f}, radius, material, 10);
        }
        for (size_t v = figureStart + weights.size(); v < scene.vertices.size(); ++v)
            weights.push_back(limbWeights(upper, lower, scene.vertices[v].position.y));
    };
    limb(HipL, KneeL, kAnkleHeight, 0.075f, cloth);
    mb.sphere({kSkeleton[HipL].bind.x, kAnkleHeight, kFootForward}, kFootRadius, body, 12, 8);
    rigid(KneeL);
    limb(HipR, KneeR, kAnkleHeight, 0.075f, cloth);
    mb.sphere({kSkeleton[HipR].bind.x, kAnkleHeight, kFootForward}, kFootRadius, body, 12, 8);
    rigid(KneeR);
    mb.sphere({0.0f, 0.98f, 0.0f}, 0.21f, cloth, 14, 8);
    rigid(Pelvis);
    mb.tube({0.0f, 1.02f, 0.0f}, {0.0f, 1.52f, 0.0f}, 0.18f, cloth, 14);
    mb.tube({-0.31f, 1.5f, 0.0f}, {0.31f, 1.5f, 0.0f}, 0.07f, cloth, 10);
    mb.tube({0.0f, 1.52f, 0.0f}, {0.0f, 1.64f, 0.0f}, 0.05f, body, 8);
    mb.sphere({0.0f, 1.75f, 0.02f}, 0.13f, body, 12, 8);
    rigid(Chest);
    limb(ShoulderL, ElbowL, kHandHeight, 0.048f, body);
    mb.sphere({kSkeleton[ShoulderL].bind.x, kHandHeight, 0.0f}, 0.055f, body, 10, 6);
    rigid(ElbowL);
    limb(ShoulderR, ElbowR, kHandHeight, 0.048f, body);
    mb.sphere({kSkeleton[ShoulderR].bind.x, kHandHeight, 0.0f}, 0.055f, body, 10, 6);
    rigid(ElbowR);
    // Linear blend skinning: each vertex by the weighted sum of its joints' matrices, on the
    // host here and on the GPU in each frame after a pose (Scene::skinning).
    const std::array<glm::mat4, kJoints> skin = skinMatrices(time);
    scene.skinning.joints.assign(skin.begin(), skin.end());
    for (size_t v = figureStart; v < scene.vertices.size(); ++v) {
        const Weights& w = weights[v - figureStart];
        const Vertex& bind = scene.vertices[v];
        const uint32_t first = static_cast<uint32_t>(scene.skinning.influences.size());
        for (const auto& [joint, weight] :
             {std::pair{w.upper, 1.0f - w.lowerWeight}, std::pair{w.lower, w.lowerWeight}})
            if (weight > 0.0f)
                scene.skinning.influences.push_back({.joint = joint, .weight = weight});
        scene.skinning.vertices.push_back(
            {.vertex = static_cast<uint32_t>(v),
             .firstInfluence = first,
             .influenceCount = static_cast<uint32_t>(scene.skinning.influences.size()) - first,
             .position = bind.position,
             .normal = bind.normal});
    }
    placeSkinnedVertices(scene);
    scene.lights.push_back({.name = "sun",
                            .type = LightType::Directional,
                            .direction = glm::normalize(kWalkerSunDirection),
                            .intensity = 2.5f,
                            .angularDiameter = 1.0f});
    scene.lights.push_back({.name = "bulb",
                            .type = LightType::Point,
                            .position = kWalkerBulbPosition,
                            .intensity = 25.0f,
                            .radius = 0.08f});
    scene.cameras.push_back(mainCamera({1.5f, 4.0f, 7.0f}, {0.0f, 0.5f, 0.0f}, 0.75f));
    return scene;
}

} // namespace penumbra::builtin
