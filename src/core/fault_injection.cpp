#include "core/fault_injection.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <charconv>
#include <cstdlib>
#include <string_view>

namespace penumbra {
namespace {

constexpr std::array<std::string_view, 5> kSiteNames = {
    "allocation:", "creation:", "submit:", "embree:", "write:"};

// The call to fail at each site; 0: never.
std::array<long long, kSiteNames.size()> readPlan() {
    std::array<long long, kSiteNames.size()> plan{};
    const char* text = std::getenv("PENUMBRA_FAULT");
    std::string_view rest = text ? text : "";
    while (!rest.empty()) {
        const std::string_view item = rest.substr(0, rest.find(','));
        rest.remove_prefix(std::min(rest.size(), item.size() + 1));
        for (size_t site = 0; site < kSiteNames.size(); ++site)
            if (item.starts_with(kSiteNames[site]))
                std::from_chars(item.data() + kSiteNames[site].size(), item.data() + item.size(),
                                plan[site]);
    }
    return plan;
}

} // namespace

bool injectFault(FaultSite site) {
    static const auto plan = readPlan();
    static std::array<std::atomic<long long>, kSiteNames.size()> calls{};
    const auto index = static_cast<size_t>(site);
    return plan[index] > 0 && ++calls[index] == plan[index];
}

uint64_t deviceMemoryForChecks(uint64_t reported) {
    const char* text = std::getenv("PENUMBRA_DEVICE_MEMORY");
    if (!text || !*text)
        return reported;
    uint64_t bytes = 0;
    const std::string_view view(text);
    const auto [end, error] = std::from_chars(view.data(), view.data() + view.size(), bytes);
    if (error != std::errc{} || end != view.data() + view.size() || bytes == 0)
        return reported; // a malformed seam changes nothing
    return std::min(bytes, reported);
}

} // namespace penumbra
