#pragma once
// The built-in scenes, made in code (docs/scenes.md). Their layout is part of the test
// contract: tests compute analytic shadows from the same constants.
#include "penumbra/scene.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace penumbra::builtin {

// Showcase geometry, shared with the analytic tests.
inline constexpr glm::vec3 kSphereCenter{-3.0f, 2.6f, 0.0f};
inline constexpr float kSphereRadius = 1.0f;
inline constexpr float kGroundHalfSize = 12.0f;
inline constexpr glm::vec3 kPoleBase{-0.6f, 0.0f, -0.4f};
inline constexpr glm::vec3 kPoleTip{0.6f, 2.6f, -1.3f};
inline constexpr float kPoleThickness = 0.08f;
// Direction the sun's light travels (normalised when used): about 60 degrees elevation.
inline constexpr glm::vec3 kSunDirection{0.35f, -1.0f, 0.45f};
inline constexpr glm::vec3 kSpotPosition{-5.2f, 11.0f, -6.0f};
inline constexpr glm::vec3 kSpotTarget{0.0f, 0.0f, 0.5f};

// Grazing: a plane lit 85 degrees from its normal, and a low box on it.
inline constexpr float kGrazingAngleDegrees = 85.0f;
inline constexpr glm::vec3 kGrazingBoxCenter{-4.0f, 0.15f, 0.0f};
inline constexpr glm::vec3 kGrazingBoxSize{1.0f, 0.3f, 1.0f};
inline constexpr float kGrazingHalfSize = 20.0f;

// Foliage: alpha-tested casters (a pergola roof of tiled leaves, bushes, a lattice trellis).
inline constexpr uint32_t kLeafTextureSize = 256;
inline constexpr uint32_t kLatticeTextureSize = 64;
inline constexpr uint32_t kLatticePeriod = 16, kLatticeBar = 5; // texels
inline constexpr float kFoliageAlphaCutoff = 0.5f;
inline constexpr glm::vec3 kCanopyMin{-4.5f, 3.0f, -3.5f}; // the roof lies at y = kCanopyMin.y
inline constexpr glm::vec3 kCanopyMax{1.5f, 3.0f, 0.5f};
inline constexpr glm::vec2 kCanopyTiles{3.0f, 2.0f};
inline constexpr glm::vec3 kTrellisMin{2.5f, 0.0f, -3.0f}; // a vertical quad at z = kTrellisMin.z
inline constexpr glm::vec3 kTrellisMax{5.5f, 2.4f, -3.0f};

// Room: a point light in a cut-away room (floor, ceiling, three walls; open towards +z).
inline constexpr float kRoomHalfWidth = 5.0f;
inline constexpr float kRoomHeight = 4.5f;
inline constexpr float kRoomCeilingFront = 2.0f; // the ceiling and side walls end at this z
inline constexpr float kRoomFloorFront = 6.0f;   // the floor runs on to this z
inline constexpr glm::vec3 kRoomLightPosition{0.0f, 1.8f, -0.5f};

// Field: an 800-unit ground, objects from 2 to kFieldFarthest units ahead of the camera (at the
// origin, looking down -z), a low sun.
inline constexpr float kFieldHalfSize = 400.0f;
inline constexpr float kFieldFarthest = 180.0f;
inline constexpr glm::vec3 kFieldSunDirection{0.55f, -0.45f, -0.35f};

// Demo: the sun's angular diameter (degrees) in `make demo`'s scene.
inline constexpr float kDemoSunDegrees = 4.0f;

// Pendulum (animated, issue 59): a ball on a rod swinging in the x-y plane from a pivot, angle
// kPendulumAmplitude * cos(2 pi t / kPendulumPeriod) from the vertical; its lowest point 0.2
// above the floor at y = 0.
inline constexpr glm::vec3 kPendulumPivot{0.0f, 4.2f, 0.0f};
inline constexpr float kPendulumLength = 3.5f; // pivot to the ball's centre
inline constexpr float kPendulumBobRadius = 0.5f;
inline constexpr double kPendulumAmplitude = 0.8; // radians
inline constexpr double kPendulumPeriod = 2.0;    // seconds
inline constexpr float kPendulumFloorHalfSize = 8.0f;
inline constexpr glm::vec3 kPendulumSunDirection{0.2f, -1.0f, 0.15f};

// Town (animated): houses and a tower on a street kTownHalfSize from the centre, under a sun
// whose arc runs from kTownSunriseAngle above the east horizon (+x) at time 0 to as far above
// the west at kTownDaySeconds, its plane leaning kTownNoonElevation towards the south (-z).
inline constexpr float kTownHalfSize = 15.0f;
inline constexpr float kTownTowerHeight = 9.0f;
inline constexpr double kTownDaySeconds = 12.0;
inline constexpr double kTownSunriseAngle = 0.2618;  // 15 degrees along the arc
inline constexpr double kTownNoonElevation = 0.9599; // 55 degrees

// Fan (animated): three blades kFanBladeLength from the axis (through the origin, vertical),
// kFanBladeWidth wide and kFanBladeThickness thick at height kFanHeight, one turn in
// kFanTurnSeconds about +y; a spot above them pointing down.
inline constexpr float kFanHeight = 2.5f;
inline constexpr float kFanBladeLength = 1.6f;
inline constexpr float kFanBladeWidth = 0.3f;
inline constexpr float kFanBladeThickness = 0.02f;
inline constexpr double kFanTurnSeconds = 0.25;
inline constexpr float kFanFloorHalfSize = 6.0f;
inline constexpr glm::vec3 kFanSpotPosition{0.4f, 4.2f, 0.3f};

// Walker (animated, skinned): a figure walking counter-clockwise (seen from above) around a
// circle of radius kWalkerCircleRadius about the origin, facing along it, starting at +x: one
// lap in kWalkerLapSeconds, a stride (two steps) in kWalkerStrideSeconds; a sun and a bulb
// above the circle's centre.
inline constexpr double kWalkerStrideSeconds = 1.0;
inline constexpr double kWalkerLapSeconds = 10.0;
inline constexpr float kWalkerCircleRadius = 2.5f;
inline constexpr float kWalkerFloorHalfSize = 7.0f;
inline constexpr glm::vec3 kWalkerSunDirection{0.35f, -1.0f, 0.25f};
inline constexpr glm::vec3 kWalkerBulbPosition{0.0f, 3.2f, 0.0f};

// Dense: kDenseRows x kDenseColumns cells of a box and a sphere of 2 x slices x (stacks - 1)
// triangles (about 100k in all), a spot light.
inline constexpr int kDenseRows = 4, kDenseColumns = 6;
inline constexpr uint32_t kDenseSphereSlices = 66, kDenseSphereStacks = 32;
inline constexpr float kDenseHalfSize = 14.0f;
inline constexpr glm::vec3 kDenseSpotPosition{-4.0f, 14.0f, -5.0f};

// builtin:sheets: a sheet over the ground, level at `height`, a rectangle about `centre` (x, z)
// of half-size `halfSize`: a filter (its transmission, tinted by `colour`) or, without
// transmission, a BLEND cover of `alpha` (grey: it lets 1 - alpha through).
struct SheetSpec {
    const char* name;
    float height;
    glm::vec2 centre, halfSize;
    glm::vec3 colour;
    float transmission;
    float alpha;
};
inline constexpr float kSheetsGroundHalfSize = 6.0f;
// Low enough that each sheet's shadow falls beside it: 0.85 of its height along x.
inline constexpr glm::vec3 kSheetsSunDirection{0.85f, -1.0f, 0.25f};
inline constexpr SheetSpec kSheets[] = {
    {"red filter", 1.0f, {-0.6f, -0.4f}, {1.2f, 1.2f}, {0.9f, 0.25f, 0.2f}, 1.0f, 1.0f},
    {"green filter", 1.5f, {0.5f, -0.5f}, {1.2f, 1.2f}, {0.2f, 0.85f, 0.3f}, 1.0f, 1.0f},
    {"blue filter", 2.0f, {0.0f, 0.5f}, {1.2f, 1.2f}, {0.25f, 0.35f, 0.95f}, 0.8f, 1.0f},
    {"curtain", 2.6f, {-1.4f, 0.6f}, {1.0f, 1.6f}, {0.8f, 0.8f, 0.8f}, 0.0f, 0.5f}};

// builtin:glass (stained glass over a floor): six panes of kGlassPaneSize at kGlassHeight, each
// a thin-walled filter of its colour (transmission 1), in lead bars kGlassLead thick on posts
// kGlassPost thick at the window's corners, and a cube of glass with a volume on the floor.
struct PaneSpec {
    const char* name;
    glm::vec2 corner; // its (x, z) corner of least x and z
    glm::vec3 colour;
};
inline constexpr float kGlassFloorHalfSize = 6.0f;
inline constexpr float kGlassHeight = 2.2f;
inline constexpr float kGlassPaneSize = 1.0f;
inline constexpr float kGlassLead = 0.06f;
inline constexpr float kGlassPost = 0.1f;
inline constexpr PaneSpec kGlassPanes[] = {{"ruby", {-1.5f, -1.0f}, {0.85f, 0.1f, 0.12f}},
                                           {"amber", {-0.5f, -1.0f}, {0.95f, 0.6f, 0.1f}},
                                           {"emerald", {0.5f, -1.0f}, {0.1f, 0.7f, 0.25f}},
                                           {"sapphire", {-1.5f, 0.0f}, {0.15f, 0.3f, 0.9f}},
                                           {"violet", {-0.5f, 0.0f}, {0.55f, 0.2f, 0.8f}},
                                           {"pale", {0.5f, 0.0f}, {0.9f, 0.88f, 0.8f}}};
// A cube of side `size` (its thickness) centred at `centre`: transmission 1 through `colour`,
// attenuated to attenuationColor every attenuationDistance.
struct GlassBlockSpec {
    glm::vec3 centre;
    float size;
    glm::vec3 colour;
    float attenuationDistance;
    glm::vec3 attenuationColor;
};
inline constexpr GlassBlockSpec kGlassBlock{
    {2.6f, 0.5f, 1.6f}, 1.0f, {0.9f, 1.0f, 0.95f}, 1.5f, {0.4f, 0.8f, 0.9f}};
// Each pane's shadow falls 0.45 of the skylight's height along x, 0.3 along z.
inline constexpr glm::vec3 kGlassSunDirection{0.45f, -1.0f, 0.3f};

// builtin:tree (a tree of BLEND leaves): kTreeLeaves square cards kTreeLeafSize wide in an
// ellipsoid crown, each a leaf of alpha kTreeLeafAlpha where it covers.
inline constexpr float kTreeGroundHalfSize = 6.0f;
inline constexpr glm::vec3 kTreeCrownCentre{0.0f, 2.6f, 0.0f};
inline constexpr glm::vec3 kTreeCrownRadii{1.4f, 0.9f, 1.4f};
inline constexpr int kTreeLeaves = 400;
inline constexpr float kTreeLeafSize = 0.45f;
inline constexpr float kTreeLeafAlpha = 0.7f;
inline constexpr uint32_t kTreeLeafTextureSize = 64;
inline constexpr glm::vec3 kTreeSunDirection{0.35f, -1.0f, 0.2f};

// Deterministic pseudo-random numbers in [0, 1) (a linear congruential generator): a built-in
// scene must be identical on every run.
struct SceneRandom {
    uint32_t state;
    float next() {
        state = state * 1664525u + 1013904223u;
        return static_cast<float>(state >> 8) / 16777216.0f;
    }
};
// A leaf's coverage at (u, v) in units of its ellipse's half-axes, `halfWidth` texels across
// its narrow half: 1 inside, 0 outside, anti-aliased over a texel at its edge (about the covered
// fraction).
inline float leafCoverage(float u, float v, float halfWidth) {
    return std::clamp((1.0f - std::sqrt(u * u + v * v)) * halfWidth + 0.5f, 0.0f, 1.0f);
}
// Tileable leaves (builtin:foliage's texture, kLeafTextureSize square): `count` ellipses with
// anti-aliased edges (alpha = covered fraction, about), greens varying per leaf; repeat-wrapped.
TextureImage leafImage(uint32_t seed = 12345u, int count = 150);
// The outdoor scenes' sun: kSunDirection, 0.53 degrees wide (the real sun's size), warm white.
Light sun();
// A built-in scene's camera: "main", near plane 0.1.
inline Camera mainCamera(glm::vec3 position, glm::vec3 target, float yfov, float zfar = 100.0f) {
    return {.name = "main",
            .position = position,
            .target = target,
            .yfov = yfov,
            .znear = 0.1f,
            .zfar = zfar};
}
// The spot scenes' light: warm white, radius 0.2, about 1.8 at `target` (inverse square).
Light spotLight(const glm::vec3& position, const glm::vec3& target, float innerConeAngle,
                float outerConeAngle);

Scene showcase();
Scene grazing();
Scene spot();
Scene foliage();
Scene room();
Scene field();
Scene bleeding();
Scene sheets();
Scene glass();
Scene tree();
Scene dense();
Scene demo();
Scene figure();
// Objects resting on a plane (the contact layer's scene): without lights, and with its sun.
Scene restingGeometry();
Scene resting();
// Animated: the scene posed `time` seconds in (any time; periodic), and the ball's centre then.
Scene pendulum(double time);
glm::vec3 pendulumBob(double time);
Scene town(double time);
glm::vec3 townSunDirection(double time); // the direction the sun's light travels at `time`
Scene fan(double time);
float fanAngle(double time); // the first blade's angle about +y from +x, in [0, 2 pi)
Scene walker(double time);

} // namespace penumbra::builtin
