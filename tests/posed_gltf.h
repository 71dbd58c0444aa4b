#pragma once
// What the tests of posed glTF scenes share (test_gltf_posed.cpp, test_gltf_skinned.cpp):
// float accessors, keyframe times, loading at a time, and refusals checked at rest and posed.
#include "gltf_builder.h"
#include "penumbra/error.h"
#include "penumbra/scene.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace penumbra::test {

// A float accessor of `per` components an element (`type`: "SCALAR", "VEC3", ...).
inline int floatAccessor(GltfBuilder& b, const std::vector<float>& v, const char* type,
                         size_t per) {
    return b.accessor(b.view(v), 5126, v.size() / per, type);
}

// Keyframe times with the min and max the specification asks of an input accessor.
inline int keyframeTimes(GltfBuilder& b, const std::vector<float>& t) {
    const int a = floatAccessor(b, t, "SCALAR", 1);
    b.j["accessors"][a]["min"] = {t.front()};
    b.j["accessors"][a]["max"] = {t.back()};
    return a;
}

inline Scene loadAt(const std::filesystem::path& f, std::optional<double> time,
                    const std::string& animation = "",
                    std::vector<std::string>* warnings = nullptr) {
    return loadScene(f.string(), {.warnings = warnings, .time = time, .animation = animation});
}

// `run` throws an InputError blaming `subject` with `expected` in its message.
inline void expectInputError(const std::function<void()>& run, const std::string& subject,
                             const std::string& expected) {
    try {
        run();
        ADD_FAILURE() << "accepted (expected: " << expected << ")";
    } catch (const InputError& e) {
        EXPECT_EQ(e.subject(), subject);
        EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
}

// Refused whether or not a time is asked for: a malformed asset is malformed at rest too.
inline void expectRefusedAtRestAndPosed(const std::filesystem::path& f, const std::string& expected,
                                        const std::string& animation = "") {
    expectInputError([&] { loadAt(f, std::nullopt); }, f.string(), expected);
    expectInputError([&] { loadAt(f, 0.5, animation); }, f.string(), expected);
}

// One row of a table of refused assets: how `Rig` is broken and the refusal after "<file>: ".
template <typename Rig>
struct Refusal {
    const char* name;
    std::function<void(Rig&)> change;
    const char* expected;
};

} // namespace penumbra::test
