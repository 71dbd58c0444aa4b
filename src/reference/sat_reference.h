#pragma once
// CPU references of the summed-area members (shaders/include/sat_scan.glsl, shadow_sat.glsl):
// the table as the two scan passes leave it (wrapping integer sums), then the queries.
// Called by techniqueReference (filter_reference.h), whose contract they share.
#include "reference/filter_reference.h"

namespace penumbra {

glm::vec4 savsmReference(const ShadowMapView& map, const FilterProbe& probe,
                         const gpu::FrameData& f, const gpu::ShadowViewData& view);
glm::vec4 vssmReference(const ShadowMapView& map, const FilterProbe& probe, const gpu::FrameData& f,
                        const gpu::ShadowViewData& view);
glm::vec4 msmSoftReference(const ShadowMapView& map, const FilterProbe& probe,
                           const gpu::FrameData& f, const gpu::ShadowViewData& view);

} // namespace penumbra
