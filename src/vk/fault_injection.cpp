#include "vk/fault_injection.h"

#include <atomic>
#include <charconv>
#include <cstdlib>
#include <string>

namespace penumbra::vk {
namespace {

struct Plan {
    long long allocation = 0, submit = 0; // 0: never
};

Plan readPlan() {
    Plan plan;
    const char* text = std::getenv("PENUMBRA_FAULT");
    std::string_view rest = text ? text : "";
    while (!rest.empty()) {
        const std::string_view item = rest.substr(0, rest.find(','));
        rest.remove_prefix(std::min(rest.size(), item.size() + 1));
        for (auto [prefix, value] : {std::pair{std::string_view("allocation:"), &plan.allocation},
                                     std::pair{std::string_view("submit:"), &plan.submit}})
            if (item.substr(0, prefix.size()) == prefix)
                std::from_chars(item.data() + prefix.size(), item.data() + item.size(), *value);
    }
    return plan;
}

} // namespace

bool injectFault(FaultSite site) {
    static const Plan plan = readPlan();
    static std::atomic<long long> allocations{0}, submits{0};
    switch (site) {
    case FaultSite::Allocation:
        return plan.allocation > 0 && ++allocations == plan.allocation;
    case FaultSite::Submit:
        return plan.submit > 0 && ++submits == plan.submit;
    }
    return false;
}

} // namespace penumbra::vk
