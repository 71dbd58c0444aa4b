#pragma once
// A test seam for the paths a user rarely sees. PENUMBRA_FAULT names, comma-separated, which call
// of each kind fails (1-based, counted over the process):
//   allocation:N  the Nth device-memory allocation fails as out of device memory
//   creation:N    the Nth Vulkan object creation (image, view, pipeline, fence, command buffer,
//                 ...) fails as out of host memory
//   submit:N      the Nth queue submission reports the device lost
//   embree:N      the Nth allocation the ray tracer asks for is refused
//   write:N       the Nth output file cannot be written (no space left on the device)
// Unset, nothing changes. The CLI's fault sweep (tests/test_cli_faults.cpp) runs each command
// with N = 1, 2, ... until it succeeds, and checks that every failure ends in one `error:` line,
// a non-zero exit and no output.
#include <cstdint>

namespace penumbra {

enum class FaultSite { Allocation, Creation, Submit, Embree, Write };

// True when this call at `site` is the one PENUMBRA_FAULT names (counts every call; thread-safe).
bool injectFault(FaultSite site);

// PENUMBRA_DEVICE_MEMORY=BYTES: the device memory the renderer's checks assume when less than
// the device reports, so that the paths for a device too small to hold a render (compare and
// bench skipping a row) can be tested on any device. Returns `reported` when unset.
uint64_t deviceMemoryForChecks(uint64_t reported);

} // namespace penumbra
