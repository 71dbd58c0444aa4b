#pragma once
// A test seam for the paths a user rarely sees: PENUMBRA_FAULT=allocation:N makes the Nth
// device-memory allocation of the process fail as out of device memory, submit:N the Nth queue
// submission report the device lost (1-based; both may be given, comma-separated). Unset, nothing
// changes. The CLI's fault sweep (tests/test_cli_faults.cpp) runs each command with N = 1, 2, ...
// until it succeeds, and checks that every failure ends in one `error:` line, a non-zero exit and
// no output.
#include <string_view>

namespace penumbra::vk {

enum class FaultSite { Allocation, Submit };

// True when this call at `site` is the one PENUMBRA_FAULT names (counts every call).
bool injectFault(FaultSite site);

} // namespace penumbra::vk
