// Loading a generated 1M-triangle glTF (a 708 x 708 grid, external .bin): parse, validation,
// flattening and sanitation, as `penumbra render` does before anything reaches the GPU.
#include "penumbra/scene.h"

#include <benchmark/benchmark.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <vector>

namespace {

std::filesystem::path writeGrid(uint32_t side) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("penumbra-bench-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    std::vector<float> pos;
    for (uint32_t z = 0; z <= side; ++z)
        for (uint32_t x = 0; x <= side; ++x)
            pos.insert(pos.end(), {float(x), 0.01f * float((x * 7 + z * 13) % 5), float(z)});
    std::vector<uint32_t> idx;
    for (uint32_t z = 0; z < side; ++z)
        for (uint32_t x = 0; x < side; ++x) {
            const uint32_t a = z * (side + 1) + x, b = a + 1, c = a + side + 1, d = c + 1;
            idx.insert(idx.end(), {a, c, b, b, c, d});
        }
    std::ofstream bin(dir / "grid.bin", std::ios::binary);
    bin.write(reinterpret_cast<const char*>(pos.data()), std::streamsize(pos.size() * 4));
    bin.write(reinterpret_cast<const char*>(idx.data()), std::streamsize(idx.size() * 4));
    const size_t posBytes = pos.size() * 4, idxBytes = idx.size() * 4;
    const nlohmann::json j = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
        {"accessors",
         {{{"bufferView", 0}, {"componentType", 5126}, {"count", pos.size() / 3}, {"type", "VEC3"}},
          {{"bufferView", 1}, {"componentType", 5125}, {"count", idx.size()}, {"type", "SCALAR"}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", posBytes}},
          {{"buffer", 0}, {"byteOffset", posBytes}, {"byteLength", idxBytes}}}},
        {"buffers", {{{"uri", "grid.bin"}, {"byteLength", posBytes + idxBytes}}}}};
    std::ofstream(dir / "grid.gltf") << j.dump();
    return dir / "grid.gltf";
}

void LoadMillionTriangleGltf(benchmark::State& state) {
    static const std::filesystem::path file = writeGrid(708); // 1,002,528 triangles
    size_t triangles = 0;
    for (auto _ : state) {
        const penumbra::Scene scene = penumbra::loadScene(file.string());
        triangles = scene.triangleCount();
        benchmark::DoNotOptimize(triangles);
    }
    state.counters["triangles"] = double(triangles);
}
BENCHMARK(LoadMillionTriangleGltf)->Unit(benchmark::kMillisecond)->Iterations(5);

} // namespace

BENCHMARK_MAIN();
