#pragma once
// smrt's screen passes (TechniqueModule::screenPasses): checkerboard tracing's fill
// (shaders/visibility_fill.comp; smrt.checkerboard) and the edge-aware filter of its noise
// (shaders/visibility_filter.comp, rows then columns; smrt.filter), with their settings.
#include "shadows/technique.h"

#include <vector>

namespace penumbra::shadows {

VisibilityFilter smrtVisibilityFilter(const ParameterValues& p);
Checkerboard smrtCheckerboard(const ParameterValues& p);
std::vector<ScreenPassDecl> smrtScreenPasses(const ParameterValues& p);

} // namespace penumbra::shadows
