#include "report/field_slice.h"

#include "penumbra/error.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>

namespace penumbra {

FieldSlice parseFieldSlice(std::string_view text) {
    FieldSlice s;
    const std::string_view axis = text.substr(0, text.find(':'));
    if (axis != "x" && axis != "y" && axis != "z")
        throw InputError("--field-slice",
                         fmt::format("'{}': expected x, y or z, optionally :POSITION", text));
    s.axis = axis[0] - 'x';
    if (axis.size() < text.size()) {
        const std::string_view number = text.substr(axis.size() + 1);
        const auto [end, error] =
            std::from_chars(number.data(), number.data() + number.size(), s.position);
        if (error != std::errc() || end != number.data() + number.size() ||
            !std::isfinite(s.position))
            throw InputError("--field-slice",
                             fmt::format("'{}': the position must be a number", text));
        s.centred = false;
    }
    return s;
}

float slicePosition(const FieldSlice& slice, const glm::vec3& origin, float voxel,
                    const glm::uvec3& voxels) {
    const int a = slice.axis;
    const float low = origin[a], high = low + voxel * float(voxels[a]);
    const float position = slice.centred ? 0.5f * (low + high) : slice.position;
    if (!(position >= low && position <= high))
        throw InputError("--field-slice",
                         fmt::format("{} is outside the field's box along {} ({} .. {})", position,
                                     char('x' + a), low, high));
    return position;
}

SliceImage fieldSlice(const std::vector<float>& voxels, const DistanceFieldInfo& info,
                      const FieldSlice& slice) {
    const int a = slice.axis, u = a == 0 ? 2 : 0, v = a == 1 ? 2 : 1;
    const float position = slicePosition(slice, info.origin, info.voxelSize, info.voxels);
    const float low = info.origin[a];
    // Between the two layers of voxel centres around the position, linearly.
    const float layer =
        std::clamp((position - low) / info.voxelSize - 0.5f, 0.0f, float(info.voxels[a] - 1));
    const auto l0 = static_cast<uint32_t>(layer);
    const uint32_t l1 = std::min(l0 + 1, info.voxels[a] - 1);
    const float f = layer - float(l0);
    SliceImage image{.width = info.voxels[u], .height = info.voxels[v]};
    image.rgb.resize(size_t{image.width} * image.height * 3);
    auto at = [&](uint32_t i, uint32_t j, uint32_t k) {
        glm::uvec3 c;
        c[a] = k, c[u] = i, c[v] = j;
        return voxels[(size_t{c.z} * info.voxels.y + c.y) * info.voxels.x + c.x];
    };
    const float band = 4.0f * info.voxelSize; // contour spacing
    for (uint32_t j = 0; j < image.height; ++j)
        for (uint32_t i = 0; i < image.width; ++i) {
            const float d = (1.0f - f) * at(i, j, l0) + f * at(i, j, l1);
            const glm::vec3 base =
                d > 0.0f ? glm::vec3(0.95f, 0.65f, 0.35f) : glm::vec3(0.45f, 0.7f, 0.95f);
            glm::vec3 c = base * (1.0f - 0.75f * std::exp(-std::abs(d) / (3.0f * band)));
            c *= 0.85f + 0.15f * std::cos(2.0f * 3.14159265f * d / band);
            const float surface = std::clamp(std::abs(d) / (0.5f * info.voxelSize), 0.0f, 1.0f);
            c = glm::mix(glm::vec3(1.0f), c, surface);
            // Across y, z runs down the image; across x and z, y runs up it.
            const uint32_t row = a == 1 ? j : image.height - 1 - j;
            uint8_t* out = &image.rgb[(size_t{row} * image.width + i) * 3];
            for (int k = 0; k < 3; ++k)
                out[k] = static_cast<uint8_t>(std::lround(255.0f * std::clamp(c[k], 0.0f, 1.0f)));
        }
    // Each voxel a square of pixels, the longer side at least 512 pixels.
    const uint32_t longer = std::max(image.width, image.height);
    const uint32_t scale = (512u + longer - 1) / longer;
    if (scale > 1) {
        SliceImage big{.width = image.width * scale, .height = image.height * scale};
        big.rgb.resize(size_t{big.width} * big.height * 3);
        for (uint32_t y = 0; y < big.height; ++y)
            for (uint32_t x = 0; x < big.width; ++x)
                for (int k = 0; k < 3; ++k)
                    big.rgb[(size_t{y} * big.width + x) * 3 + k] =
                        image.rgb[(size_t{y / scale} * image.width + x / scale) * 3 + k];
        image = std::move(big);
    }
    return image;
}

} // namespace penumbra
