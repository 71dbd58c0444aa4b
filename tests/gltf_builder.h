#pragma once
// Builds glTF 2.0 assets for the loader tests: a JSON document plus one binary buffer, written
// as .gltf with a data URI or an external .bin, or as .glb. Tests then break what they test.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace penumbra::test {

class GltfBuilder {
public:
    nlohmann::json j = {{"asset", {{"version", "2.0"}}},
                        {"scene", 0},
                        {"scenes", nlohmann::json::array({{{"nodes", nlohmann::json::array()}}})}};
    std::vector<uint8_t> bin;

    template <typename T>
    int view(const std::vector<T>& data, int stride = 0) {
        while (bin.size() % 4)
            bin.push_back(0);
        const size_t offset = bin.size();
        bin.resize(offset + data.size() * sizeof(T));
        std::memcpy(bin.data() + offset, data.data(), data.size() * sizeof(T));
        nlohmann::json v = {
            {"buffer", 0}, {"byteOffset", offset}, {"byteLength", data.size() * sizeof(T)}};
        if (stride)
            v["byteStride"] = stride;
        return push("bufferViews", v);
    }
    int accessor(int bufferView, int componentType, size_t count, const char* type,
                 bool normalized = false) {
        nlohmann::json a = {{"bufferView", bufferView},
                            {"componentType", componentType},
                            {"count", count},
                            {"type", type}};
        if (normalized)
            a["normalized"] = true;
        return push("accessors", a);
    }
    // A POSITION accessor with the min and max the spec requires.
    int positions(const std::vector<float>& xyz) {
        const int a = accessor(view(xyz), 5126, xyz.size() / 3, "VEC3");
        std::vector<float> lo(xyz.begin(), xyz.begin() + 3), hi = lo;
        for (size_t i = 0; i < xyz.size(); ++i)
            lo[i % 3] = std::min(lo[i % 3], xyz[i]), hi[i % 3] = std::max(hi[i % 3], xyz[i]);
        j["accessors"][a]["min"] = lo;
        j["accessors"][a]["max"] = hi;
        return a;
    }
    int mesh(int position, int indices = -1, int mode = 4) {
        nlohmann::json prim = {{"attributes", {{"POSITION", position}}}, {"mode", mode}};
        if (indices >= 0)
            prim["indices"] = indices;
        return push("meshes", {{"primitives", nlohmann::json::array({prim})}});
    }
    int node(nlohmann::json n, bool root = true) {
        const int i = push("nodes", std::move(n));
        if (root)
            j["scenes"][0]["nodes"].push_back(i);
        return i;
    }
    // A unit ground quad (two triangles, uint16 indices) at y = 0: the usual receiver.
    int ground() {
        const int p = positions({-5, 0, -5, 5, 0, -5, 5, 0, 5, -5, 0, 5});
        const int i = accessor(view(std::vector<uint16_t>{0, 2, 1, 0, 3, 2}), 5123, 6, "SCALAR");
        return node({{"mesh", mesh(p, i)}});
    }

    std::filesystem::path writeGltf(const std::filesystem::path& file, bool external = false) {
        finishBuffer(external ? file.stem().string() + ".bin" : dataUri());
        if (external)
            write(file.parent_path() / (file.stem().string() + ".bin"), bin);
        write(file, j.dump());
        return file;
    }
    std::filesystem::path writeGlb(const std::filesystem::path& file) {
        finishBuffer("");
        j["buffers"][0].erase("uri");
        std::string json = j.dump();
        while (json.size() % 4)
            json += ' ';
        while (bin.size() % 4)
            bin.push_back(0);
        std::vector<uint8_t> out;
        auto u32 = [&](uint32_t v) {
            for (int k = 0; k < 4; ++k)
                out.push_back(uint8_t(v >> (8 * k)));
        };
        u32(0x46546C67), u32(2), u32(uint32_t(12 + 8 + json.size() + 8 + bin.size()));
        u32(uint32_t(json.size())), u32(0x4E4F534A);
        out.insert(out.end(), json.begin(), json.end());
        u32(uint32_t(bin.size())), u32(0x004E4942);
        out.insert(out.end(), bin.begin(), bin.end());
        write(file, out);
        return file;
    }

    // Standard base64 with padding, as data URIs carry it.
    static std::string base64(const std::vector<uint8_t>& bytes) {
        static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        std::string s;
        for (size_t i = 0; i < bytes.size(); i += 3) {
            const uint32_t n = (uint32_t(bytes[i]) << 16) |
                               (i + 1 < bytes.size() ? uint32_t(bytes[i + 1]) << 8 : 0) |
                               (i + 2 < bytes.size() ? bytes[i + 2] : 0);
            s += k[(n >> 18) & 63], s += k[(n >> 12) & 63];
            s += i + 1 < bytes.size() ? k[(n >> 6) & 63] : '=';
            s += i + 2 < bytes.size() ? k[n & 63] : '=';
        }
        return s;
    }

private:
    int push(const char* array, nlohmann::json item) {
        if (!j.contains(array))
            j[array] = nlohmann::json::array();
        j[array].push_back(std::move(item));
        return static_cast<int>(j[array].size() - 1);
    }
    void finishBuffer(const std::string& uri) {
        if (!j.contains("buffers"))
            j["buffers"] = nlohmann::json::array({nlohmann::json::object()});
        j["buffers"][0]["byteLength"] = bin.size();
        if (!uri.empty())
            j["buffers"][0]["uri"] = uri;
    }
    std::string dataUri() const { return "data:application/octet-stream;base64," + base64(bin); }
    template <typename Bytes>
    static void write(const std::filesystem::path& file, const Bytes& bytes) {
        std::ofstream out(file, std::ios::binary);
        out.write(reinterpret_cast<const char*>(bytes.data()),
                  static_cast<std::streamsize>(bytes.size()));
    }
};

// Ground, a fan-indexed (uint8) quad above it, a perspective camera and a directional sun.
inline GltfBuilder floatingQuad() {
    GltfBuilder b;
    b.ground();
    const int p = b.positions({-1, 2, -1, 1, 2, -1, 1, 2, 1, -1, 2, 1});
    const int fan = b.accessor(b.view(std::vector<uint8_t>{0, 1, 2, 3}), 5121, 4, "SCALAR");
    b.node({{"mesh", b.mesh(p, fan, 6)}});
    b.node({{"camera", 0}, {"translation", {0, 6, 9}}, {"rotation", {-0.2588, 0, 0, 0.9659}}});
    b.j["cameras"] = {{{"type", "perspective"},
                       {"name", "eye"},
                       {"perspective", {{"yfov", 0.8}, {"znear", 0.1}, {"zfar", 100}}}}};
    b.node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}},
            {"rotation", {-0.7071, 0, 0, 0.7071}}});
    b.j["extensions"] = {{"KHR_lights_punctual",
                          {{"lights",
                            {{{"type", "directional"},
                              {"intensity", 2.0},
                              {"extras", {{"angularDiameter", 2.5}}}}}}}}};
    b.j["extensionsUsed"] = {"KHR_lights_punctual"};
    return b;
}

// Every index component type, a sparse POSITION accessor, an interleaved (strided) one, and a
// sparse accessor with no bufferView (zeros plus the sparse values).
inline GltfBuilder componentTypes() {
    GltfBuilder b;
    const std::vector<float> xyz = {0, 0, 0, 1, 0, 0, 0, 0, 1, 9, 9, 9};
    const int p = b.accessor(b.view(xyz), 5126, 4, "VEC3");
    b.j["accessors"][p]["sparse"] = {
        {"count", 1},
        {"indices", {{"bufferView", b.view(std::vector<uint16_t>{3, 0})}, {"componentType", 5123}}},
        {"values", {{"bufferView", b.view(std::vector<float>{1, 0, 1})}}}};
    const int u8 = b.accessor(b.view(std::vector<uint8_t>{0, 2, 1, 1, 2, 3}), 5121, 6, "SCALAR");
    const int u16 = b.accessor(b.view(std::vector<uint16_t>{0, 2, 1, 1, 2, 3}), 5123, 6, "SCALAR");
    const int u32 = b.accessor(b.view(std::vector<uint32_t>{0, 2, 1, 1, 2, 3}), 5125, 6, "SCALAR");
    for (int idx : {u8, u16, u32})
        b.node({{"mesh", b.mesh(p, idx)}});
    const int strided = b.accessor(
        b.view(std::vector<float>{0, 0, 3, 7, 1, 0, 3, 7, 0, 1, 3, 7}, 16), 5126, 3, "VEC3");
    b.node({{"mesh", b.mesh(strided)}});
    b.j["accessors"].push_back(
        {{"componentType", 5126},
         {"count", 3},
         {"type", "VEC3"},
         {"sparse",
          {{"count", 2},
           {"indices",
            {{"bufferView", b.view(std::vector<uint8_t>{1, 2})}, {"componentType", 5121}}},
           {"values", {{"bufferView", b.view(std::vector<float>{1, 0, 0, 0, 1, 0})}}}}}});
    b.node({{"mesh", b.mesh(static_cast<int>(b.j["accessors"].size() - 1))}});
    return b;
}

} // namespace penumbra::test
