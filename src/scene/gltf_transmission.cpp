// KHR_materials_transmission and KHR_materials_volume: light through a material
// (docs/translucency.md). Read from the document itself: every number checked, a value out of
// the extension's range refused with its JSON path.
#include "scene/gltf_transmission.h"

#include "penumbra/error.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>

namespace penumbra::gltf {
namespace {

// The number at `key` of `owner` (`fallback` when absent), refused unless `ok` holds for it:
// `expected` says what is.
double numberAt(const std::filesystem::path& file, const std::string& at,
                const nlohmann::json& owner, const char* key, double fallback, bool (*ok)(double),
                const char* expected) {
    if (!owner.contains(key))
        return fallback;
    const nlohmann::json& v = owner[key];
    if (!v.is_number() || !ok(v.get<double>()))
        throw InputError(file.string(),
                         fmt::format("{}.{}: {} is not {}", at, key, v.dump(), expected));
    return v.get<double>();
}

bool fraction(double x) {
    return x >= 0.0 && x <= 1.0;
}

} // namespace

void readTransmission(const std::filesystem::path& file, const std::string& path,
                      const nlohmann::json& material, const TransmissionTextures& textures,
                      Material& out, const std::function<void(const std::string&)>& warn) {
    if (!material.is_object() || !material.contains("extensions") ||
        !material["extensions"].is_object())
        return;
    const nlohmann::json& extensions = material["extensions"];
    if (extensions.contains("KHR_materials_transmission")) {
        const std::string at = path + ".extensions.KHR_materials_transmission";
        const nlohmann::json& e = extensions["KHR_materials_transmission"];
        if (!e.is_object())
            throw InputError(file.string(), at + ": an object is expected");
        out.transmission = static_cast<float>(
            numberAt(file, at, e, "transmissionFactor", 0.0, fraction, "a number in [0, 1]"));
        if (e.contains("transmissionTexture")) { // indices checked with the document
            const nlohmann::json& info = e["transmissionTexture"];
            // Checked a non-negative integer with the document; any size (2^32 is no 0).
            const auto texCoord = info.value("texCoord", int64_t{0});
            const bool transformed = info.contains("extensions") &&
                                     info["extensions"].is_object() &&
                                     info["extensions"].contains("KHR_texture_transform");
            const size_t index = info["index"].get<size_t>();
            if (texCoord != textures.baseTexCoord || transformed || textures.baseTransformed)
                warn(fmt::format("{}.transmissionTexture: read with coordinates other than the "
                                 "base colour's; its factor alone is used",
                                 at));
            else if (index < textures.sceneTextureOf.size())
                out.transmissionTexture = textures.sceneTextureOf[index];
        }
    }
    if (extensions.contains("KHR_materials_volume")) {
        const std::string at = path + ".extensions.KHR_materials_volume";
        const nlohmann::json& e = extensions["KHR_materials_volume"];
        if (!e.is_object())
            throw InputError(file.string(), at + ": an object is expected");
        // Floats: past 1e30 their arithmetic overflows, under 1e-30 a length would round to 0
        // (a volume turned thin-walled, an attenuation turned off). The distance's default is
        // infinite: no attenuation.
        out.thickness = static_cast<float>(numberAt(
            file, at, e, "thicknessFactor", 0.0,
            [](double x) { return x == 0.0 || (x >= 1e-30 && x <= 1e30); },
            "0 or a number in [1e-30, 1e30]"));
        out.attenuationDistance = static_cast<float>(numberAt(
            file, at, e, "attenuationDistance", HUGE_VAL,
            [](double x) { return x >= 1e-30 && x <= 1e30; }, "a number in [1e-30, 1e30]"));
        if (e.contains("attenuationColor")) {
            const nlohmann::json& c = e["attenuationColor"];
            if (!c.is_array() || c.size() != 3)
                throw InputError(file.string(), at + ".attenuationColor: needs 3 numbers");
            for (int i = 0; i < 3; ++i)
                if (!c[i].is_number() || !fraction(c[i].get<double>()))
                    throw InputError(file.string(),
                                     fmt::format("{}.attenuationColor[{}]: {} is not a number in "
                                                 "[0, 1]",
                                                 at, i, c[i].dump()));
            for (int i = 0; i < 3; ++i)
                out.attenuationColor[i] = c[i].get<float>();
        }
        if (e.contains("thicknessTexture"))
            warn(at + ".thicknessTexture: not used; the thickness factor is");
    }
}

} // namespace penumbra::gltf
