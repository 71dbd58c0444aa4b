#pragma once
// Files that appear whole or not at all, for directories that several shards, processes and
// machines write at once (task records, the truth cache, sweep.json).
#include <filesystem>
#include <functional>
#include <ostream>

namespace penumbra::sweep {

// Writes `file` through `write` into a temporary name in the same directory, unique across
// threads, processes and machines sharing it, then renames it over `file`: a reader sees the old
// file or the new one, never a part. Throws InputError naming `file` (the temporary removed).
void writeFileAtomically(const std::filesystem::path& file,
                         const std::function<void(std::ostream&)>& write);

} // namespace penumbra::sweep
