#pragma once
// The `sdf` technique's debug picture: one slice of its distance field as `render` writes it
// (field_slice.png), so a user sees what the tracer sees: outside in warm tones, inside closed
// surfaces in cool ones, darker towards the surface, a contour every four voxels and the surface
// itself (the zero crossing) in white.
#include "penumbra/renderer.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

struct FieldSlice {
    int axis = 1;          // 0 x, 1 y, 2 z: the slice is across this axis
    bool centred = true;   // at the middle of the field's box, else at `position`
    float position = 0.0f; // world coordinate along the axis
};

// "x", "y", "z" or "AXIS:POSITION" (e.g. "y:0.25"); throws InputError("--field-slice", ...).
FieldSlice parseFieldSlice(std::string_view text);

// Where the slice lies along its axis in a field of that box; throws InputError("--field-slice",
// ...) outside it.
float slicePosition(const FieldSlice& slice, const glm::vec3& origin, float voxel,
                    const glm::uvec3& voxels);

// RGB rows top to bottom, each voxel a square of pixels (the longer side at least 512). Across y: x
// to the right, z downwards; across x: z right, y up; across z: x right, y up. Throws
// InputError("--field-slice", ...) when `position` lies outside the field's box.
struct SliceImage {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgb;
};
SliceImage fieldSlice(const std::vector<float>& voxels, const DistanceFieldInfo& info,
                      const FieldSlice& slice);

} // namespace penumbra
