#pragma once
// The host's placement of skinned vertices for a range of Scene::skinning's (a loader places each
// primitive's as it reads it); penumbra/scene.h's placeSkinnedVertices places them all.
#include "penumbra/scene.h"

#include <cstddef>

namespace penumbra {

// Places skinned vertices [first, end) of scene.skinning, as placeSkinnedVertices does, with no
// check (the loader builds them right).
void placeSkinnedVertices(Scene& scene, size_t first, size_t end);

} // namespace penumbra
