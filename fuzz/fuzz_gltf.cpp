// libFuzzer target for the glTF loader (assets are hostile: docs/testing.md). Each input is written
// to a private temporary folder as scene.glb (when it starts with the GLB magic "glTF") or
// scene.gltf and loaded with a small size cap. Refusing it with InputError is the expected
// outcome; any other exception escaping, a crash, or an ASan/UBSan report is a finding.
#include "penumbra/error.h"
#include "penumbra/scene.h"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include <unistd.h>

namespace {

std::filesystem::path gDir; // created once, removed at exit
std::string gGlb, gGltf;    // the two file names inside it

void removeDir() {
    std::error_code ec;
    std::filesystem::remove_all(gDir, ec);
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "penumbra-fuzz-XXXXXX").string();
    if (!::mkdtemp(pattern.data())) {
        std::perror("penumbra_fuzz_gltf: mkdtemp");
        std::abort();
    }
    gDir = pattern;
    gGlb = (gDir / "scene.glb").string();
    gGltf = (gDir / "scene.gltf").string();
    std::atexit(removeDir);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    const std::string& path = glb ? gGlb : gGltf;
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f || (size && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0) {
        std::perror("penumbra_fuzz_gltf: writing the input");
        std::abort();
    }
    static std::vector<std::string> warnings;
    warnings.clear();
    try {
        const penumbra::Scene scene =
            penumbra::loadScene(path, {.maxFileSize = uint64_t{1} << 20,
                                       .maxTriangles = 200'000, // instancing stays fast
                                       .warnings = &warnings});
        (void)scene;
    } catch (const penumbra::InputError&) {
        // a clear refusal: what the loader must do with a malformed asset
    }
    // The folder is empty between inputs, so a .gltf that names scene.glb (or itself) as a
    // buffer sees the same bytes whenever the input is replayed.
    ::unlink(path.c_str());
    return 0;
}
