#pragma once
// Standard padded base64 to bytes, for tests that read what the code encoded (a report's inlined
// PNGs, a glTF builder's data URIs); a character outside the alphabet or a length that is not a
// multiple of 4 fails the test.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace penumbra::test {

inline std::vector<uint8_t> decodeBase64(const std::string& text) {
    const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::vector<uint8_t> out;
    uint32_t bits = 0;
    int count = 0;
    for (char c : text) {
        if (c == '=')
            break;
        const size_t value = alphabet.find(c);
        EXPECT_NE(value, std::string::npos) << c;
        bits = (bits << 6) | uint32_t(value);
        count += 6;
        if (count >= 8) {
            count -= 8;
            out.push_back(uint8_t(bits >> count));
        }
    }
    EXPECT_EQ(text.size() % 4, 0u);
    return out;
}

} // namespace penumbra::test
