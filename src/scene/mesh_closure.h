#pragma once
// Whether a scene's surfaces are closed and consistently wound, as the techniques that take the
// inside of a model from its winding assume (`sdf` signs its field by it, `second-depth` keeps
// the far sides). Welded by position (to a millionth of the scene's size), every edge of a
// closed, consistent surface is shared by exactly two triangles that run it in opposite
// directions.
#include "penumbra/scene.h"

#include <cstdint>

namespace penumbra {

struct MeshClosure {
    uint64_t triangles = 0;
    uint64_t open = 0;     // triangles with an edge no other triangle shares
    uint64_t misWound = 0; // triangles with an edge another runs the same way (or 3+ share)
    bool closed() const { return open == 0 && misWound == 0; }
};
MeshClosure meshClosure(const Scene& scene);

} // namespace penumbra
