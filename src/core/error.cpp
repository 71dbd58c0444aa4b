#include "penumbra/error.h"

#include <cstdio>
#include <cstdlib>

namespace penumbra {

void fatal(const char* file, int line, const std::string& message) {
    std::fprintf(stderr, "penumbra: fatal: %s:%d: %s\n", file, line, message.c_str());
    std::abort();
}

} // namespace penumbra
