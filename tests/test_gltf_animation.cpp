// glTF animation samplers (src/scene/animation.cpp) against the specification's Appendix C,
// evaluated here in closed form: held values outside the keyframes, STEP, LINEAR, the shorter
// arc of a rotation's slerp, and CUBICSPLINE's Hermite spline, which reproduces any cubic whose
// tangents it is given; and the samplers the specification forbids, each refused with its reason.
#include "scene/animation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace penumbra::scene;

namespace {

// The quaternion (x, y, z, w) of `angle` radians about the unit axis (ax, ay, az).
std::vector<float> aboutAxis(double ax, double ay, double az, double angle) {
    const double s = std::sin(angle / 2);
    return {float(ax * s), float(ay * s), float(az * s), float(std::cos(angle / 2))};
}

void expectNear(const std::vector<float>& got, const std::vector<float>& want, double tolerance,
                const std::string& what) {
    ASSERT_EQ(got.size(), want.size()) << what;
    for (size_t i = 0; i < got.size(); ++i)
        EXPECT_NEAR(got[i], want[i], tolerance) << what << ", component " << i;
}

// A rotation or its negation (one rotation), component by component.
void expectSameRotation(const std::vector<float>& got, const std::vector<float>& want,
                        const std::string& what) {
    ASSERT_EQ(got.size(), 4u) << what;
    double d = 0;
    for (size_t i = 0; i < 4; ++i)
        d += double(got[i]) * want[i];
    for (size_t i = 0; i < 4; ++i)
        EXPECT_NEAR(d < 0 ? -got[i] : got[i], want[i], 1e-6) << what << ", component " << i;
}

} // namespace

TEST(GltfAnimation, LinearAndStepBetweenKeyframesAndHeldOutsideThem) {
    const AnimationSampler move{.times = {1.0f, 3.0f, 4.0f},
                                .values = {0, 0, 0, 2, -4, 6, 2, -4, 10},
                                .components = 3,
                                .interpolation = Interpolation::Linear};
    ASSERT_EQ(samplerProblem(move, AnimatedPath::Translation), "");
    const auto at = [&](double t) { return sampleAt(move, AnimatedPath::Translation, t); };
    expectNear(at(0.0), {0, 0, 0}, 0, "before the first keyframe");
    expectNear(at(1.0), {0, 0, 0}, 0, "at the first");
    expectNear(at(1.5), {0.5f, -1, 1.5f}, 1e-6, "a quarter of the first span");
    expectNear(at(3.0), {2, -4, 6}, 1e-6, "at the second");
    expectNear(at(3.75), {2, -4, 9}, 1e-6, "three quarters of the second span");
    expectNear(at(4.0), {2, -4, 10}, 0, "at the last");
    expectNear(at(99.0), {2, -4, 10}, 0, "after the last");
    AnimationSampler step = move;
    step.interpolation = Interpolation::Step;
    const auto held = [&](double t) { return sampleAt(step, AnimatedPath::Scale, t); };
    expectNear(held(2.99), {0, 0, 0}, 0, "STEP holds the keyframe before");
    expectNear(held(3.0), {2, -4, 6}, 0, "STEP at a keyframe takes it");
    expectNear(held(3.5), {2, -4, 6}, 0, "STEP in the second span");
    expectNear(held(5.0), {2, -4, 10}, 0, "STEP after the last");
    const AnimationSampler one{.times = {2.0f}, .values = {7}, .components = 1};
    for (double t : {0.0, 2.0, 3.0})
        expectNear(sampleAt(one, AnimatedPath::Weights, t), {7}, 0, "a single keyframe");
}

// Slerp keeps a constant angular speed about the axis, takes the shorter arc when the second
// quaternion is stored negated, and returns unit quaternions.
TEST(GltfAnimation, RotationsTurnAtAConstantRateAlongTheShorterArc) {
    const double pi = std::numbers::pi;
    std::vector<float> values = aboutAxis(0, 0, 1, 0);
    const std::vector<float> end = aboutAxis(0, 0, 1, 2 * pi / 3); // 120 degrees about z
    values.insert(values.end(), end.begin(), end.end());
    AnimationSampler turn{.times = {0.0f, 2.0f},
                          .values = values,
                          .components = 4,
                          .interpolation = Interpolation::Linear};
    ASSERT_EQ(samplerProblem(turn, AnimatedPath::Rotation), "");
    for (double t : {0.25, 0.5, 1.0, 1.7})
        expectSameRotation(sampleAt(turn, AnimatedPath::Rotation, t),
                           aboutAxis(0, 0, 1, 2 * pi / 3 * t / 2), "t = " + std::to_string(t));
    // The same end stored as -q: the rotation at half time is still 60 degrees, not 120 the
    // long way round (-120 is 240 degrees: halfway is then 120 the other way).
    for (size_t i = 4; i < 8; ++i)
        turn.values[i] = -turn.values[i];
    expectSameRotation(sampleAt(turn, AnimatedPath::Rotation, 1.0), aboutAxis(0, 0, 1, pi / 3),
                       "negated end");
    // Nearly the same rotation at both ends (where the arc's weights lose their digits).
    AnimationSampler tiny = turn;
    const std::vector<float> close = aboutAxis(1, 0, 0, 1e-4);
    std::copy(close.begin(), close.end(), tiny.values.begin() + 4);
    expectSameRotation(sampleAt(tiny, AnimatedPath::Rotation, 1.0), aboutAxis(1, 0, 0, 0.5e-4),
                       "nearly parallel");
    // A keyframe stored a little off unit length comes back unit.
    AnimationSampler loose = turn;
    for (float& v : loose.values)
        v *= 1.01f;
    const std::vector<float> q = sampleAt(loose, AnimatedPath::Rotation, 0.0);
    EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0, 1e-6);
    // A keyframe of no length (a spline may pass through one) is no turn, not NaN.
    AnimationSampler none = turn;
    none.interpolation = Interpolation::Step;
    std::fill(none.values.begin(), none.values.begin() + 4, 0.0f);
    expectNear(sampleAt(none, AnimatedPath::Rotation, 0.5), {0, 0, 0, 1}, 0, "zero quaternion");
}

// The Hermite spline through each span's end values with tangents scaled by the span: given the
// values and derivatives of a cubic polynomial at the keyframes, it is that polynomial.
TEST(GltfAnimation, CubicSplineReproducesACubicFromItsValuesAndDerivatives) {
    const auto f = [](double t) { return 0.5 * t * t * t - 2 * t * t + t + 3; };
    const auto df = [](double t) { return 1.5 * t * t - 4 * t + 1; };
    const std::vector<float> times{0.5f, 1.25f, 3.0f};
    AnimationSampler spline{
        .times = times, .components = 2, .interpolation = Interpolation::CubicSpline};
    for (float t : times) // in-tangent, value, out-tangent; the second component is -f
        spline.values.insert(spline.values.end(), {float(df(t)), float(-df(t)), float(f(t)),
                                                   float(-f(t)), float(df(t)), float(-df(t))});
    ASSERT_EQ(samplerProblem(spline, AnimatedPath::Weights), "");
    for (double t = 0.5; t <= 3.0; t += 0.0625) {
        const std::vector<float> v = sampleAt(spline, AnimatedPath::Weights, t);
        EXPECT_NEAR(v[0], f(t), 2e-5) << "t = " << t;
        EXPECT_NEAR(v[1], -f(t), 2e-5) << "t = " << t;
    }
    expectNear(sampleAt(spline, AnimatedPath::Weights, 0.0), {float(f(0.5)), float(-f(0.5))}, 0,
               "held before");
    expectNear(sampleAt(spline, AnimatedPath::Weights, 9.0), {float(f(3.0)), float(-f(3.0))}, 0,
               "held after");
    // In- and out-tangents are read from their own places: a kink at the middle keyframe (its
    // in-tangent differs from its out-tangent) shapes only the span on its side.
    AnimationSampler kinked = spline;
    kinked.values[6] = 40.0f; // the middle keyframe's in-tangent, first component
    EXPECT_NEAR(sampleAt(kinked, AnimatedPath::Weights, 2.0)[0], f(2.0), 2e-5)
        << "the span after the kink";
    EXPECT_GT(std::abs(sampleAt(kinked, AnimatedPath::Weights, 1.0)[0] - f(1.0)), 0.1)
        << "the span before it";
    // A spline of rotations is normalized.
    AnimationSampler spun{
        .times = {0.0f, 1.0f},
        .values = {0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0},
        .components = 4,
        .interpolation = Interpolation::CubicSpline};
    ASSERT_EQ(samplerProblem(spun, AnimatedPath::Rotation), "");
    const std::vector<float> half = sampleAt(spun, AnimatedPath::Rotation, 0.5);
    expectSameRotation(half, aboutAxis(0, 0, 1, std::numbers::pi / 2), "halfway from 0 to 180");
}

TEST(GltfAnimation, SamplersTheSpecificationForbidsAreRefusedWithTheirReason) {
    const AnimationSampler good{
        .times = {0.0f, 1.0f}, .values = {0, 0, 0, 1, 1, 1}, .components = 3};
    ASSERT_EQ(samplerProblem(good, AnimatedPath::Translation), "");
    const auto problem = [&](auto edit, AnimatedPath path = AnimatedPath::Translation) {
        AnimationSampler s = good;
        edit(s);
        return samplerProblem(s, path);
    };
    EXPECT_EQ(problem([](AnimationSampler& s) { s.times.clear(), s.values.clear(); }),
              "no keyframes");
    EXPECT_EQ(problem([](AnimationSampler& s) {
                  s.times = {1.0f, 1.0f};
              }),
              "keyframe 1's time 1 is not after keyframe 0's 1");
    EXPECT_EQ(problem([](AnimationSampler& s) {
                  s.times = {1.0f, 0.5f};
              }),
              "keyframe 1's time 0.5 is not after keyframe 0's 1");
    EXPECT_EQ(problem([](AnimationSampler& s) {
                  s.times = {-0.5f, 1.0f};
              }),
              "keyframe 0's time -0.5 is not a finite number of seconds from 0");
    EXPECT_EQ(problem([](AnimationSampler& s) { s.times[1] = std::nanf(""); }),
              "keyframe 1's time nan is not a finite number of seconds from 0");
    EXPECT_EQ(problem([](AnimationSampler& s) { s.values.pop_back(); }),
              "5 values for 2 keyframes of 3 components (6 expected)");
    EXPECT_EQ(problem([](AnimationSampler& s) { s.interpolation = Interpolation::CubicSpline; }),
              "6 values for 2 keyframes of 3 components with in- and out-tangents (18 expected)");
    EXPECT_EQ(problem([](AnimationSampler& s) {
                  s.interpolation = Interpolation::CubicSpline;
                  s.times = {0.0f};
                  s.values.resize(9);
              }),
              "CUBICSPLINE with one keyframe (it needs two)");
    EXPECT_EQ(problem([](AnimationSampler& s) { s.values[4] = INFINITY; }),
              "value 4 is not a finite number");
    EXPECT_EQ(problem([](AnimationSampler&) {}, AnimatedPath::Rotation),
              "a rotation has 4 components, not 3");
    EXPECT_EQ(problem([](AnimationSampler& s) { s.components = 0; }, AnimatedPath::Weights),
              "no components");
    EXPECT_EQ(problem([](AnimationSampler& s) { s.components = 2, s.values.resize(4); },
                      AnimatedPath::Scale),
              "a scale has 3 components, not 2");
    EXPECT_EQ(problem([](AnimationSampler& s) { s.components = 2, s.values.resize(4); },
                      AnimatedPath::Weights),
              "");
}
