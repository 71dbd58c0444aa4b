#pragma once
// The loader tests' one check of a refusal: an InputError naming the file, whose message
// contains `expected` (the JSON path and what is wrong).
#include "penumbra/error.h"
#include "penumbra/scene.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace penumbra::test {

inline void expectRefused(const std::filesystem::path& file, const std::string& expected,
                          const SceneLoadOptions& options = {}) {
    try {
        loadScene(file.string(), options);
        ADD_FAILURE() << "accepted " << file << " (expected: " << expected << ")";
    } catch (const InputError& e) {
        EXPECT_EQ(e.subject(), file.string());
        EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
}

} // namespace penumbra::test
