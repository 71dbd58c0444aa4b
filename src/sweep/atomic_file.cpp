#include "sweep/atomic_file.h"

#include "penumbra/error.h"

#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <fstream>
#include <random>

namespace penumbra::sweep {

void writeFileAtomically(const std::filesystem::path& file,
                         const std::function<void(std::ostream&)>& write) {
    static std::atomic<uint64_t> counter{0};
    // Unique among processes (pid), machines sharing the directory (random) and threads.
    const std::filesystem::path temp =
        file.parent_path() / fmt::format(".{}.{}-{}-{}.tmp", file.filename().string(), ::getpid(),
                                         std::random_device{}(), ++counter);
    std::error_code ec;
    {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        write(out);
        out.flush();
        if (!out) {
            std::filesystem::remove(temp, ec);
            throw InputError(file.string(), "cannot write the file");
        }
    }
    std::filesystem::rename(temp, file, ec);
    if (ec) {
        std::filesystem::remove(temp, ec);
        throw InputError(file.string(), "cannot rename the file into place");
    }
}

} // namespace penumbra::sweep
