// The truth cache (truth_cache.h). File layout, little-endian: "PNTRUTH" + version byte; width,
// height, layer count, coloured (0 or 1) (uint32 each); rays (uint64); seconds and trace seconds
// (double); then per layer the visibility and the occluder distances (width * height float32
// each), and where coloured its transmittance (3 x width * height float32).
#include "sweep/truth_cache.h"

#include "penumbra/error.h"
#include "sweep/atomic_file.h"
#include "sweep/tasks.h"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <fstream>

namespace penumbra::sweep {
namespace {

class Hasher {
public:
    template <typename T>
    void add(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        mBytes.append(reinterpret_cast<const char*>(&value), sizeof(T));
    }
    void add(const std::string& text) {
        add(uint64_t(text.size()));
        mBytes += text;
    }
    template <typename T>
    void addRange(const std::vector<T>& values) {
        add(uint64_t(values.size()));
        mBytes.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
    }
    std::string hex() const { return hashHex(mBytes); }

private:
    std::string mBytes;
};

void write(std::ostream& out, const void* data, size_t bytes) {
    out.write(static_cast<const char*>(data), std::streamsize(bytes));
}

constexpr char kMagic[8] = {'P', 'N', 'T', 'R', 'U', 'T', 'H', char(kTruthVersion)};

} // namespace

std::string sceneContentHash(const Scene& scene) {
    Hasher h;
    h.add(uint64_t(scene.vertices.size()));
    for (const Vertex& v : scene.vertices) {
        h.add(v.position), h.add(v.normal), h.add(v.material), h.add(v.uv), h.add(v.color.w);
        // A colour tints only what crosses a translucent surface.
        if (v.material < scene.materials.size() && scene.materials[v.material].translucent())
            h.add(glm::vec3(v.color));
    }
    h.addRange(scene.indices);
    h.add(uint64_t(scene.materials.size()));
    for (const Material& m : scene.materials) {
        h.add(int(m.alphaMode)), h.add(m.alphaCutoff), h.add(m.baseColor.w);
        h.add(m.baseColorTexture), h.add(m.doubleSided), h.add(m.transmission);
        h.add(m.transmissionTexture), h.add(m.thickness), h.add(m.attenuationDistance);
        h.add(m.attenuationColor);
        if (m.translucent())
            h.add(glm::vec3(m.baseColor));
    }
    h.add(uint64_t(scene.textures.size()));
    for (const Texture& t : scene.textures)
        h.add(t.image), h.add(int(t.wrapS)), h.add(int(t.wrapT)), h.add(t.nearest);
    h.add(uint64_t(scene.images.size()));
    for (const TextureImage& image : scene.images)
        h.add(image.width), h.add(image.height), h.addRange(image.rgba);
    return h.hex();
}

std::string truthKey(const Scene& lit, const std::string& cameraName, uint32_t width,
                     uint32_t height, uint32_t samples) {
    Hasher h;
    h.add(kTruthVersion);
    h.add(sceneContentHash(lit));
    h.add(uint64_t(lit.lights.size()));
    for (const Light& l : lit.lights) {
        h.add(int(l.type)), h.add(l.position), h.add(l.direction), h.add(l.range);
        h.add(l.innerConeAngle), h.add(l.outerConeAngle), h.add(l.radius);
        h.add(l.angularDiameter), h.add(l.castsShadow);
    }
    const Camera c = lit.camera(cameraName);
    h.add(c.position), h.add(c.target), h.add(c.up), h.add(c.yfov), h.add(c.orthographic);
    h.add(c.ymag), h.add(c.znear), h.add(c.zfar);
    h.add(width), h.add(height), h.add(samples);
    return h.hex();
}

TruthCache::TruthCache(std::filesystem::path dir) : mDir(std::move(dir)) {
    std::error_code ec;
    std::filesystem::create_directories(mDir, ec);
    if (!std::filesystem::is_directory(mDir, ec))
        throw InputError(mDir.string(), "cannot create the truth cache directory");
}

std::filesystem::path TruthCache::fileOf(const std::string& key) const {
    return mDir / (key + ".truth");
}

std::optional<ReferenceResult> TruthCache::load(const std::string& key) const {
    std::ifstream in(fileOf(key), std::ios::binary);
    if (!in)
        return std::nullopt;
    char magic[8];
    ReferenceResult r;
    uint32_t layers = 0, coloured = 0;
    in.read(magic, 8);
    in.read(reinterpret_cast<char*>(&r.width), 4);
    in.read(reinterpret_cast<char*>(&r.height), 4);
    in.read(reinterpret_cast<char*>(&layers), 4);
    in.read(reinterpret_cast<char*>(&coloured), 4);
    in.read(reinterpret_cast<char*>(&r.rays), 8);
    in.read(reinterpret_cast<char*>(&r.seconds), 8);
    in.read(reinterpret_cast<char*>(&r.traceSeconds), 8);
    if (!in || std::memcmp(magic, kMagic, 8) != 0 || layers > 64 || coloured > 1 ||
        uint64_t(r.width) * r.height > (uint64_t{1} << 28))
        return std::nullopt; // not ours or damaged: computed again and replaced
    const size_t pixels = size_t(r.width) * r.height;
    for (uint32_t l = 0; l < layers; ++l) {
        r.visibility.emplace_back(pixels);
        r.occluderDistance.emplace_back(pixels);
        in.read(reinterpret_cast<char*>(r.visibility.back().data()), std::streamsize(pixels * 4));
        in.read(reinterpret_cast<char*>(r.occluderDistance.back().data()),
                std::streamsize(pixels * 4));
        if (coloured) {
            r.transmittance.emplace_back(3 * pixels);
            in.read(reinterpret_cast<char*>(r.transmittance.back().data()),
                    std::streamsize(3 * pixels * 4));
        }
    }
    if (!in || in.peek() != std::char_traits<char>::eof())
        return std::nullopt;
    return r;
}

void TruthCache::store(const std::string& key, const ReferenceResult& truth) const {
    writeFileAtomically(fileOf(key), [&](std::ostream& out) {
        const uint32_t layers = uint32_t(truth.visibility.size());
        const uint32_t coloured = truth.transmittance.size() == layers && layers > 0;
        write(out, kMagic, 8);
        write(out, &truth.width, 4);
        write(out, &truth.height, 4);
        write(out, &layers, 4);
        write(out, &coloured, 4);
        write(out, &truth.rays, 8);
        write(out, &truth.seconds, 8);
        write(out, &truth.traceSeconds, 8);
        for (uint32_t l = 0; l < layers; ++l) {
            const std::vector<float>& visibility = truth.visibility[l];
            // A truth without occluder distances (a caller's own) stores them unknown (NaN).
            const bool known = l < truth.occluderDistance.size() &&
                               truth.occluderDistance[l].size() == visibility.size();
            const std::vector<float> unknown(known ? 0 : visibility.size(), NAN);
            write(out, visibility.data(), visibility.size() * 4);
            write(out, (known ? truth.occluderDistance[l] : unknown).data(), visibility.size() * 4);
            if (coloured)
                write(out, truth.transmittance[l].data(), visibility.size() * 3 * 4);
        }
    });
}

ReferenceResult cachedTruth(const TruthCache* cache, const std::string& key,
                            const std::function<ReferenceResult()>& compute, bool* computed) {
    if (cache)
        if (std::optional<ReferenceResult> hit = cache->load(key)) {
            if (computed)
                *computed = false;
            return std::move(*hit);
        }
    ReferenceResult truth = compute();
    if (computed)
        *computed = true;
    if (cache)
        cache->store(key, truth);
    return truth;
}

} // namespace penumbra::sweep
