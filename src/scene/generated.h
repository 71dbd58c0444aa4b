#pragma once
// Generated scene families (docs/scenes.md, "Generated scenes"): `builtin:gen/FAMILY?seed=N`,
// with `&scale=S` to make the whole scene S times larger (huge and tiny worlds). Each seed
// varies the family's counts, sizes and placements, its light (sun, spot or point; sizes from
// zero up) and its camera. The same spec gives the same scene on every run and platform: the
// numbers come from splitmix64 through integer arithmetic, one draw per statement.
#include "penumbra/scene.h"

#include <cstdint>
#include <string_view>
#include <vector>

namespace penumbra {

struct GeneratedSpec {
    std::string family;
    uint64_t seed = 1;
    float scale = 1.0f;
};

inline constexpr float kLeastGeneratedScale = 1e-3f, kMostGeneratedScale = 1e4f;

// The families by name, in the order the docs list them.
std::vector<std::string_view> generatedFamilies();
// "FAMILY?seed=N&scale=S" (the part after "builtin:gen/"): InputError naming `spec` on an unknown
// family or key, a seed that is not a whole number below 2^63, or a scale outside
// [kLeastGeneratedScale, kMostGeneratedScale].
GeneratedSpec parseGeneratedSpec(std::string_view spec);
Scene generatedScene(std::string_view spec);
Scene generatedScene(const GeneratedSpec& spec);

// The generator's numbers: splitmix64 (Steele, Lea and Flood 2014), the same on every platform.
class GenRandom {
public:
    explicit GenRandom(uint64_t seed) : mState(seed) {}
    uint64_t next() {
        uint64_t z = (mState += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    float unit() { return static_cast<float>(next() >> 40) * 0x1p-24f; } // [0, 1)
    float uniform(float lo, float hi) { return lo + (hi - lo) * unit(); }
    // Uniform in log space: sizes that span decades.
    float logUniform(float lo, float hi);
    int integer(int lo, int hi) { // inclusive
        return lo + static_cast<int>(next() % static_cast<uint64_t>(hi - lo + 1));
    }
    bool chance(float p) { return unit() < p; }

private:
    uint64_t mState;
};

} // namespace penumbra
