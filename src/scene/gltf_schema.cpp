// The glTF schema's required properties and their JSON types, checked by JSON path before the
// parser sees the document: the parser would refuse the same files in its own words ("'yfov'
// property is missing in OrthographicCamera.") or, for some, read a default.
#include "penumbra/error.h"
#include "scene/gltf_container.h"

#include <fmt/format.h>

#include <functional>

namespace penumbra::gltf {
namespace {

enum class Kind { Integer, Number, String, Boolean, Object, Array };

const char* kindName(Kind k) {
    switch (k) {
    case Kind::Integer:
        return "an integer";
    case Kind::Number:
        return "a number";
    case Kind::String:
        return "a string";
    case Kind::Boolean:
        return "true or false";
    case Kind::Object:
        return "an object";
    case Kind::Array:
        return "an array";
    }
    return "";
}

bool isKind(const nlohmann::json& v, Kind k) {
    switch (k) {
    case Kind::Integer:
        return v.is_number_integer();
    case Kind::Number:
        return v.is_number();
    case Kind::String:
        return v.is_string();
    case Kind::Boolean:
        return v.is_boolean();
    case Kind::Object:
        return v.is_object();
    case Kind::Array:
        return v.is_array();
    }
    return false;
}

struct Property {
    const char* name;
    Kind kind;
    bool required;
};

struct Schema {
    const std::filesystem::path& file;

    [[noreturn]] void refuse(const std::string& what) const {
        throw InputError(file.string(), what);
    }

    // `o` (at `path`) is an object whose listed properties exist where required and have their
    // JSON type wherever present.
    void object(const std::string& path, const nlohmann::json& o,
                std::initializer_list<Property> properties) const {
        if (!o.is_object())
            refuse(path + ": wrong JSON type (an object is expected)");
        for (const Property& p : properties) {
            if (!o.contains(p.name)) {
                if (p.required)
                    refuse(fmt::format("{}.{}: missing (required)", path, p.name));
                continue;
            }
            if (!isKind(o[p.name], p.kind))
                refuse(fmt::format("{}.{}: wrong JSON type ({} is expected)", path, p.name,
                                   kindName(p.kind)));
        }
    }

    // Each element of the top-level or nested array `key` of `owner`.
    void each(const std::string& path, const nlohmann::json& owner, const char* key,
              const std::function<void(const std::string&, const nlohmann::json&)>& visit) const {
        if (!owner.is_object() || !owner.contains(key))
            return;
        const std::string at = path.empty() ? key : path + "." + key;
        if (!owner[key].is_array())
            refuse(at + ": wrong JSON type (an array is expected)");
        for (size_t i = 0; i < owner[key].size(); ++i)
            visit(fmt::format("{}[{}]", at, i), owner[key][i]);
    }
};

} // namespace

void checkRequiredProperties(const std::filesystem::path& file, const nlohmann::json& j) {
    const Schema s{file};
    for (const char* array :
         {"accessors", "animations", "buffers", "bufferViews", "cameras", "images", "materials",
          "meshes", "nodes", "samplers", "scenes", "skins", "textures"})
        s.each("", j, array, [&](const std::string& path, const nlohmann::json& o) {
            s.object(path, o, {{"name", Kind::String, false}});
        });
    s.each("", j, "accessors", [&](const std::string& path, const nlohmann::json& a) {
        s.object(path, a,
                 {{"componentType", Kind::Integer, true},
                  {"count", Kind::Integer, true},
                  {"type", Kind::String, true},
                  {"byteOffset", Kind::Integer, false},
                  {"normalized", Kind::Boolean, false},
                  {"min", Kind::Array, false},
                  {"max", Kind::Array, false},
                  {"sparse", Kind::Object, false}});
        const int componentType = a["componentType"].get<int>();
        if (componentType != 5120 && componentType != 5121 && componentType != 5122 &&
            componentType != 5123 && componentType != 5125 && componentType != 5126)
            s.refuse(fmt::format("{}.componentType: {} is not a glTF component type", path,
                                 componentType));
        const std::string type = a["type"];
        if (type != "SCALAR" && type != "VEC2" && type != "VEC3" && type != "VEC4" &&
            type != "MAT2" && type != "MAT3" && type != "MAT4")
            s.refuse(fmt::format("{}.type: '{}' is not a glTF accessor type", path, type));
        if (!a.contains("sparse"))
            return;
        const auto& sparse = a["sparse"];
        s.object(path + ".sparse", sparse,
                 {{"count", Kind::Integer, true},
                  {"indices", Kind::Object, true},
                  {"values", Kind::Object, true}});
        s.object(path + ".sparse.indices", sparse["indices"],
                 {{"bufferView", Kind::Integer, true},
                  {"componentType", Kind::Integer, true},
                  {"byteOffset", Kind::Integer, false}});
        s.object(path + ".sparse.values", sparse["values"],
                 {{"bufferView", Kind::Integer, true}, {"byteOffset", Kind::Integer, false}});
    });
    s.each("", j, "bufferViews", [&](const std::string& path, const nlohmann::json& v) {
        s.object(path, v,
                 {{"buffer", Kind::Integer, true},
                  {"byteLength", Kind::Integer, true},
                  {"byteOffset", Kind::Integer, false},
                  {"byteStride", Kind::Integer, false},
                  {"target", Kind::Integer, false}});
        if (v.contains("target") && v["target"] != 34962 && v["target"] != 34963)
            s.refuse(fmt::format("{}.target: {} is not ARRAY_BUFFER (34962) or "
                                 "ELEMENT_ARRAY_BUFFER (34963)",
                                 path, v["target"].dump()));
    });
    s.each("", j, "buffers", [&](const std::string& path, const nlohmann::json& b) {
        s.object(path, b, {{"byteLength", Kind::Integer, true}, {"uri", Kind::String, false}});
    });
    s.each("", j, "cameras", [&](const std::string& path, const nlohmann::json& c) {
        s.object(path, c, {{"type", Kind::String, true}});
        const std::string type = c["type"];
        if (type == "perspective") {
            s.object(path, c, {{"perspective", Kind::Object, true}});
            s.object(path + ".perspective", c["perspective"],
                     {{"yfov", Kind::Number, true},
                      {"znear", Kind::Number, true},
                      {"zfar", Kind::Number, false},
                      {"aspectRatio", Kind::Number, false}});
        } else if (type == "orthographic") {
            s.object(path, c, {{"orthographic", Kind::Object, true}});
            s.object(path + ".orthographic", c["orthographic"],
                     {{"xmag", Kind::Number, true},
                      {"ymag", Kind::Number, true},
                      {"znear", Kind::Number, true},
                      {"zfar", Kind::Number, true}});
        } else {
            s.refuse(fmt::format("{}.type: '{}' is not perspective or orthographic", path, type));
        }
    });
    s.each("", j, "animations", [&](const std::string& path, const nlohmann::json& a) {
        s.object(path, a, {{"channels", Kind::Array, true}, {"samplers", Kind::Array, true}});
        s.each(path, a, "channels", [&](const std::string& at, const nlohmann::json& c) {
            s.object(at, c, {{"sampler", Kind::Integer, true}, {"target", Kind::Object, true}});
            s.object(at + ".target", c["target"],
                     {{"path", Kind::String, true}, {"node", Kind::Integer, false}});
        });
        s.each(path, a, "samplers", [&](const std::string& at, const nlohmann::json& sampler) {
            s.object(at, sampler,
                     {{"input", Kind::Integer, true},
                      {"output", Kind::Integer, true},
                      {"interpolation", Kind::String, false}});
        });
    });
    s.each("", j, "skins", [&](const std::string& path, const nlohmann::json& skin) {
        s.object(path, skin,
                 {{"joints", Kind::Array, true},
                  {"inverseBindMatrices", Kind::Integer, false},
                  {"skeleton", Kind::Integer, false}});
    });
    s.each("", j, "nodes", [&](const std::string& path, const nlohmann::json& n) {
        s.object(path, n,
                 {{"matrix", Kind::Array, false},
                  {"translation", Kind::Array, false},
                  {"rotation", Kind::Array, false},
                  {"scale", Kind::Array, false},
                  {"skin", Kind::Integer, false},
                  {"weights", Kind::Array, false}});
    });
    s.each("", j, "samplers", [&](const std::string& path, const nlohmann::json& sampler) {
        s.object(path, sampler,
                 {{"magFilter", Kind::Integer, false},
                  {"minFilter", Kind::Integer, false},
                  {"wrapS", Kind::Integer, false},
                  {"wrapT", Kind::Integer, false}});
    });
    s.each("", j, "materials", [&](const std::string& path, const nlohmann::json& m) {
        s.object(path, m,
                 {{"alphaMode", Kind::String, false},
                  {"alphaCutoff", Kind::Number, false},
                  {"doubleSided", Kind::Boolean, false},
                  {"emissiveFactor", Kind::Array, false}});
    });
    if (j.contains("extensions") && j["extensions"].is_object() &&
        j["extensions"].contains("KHR_lights_punctual")) {
        const auto& lights = j["extensions"]["KHR_lights_punctual"];
        s.object("extensions.KHR_lights_punctual", lights, {{"lights", Kind::Array, true}});
        s.each("extensions.KHR_lights_punctual", lights, "lights",
               [&](const std::string& path, const nlohmann::json& l) {
                   s.object(path, l,
                            {{"type", Kind::String, true},
                             {"color", Kind::Array, false},
                             {"intensity", Kind::Number, false},
                             {"range", Kind::Number, false},
                             {"spot", Kind::Object, false}});
               });
    }
}

} // namespace penumbra::gltf
