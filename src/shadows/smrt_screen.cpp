#include "shadows/smrt_screen.h"

#include "bindings.h"

#include <bit>

namespace penumbra::shadows {
namespace {

// The filter's constants for a light of this type along one axis (0: rows, 1: columns).
template <uint32_t axis>
std::vector<SpecConstant> filterConstants(const ParameterValues& p, uint32_t lightType, bool) {
    const VisibilityFilter filter = smrtVisibilityFilter(p);
    return {{SPEC_FILTER_RADIUS, filter.radiusFor(lightType)},
            {SPEC_FILTER_TOLERANCE, std::bit_cast<uint32_t>(filter.toleranceFor(lightType))},
            {SPEC_FILTER_AXIS, axis},
            {SPEC_FILTER_WIDE, filter.wideFor(lightType)}};
}

bool filters(const ParameterValues& p, uint32_t lightType) {
    return smrtVisibilityFilter(p).radiusFor(lightType) > 0;
}

// The filter's pass along one axis: rows read the visibility layer into the scratch, columns
// read the scratch back into the layer.
template <uint32_t axis>
ScreenPassDecl filterPass() {
    return {.name = "filter",
            .shader = "visibility_filter.comp",
            .visibility = axis == 0 ? ScreenAccess::ReadWrite : ScreenAccess::Write,
            .results = kScreenScratch,
            .resultsAccess = axis == 0 ? ScreenAccess::Write : ScreenAccess::Read,
            .constants = filterConstants<axis>,
            .runsFor = filters};
}

std::vector<SpecConstant> fillConstants(const ParameterValues& p, uint32_t lightType, bool sized) {
    return {
        {SPEC_FILL_RANGE, std::bit_cast<uint32_t>(smrtCheckerboard(p).rangeFor(lightType, sized))}};
}

} // namespace

VisibilityFilter smrtVisibilityFilter(const ParameterValues& p) {
    return VisibilityFilter{.radius = static_cast<uint32_t>(p.number("smrt.filter")),
                            .tolerance = static_cast<float>(p.number("smrt.filterTolerance")),
                            .cubeRadius = static_cast<uint32_t>(p.number("smrt.cubeFilter")),
                            .cubeTolerance =
                                static_cast<float>(p.number("smrt.cubeFilterTolerance")),
                            .wide = static_cast<uint32_t>(p.number("smrt.filterWide")),
                            .cubeWide = static_cast<uint32_t>(p.number("smrt.cubeFilterWide"))};
}

Checkerboard smrtCheckerboard(const ParameterValues& p) {
    return Checkerboard{.runs = p.number("smrt.checkerboard") != 0.0,
                        .range = static_cast<float>(p.number("smrt.fillRange")),
                        .cubeRange = static_cast<float>(p.number("smrt.cubeFillRange"))};
}

std::vector<ScreenPassDecl> smrtScreenPasses(const ParameterValues& p) {
    std::vector<ScreenPassDecl> passes;
    // Its fill is part of its tracing: timed as "visibility", with the even pixels' dispatch.
    if (smrtCheckerboard(p).runs)
        passes.push_back({.name = "visibility",
                          .shader = "visibility_fill.comp",
                          .visibility = ScreenAccess::ReadWrite,
                          .resultsAccess = ScreenAccess::Write,
                          .constants = fillConstants,
                          .fillsCheckerboard = true,
                          .parameter = "smrt.checkerboard"});
    // The filter: rows from the visibility layer into the scratch, columns back.
    if (smrtVisibilityFilter(p).runs()) {
        passes.push_back(filterPass<0>());
        passes.push_back(filterPass<1>());
    }
    return passes;
}

} // namespace penumbra::shadows
