#pragma once
// GPU times per pass over many frames (a render's frames, `render --fps`'s poses): each pass gets
// one value a frame, 0 in a frame it did not run in (the `skin` pass runs only after a pose,
// sdf's `sdf_build` only when the field is built), so that the lists line up frame by frame and
// a pass's median counts the frames it skipped.
#include "penumbra/renderer.h"

#include <vector>

namespace penumbra {

// Appends frame number `index` (from 0; each frame appended once, in order): `frame`'s passes
// (each one value, PassTime::medianMs) to `passes`, a pass new to the list with 0 for the frames
// before, and 0 to every pass of the list that `frame` lacks.
void appendFrameTimes(std::vector<PassTime>& passes, const std::vector<PassTime>& frame,
                      size_t index);
// Each pass's median over its frames.
void setMedians(std::vector<PassTime>& passes);

} // namespace penumbra
