#pragma once
// Float images compared bit for bit: a PFM and an OpenEXR file of the same data, NaN payloads and
// -0 included, must hold the same pixels.
#include "core/image_io.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

namespace penumbra::test {

inline void expectSameImage(const FloatImage& expected, const FloatImage& actual,
                            const std::string& what) {
    ASSERT_EQ(expected.width, actual.width) << what;
    ASSERT_EQ(expected.height, actual.height) << what;
    ASSERT_EQ(expected.channels, actual.channels) << what;
    ASSERT_EQ(expected.pixels.size(), actual.pixels.size()) << what;
    EXPECT_EQ(0, std::memcmp(expected.pixels.data(), actual.pixels.data(),
                             expected.pixels.size() * sizeof(float)))
        << what << ": the pixels differ";
}

} // namespace penumbra::test
