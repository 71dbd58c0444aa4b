#include "report/truth_notes.h"

#include "report/html_report.h"

#include "penumbra/error.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace penumbra {

namespace {

std::string lightsWord(size_t n) {
    return n == 1 ? "1 light" : fmt::format("{} lights", n);
}

} // namespace

std::vector<uint32_t> truthRays(uint32_t samples, const std::vector<bool>& sized) {
    std::vector<uint32_t> rays;
    for (const bool s : sized)
        rays.push_back(s ? samples : 1u);
    return rays;
}

std::string truthRaysText(uint32_t samples, const std::vector<bool>& sized) {
    if (sized.empty())
        return "no shadow-casting light";
    const auto withSize = static_cast<size_t>(std::count(sized.begin(), sized.end(), true));
    if (withSize == 0)
        return sized.size() == 1
                   ? "1 exact ray per pixel (the light has no size: a hard truth)"
                   : "1 exact ray per pixel and light (no light has a size: a hard truth)";
    const std::string per = fmt::format("{} ray{} per pixel", samples, samples == 1 ? "" : "s");
    if (withSize == sized.size())
        return per + " and light";
    return fmt::format("{} towards the {} with a size, 1 exact ray towards the {} without", per,
                       lightsWord(withSize), lightsWord(sized.size() - withSize));
}

std::vector<bool> lightsSized(const ReportData& data) {
    PENUMBRA_CHECK(data.lightSized.empty() || data.lightSized.size() == data.lights.size(),
                   "a report's light sizes are one per light");
    return data.lightSized.empty() ? std::vector<bool>(data.lights.size(), true) : data.lightSized;
}

std::string hardTruthNote(const ReportData& data) {
    const std::vector<bool> sized = lightsSized(data);
    std::vector<std::string> hard, soft;
    for (size_t l = 0; l < sized.size(); ++l)
        if (!sized[l]) // "sun: directional, ..." -> "sun"
            hard.push_back(data.lights[l].substr(0, data.lights[l].find(':')));
    for (const ReportRow& row : data.rows)
        if (row.skipped.empty() && row.modelsLightSize)
            soft.push_back(row.name);
    if (hard.empty() || soft.empty())
        return "";
    return fmt::format("The truth is hard towards {} (no size: one exact ray), so the penumbrae "
                       "of {} count as error there. Give the light a size (--light-radius, "
                       "--light-angle) to rank them on what they model.",
                       fmt::join(hard, ", "), fmt::join(soft, ", "));
}

} // namespace penumbra
