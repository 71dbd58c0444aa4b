#pragma once
// glTF 2.0 animation samplers (the specification's section 3.11 and Appendix C): keyframe times
// and values sampled at a time with STEP, LINEAR (spherical for rotations) or CUBICSPLINE
// interpolation. The first step of animated scenes (issue 59): the loader, skins and the renderer
// build on it. Pure CPU code; the vertex positions the renderer will compute are checked against
// this evaluation.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra::scene {

enum class Interpolation { Step, Linear, CubicSpline };

// What a channel animates: a node's translation (3 floats), rotation (a quaternion x, y, z, w),
// scale (3), or the weights of its mesh's morph targets (one per target).
enum class AnimatedPath { Translation, Rotation, Scale, Weights };

struct AnimationSampler {
    std::vector<float> times; // seconds, strictly increasing
    // Per keyframe, `components` floats; CUBICSPLINE holds three groups a keyframe: the in-tangent,
    // the value, the out-tangent (the specification's order).
    std::vector<float> values;
    uint32_t components = 0;
    Interpolation interpolation = Interpolation::Linear;
};

// Why the sampler breaks the specification ("" when it does not): no keyframe, times not finite,
// negative or not strictly increasing, a value count that is not the keyframes' (times three for
// CUBICSPLINE, which needs two keyframes), values not finite, a rotation without 4 components.
std::string samplerProblem(const AnimationSampler& sampler, AnimatedPath path);

// glTF's name of a path ("translation", "rotation", "scale", "weights") and the path of a name
// (false for any other).
const char* animatedPathName(AnimatedPath path);
bool animatedPathFromName(std::string_view name, AnimatedPath& path);

// The sampler's value at `time` (seconds): held at the first keyframe before it and at the last
// after it. A rotation comes back as a unit quaternion. The sampler must have no problem.
std::vector<float> sampleAt(const AnimationSampler& sampler, AnimatedPath path, double time);
// The same into `out` (sampler.components floats) without allocating: the per-frame path. The
// sampler must have no problem (samplerProblem is not asked again here).
void sampleInto(const AnimationSampler& sampler, AnimatedPath path, double time,
                std::span<float> out);

// Spherical linear interpolation of unit quaternions (x, y, z, w) along the shorter arc.
void slerp(std::span<const float, 4> a, std::span<const float, 4> b, float t,
           std::span<float, 4> out);

} // namespace penumbra::scene
