#include "scene/animation.h"

#include "penumbra/error.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace penumbra::scene {
namespace {

// Each path's name in glTF and its components a keyframe (0: any; weights: one per morph target).
struct PathInfo {
    AnimatedPath path;
    const char* name;
    uint32_t components;
};
constexpr PathInfo kPaths[] = {{AnimatedPath::Translation, "translation", 3},
                               {AnimatedPath::Rotation, "rotation", 4},
                               {AnimatedPath::Scale, "scale", 3},
                               {AnimatedPath::Weights, "weights", 0}};

const PathInfo& infoOf(AnimatedPath path) {
    return kPaths[static_cast<size_t>(path)];
}
static_assert(kPaths[static_cast<size_t>(AnimatedPath::Weights)].path == AnimatedPath::Weights);

// A rotation normalized in place; a quaternion of no length (a spline may pass through one) is
// none.
template <typename T>
void normalizeRotation(std::span<T, 4> q) {
    double length = 0.0;
    for (const T c : q)
        length += double(c) * double(c);
    length = std::sqrt(length);
    if (length > 0.0)
        for (T& c : q)
            c = static_cast<T>(c / length);
    else
        q[0] = q[1] = q[2] = T(0), q[3] = T(1);
}

} // namespace

std::string samplerProblem(const AnimationSampler& s, AnimatedPath path) {
    if (s.times.empty())
        return "no keyframes";
    const uint32_t wanted = infoOf(path).components;
    if (s.components == 0)
        return "no components";
    if (wanted != 0 && s.components != wanted)
        return fmt::format("a {} has {} components, not {}", infoOf(path).name, wanted,
                           s.components);
    for (size_t k = 0; k < s.times.size(); ++k) {
        if (!std::isfinite(s.times[k]) || s.times[k] < 0.0f)
            return fmt::format("keyframe {}'s time {} is not a finite number of seconds from 0", k,
                               s.times[k]);
        if (k > 0 && !(s.times[k] > s.times[k - 1]))
            return fmt::format("keyframe {}'s time {} is not after keyframe {}'s {}", k, s.times[k],
                               k - 1, s.times[k - 1]);
    }
    const bool cubic = s.interpolation == Interpolation::CubicSpline;
    if (cubic && s.times.size() < 2)
        return "CUBICSPLINE with one keyframe (it needs two)";
    const size_t expected = s.times.size() * s.components * (cubic ? 3 : 1);
    if (s.values.size() != expected)
        return fmt::format("{} values for {} keyframes of {} components{} ({} expected)",
                           s.values.size(), s.times.size(), s.components,
                           cubic ? " with in- and out-tangents" : "", expected);
    const auto bad =
        std::find_if(s.values.begin(), s.values.end(), [](float v) { return !std::isfinite(v); });
    if (bad != s.values.end())
        return fmt::format("value {} is not a finite number", bad - s.values.begin());
    return "";
}

void slerp(std::span<const float, 4> a, std::span<const float, 4> b, float t,
           std::span<float, 4> out) {
    double d = 0.0;
    for (size_t i = 0; i < 4; ++i)
        d += double(a[i]) * double(b[i]);
    const double sign = d < 0.0 ? -1.0 : 1.0; // q and -q are one rotation: take the shorter arc
    d = std::min(std::abs(d), 1.0);
    double wa = 1.0 - t, wb = t;
    // Far from parallel the arc's weights; nearly parallel, where sin(angle) loses its digits,
    // the chord's (normalized below, as the arc's are not quite).
    if (d < 0.9995) {
        const double angle = std::acos(d);
        wa = std::sin((1.0 - t) * angle) / std::sin(angle);
        wb = std::sin(t * angle) / std::sin(angle);
    }
    std::array<double, 4> q{};
    for (size_t i = 0; i < 4; ++i)
        q[i] = wa * a[i] + sign * wb * b[i];
    normalizeRotation(std::span<double, 4>(q));
    for (size_t i = 0; i < 4; ++i)
        out[i] = static_cast<float>(q[i]);
}

const char* animatedPathName(AnimatedPath path) {
    return infoOf(path).name;
}

bool animatedPathFromName(std::string_view name, AnimatedPath& path) {
    for (const PathInfo& info : kPaths)
        if (name == info.name) {
            path = info.path;
            return true;
        }
    return false;
}

std::vector<float> sampleAt(const AnimationSampler& s, AnimatedPath path, double time) {
    PENUMBRA_CHECK(samplerProblem(s, path).empty(), "sampleAt: " + samplerProblem(s, path));
    std::vector<float> out(s.components);
    sampleInto(s, path, time, out);
    return out;
}

void sampleInto(const AnimationSampler& s, AnimatedPath path, double time, std::span<float> out) {
    const size_t n = s.times.size(), c = s.components;
    PENUMBRA_CHECK(out.size() == c && n > 0, "sampleInto: the output holds one keyframe's values");
    const bool cubic = s.interpolation == Interpolation::CubicSpline;
    const size_t groups = cubic ? 3 : 1;
    const auto value = [&](size_t k) {
        return s.values.data() + (k * groups + (cubic ? 1 : 0)) * c;
    };
    const auto held = [&](size_t k) { std::copy(value(k), value(k) + c, out.begin()); };
    // Before the first keyframe and after the last, the nearest one holds (Appendix C).
    if (n == 1 || !(time > s.times.front())) {
        held(0);
    } else if (time >= s.times.back()) {
        held(n - 1);
    } else {
        const size_t k =
            static_cast<size_t>(std::upper_bound(s.times.begin(), s.times.end(), time) -
                                s.times.begin()) -
            1; // times[k] <= time < times[k + 1]
        const double t0 = s.times[k], t1 = s.times[k + 1], span = t1 - t0;
        const double u = (time - t0) / span;
        if (s.interpolation == Interpolation::Step) {
            held(k);
        } else if (!cubic) {
            if (path == AnimatedPath::Rotation) {
                slerp(std::span<const float, 4>(value(k), 4),
                      std::span<const float, 4>(value(k + 1), 4), static_cast<float>(u),
                      out.first<4>());
            } else {
                for (size_t i = 0; i < c; ++i)
                    out[i] = static_cast<float>((1.0 - u) * value(k)[i] + u * value(k + 1)[i]);
            }
        } else {
            // The Hermite spline of Appendix C: the keyframes' values and their out- and
            // in-tangents, scaled by the span between them.
            const float* outTangent = s.values.data() + (k * 3 + 2) * c;
            const float* inTangent = s.values.data() + ((k + 1) * 3) * c;
            const double u2 = u * u, u3 = u2 * u;
            const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u;
            const double h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
            for (size_t i = 0; i < c; ++i)
                out[i] = static_cast<float>(h00 * value(k)[i] + h10 * span * outTangent[i] +
                                            h01 * value(k + 1)[i] + h11 * span * inTangent[i]);
        }
    }
    if (path == AnimatedPath::Rotation)
        normalizeRotation(out.first<4>());
}

} // namespace penumbra::scene
