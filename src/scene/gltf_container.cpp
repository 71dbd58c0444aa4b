#include "scene/gltf_container.h"

#include "penumbra/error.h"
#include "scene/gltf_compression.h"

#include <fmt/format.h>

#include <optional>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <set>

namespace penumbra::gltf {
namespace {

constexpr uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A; // "JSON"
constexpr uint32_t kChunkBin = 0x004E4942;  // "BIN\0"
// KHR_texture_transform: on the base colour (its alpha tests holes too), applied to the vertices'
// coordinates at load time.
// KHR_texture_basisu and EXT_texture_webp: their images are not decoded, and their textures
// fall back to the colour factor with a warning (shadows do not depend on them).
constexpr std::array<std::string_view, 11> kSupportedRequired = {
    "KHR_lights_punctual",        "KHR_materials_emissive_strength",
    "KHR_materials_unlit",        "KHR_mesh_quantization",
    "KHR_materials_transmission", "KHR_materials_volume",
    "KHR_draco_mesh_compression", "EXT_meshopt_compression",
    "KHR_texture_basisu",         "EXT_texture_webp",
    "KHR_texture_transform"};

uint32_t readU32(const std::vector<uint8_t>& b, size_t at) {
    uint32_t v = 0;
    std::memcpy(&v, b.data() + at, 4); // GLB is little-endian, as is every target we build for
    return v;
}

[[noreturn]] void refuse(const std::filesystem::path& file, const std::string& what) {
    throw InputError(file.string(), what);
}

void checkUri(const std::filesystem::path& file, const std::string& path, const std::string& uri) {
    if (uri.rfind("data:", 0) == 0) {
        std::string error;
        if (!parseDataUri(uri, &error))
            refuse(file, path + ": " + error);
        return;
    }
    if (uri.empty())
        refuse(file, path + ": empty URI");
    // The parser percent-decodes relative URIs once (and reads '+' as a space), so the checks
    // below apply to the name it will open.
    if (uri.find('+') != std::string::npos)
        refuse(file,
               path + ": '+' in a URI is ambiguous; percent-encode it as %2B ('" + uri + "')");
    const std::optional<std::string> decoded = percentDecode(uri);
    if (!decoded)
        refuse(file, path + ": malformed percent-encoding ('" + uri + "')");
    const std::string& name = *decoded;
    const std::filesystem::path p(name);
    if (p.is_absolute() || name.find(':') != std::string::npos || name[0] == '\\')
        refuse(file, path +
                         ": absolute URIs are not supported (only files beside the asset "
                         "and data URIs are read) ('" +
                         uri + "')");
    for (const auto& part : p)
        if (part == "..")
            refuse(file, path + ": URIs may not leave the asset's folder ('" + uri + "')");
    for (char c : name)
        if (c == '\0' || c == '$' || c == '`' || c == '~' || c == '\\')
            refuse(file, path + fmt::format(": refused character '{}' in URI (no expansion is "
                                            "done)",
                                            c == '\0' ? std::string("\\0") : std::string(1, c)));
}

// A buffer's data URI decodes to exactly its byteLength (the validator's
// BUFFER_EMBEDDED_BYTELENGTH_MISMATCH); checkUri has checked its form.
void dataUriHoldsByteLength(const std::filesystem::path& file, const std::string& path,
                            size_t bytes, const nlohmann::json& byteLength) {
    if (!byteLength.is_number_integer() || byteLength.get<int64_t>() < 0 ||
        bytes != byteLength.get<uint64_t>())
        refuse(file, fmt::format("{}: the data URI holds {} bytes but byteLength says {}", path,
                                 bytes, byteLength.dump()));
}

// An index field: must be an integer naming an element of `target` (the JSON path says where).
void checkIndex(const std::filesystem::path& file, const nlohmann::json& j, const std::string& path,
                const nlohmann::json& value, const char* target) {
    if (!value.is_number_integer())
        refuse(file, path + ": wrong JSON type (an integer index is expected)");
    const size_t size = j.contains(target) && j[target].is_array() ? j[target].size() : 0;
    const long long i = value.get<long long>();
    if (i < 0 || static_cast<unsigned long long>(i) >= size)
        refuse(file, fmt::format("{}: index {} is out of range ({} {})", path, i, size, target));
}

// Before any parser follows them: every cross-reference and byteStride, by JSON path.
void checkReferences(const std::filesystem::path& file, const nlohmann::json& j) {
    auto each = [&](const char* array, auto visit) {
        if (!j.contains(array))
            return;
        if (!j[array].is_array())
            refuse(file, std::string(array) + ": wrong JSON type (array expected)");
        for (size_t i = 0; i < j[array].size(); ++i) {
            if (!j[array][i].is_object())
                refuse(file, fmt::format("{}[{}]: wrong JSON type (object expected)", array, i));
            visit(fmt::format("{}[{}]", array, i), j[array][i]);
        }
    };
    if (j.contains("scene"))
        checkIndex(file, j, "scene", j["scene"], "scenes");
    each("scenes", [&](const std::string& path, const nlohmann::json& s) {
        if (s.contains("nodes"))
            for (size_t k = 0; k < s["nodes"].size(); ++k)
                checkIndex(file, j, fmt::format("{}.nodes[{}]", path, k), s["nodes"][k], "nodes");
    });
    each("nodes", [&](const std::string& path, const nlohmann::json& n) {
        if (n.contains("mesh"))
            checkIndex(file, j, path + ".mesh", n["mesh"], "meshes");
        if (n.contains("camera"))
            checkIndex(file, j, path + ".camera", n["camera"], "cameras");
        // The parser reads a matrix and drops TRS beside it without a word.
        if (n.contains("matrix") &&
            (n.contains("translation") || n.contains("rotation") || n.contains("scale")))
            refuse(file, path + ": has both a matrix and translation, rotation or scale");
        if (n.contains("children")) {
            if (!n["children"].is_array())
                refuse(file, path + ".children: wrong JSON type");
            for (size_t k = 0; k < n["children"].size(); ++k)
                checkIndex(file, j, fmt::format("{}.children[{}]", path, k), n["children"][k],
                           "nodes");
        }
    });
    each("meshes", [&](const std::string& path, const nlohmann::json& m) {
        if (!m.contains("primitives") || !m["primitives"].is_array())
            refuse(file, path + ".primitives: missing or not an array");
        for (size_t k = 0; k < m["primitives"].size(); ++k) {
            const auto& p = m["primitives"][k];
            const std::string pp = fmt::format("{}.primitives[{}]", path, k);
            if (!p.is_object() || !p.contains("attributes") || !p["attributes"].is_object())
                refuse(file, pp + ".attributes: missing or not an object");
            for (const auto& [name, a] : p["attributes"].items())
                checkIndex(file, j, pp + ".attributes." + name, a, "accessors");
            if (p.contains("indices"))
                checkIndex(file, j, pp + ".indices", p["indices"], "accessors");
            if (p.contains("material"))
                checkIndex(file, j, pp + ".material", p["material"], "materials");
        }
    });
    each("materials", [&](const std::string& path, const nlohmann::json& m) {
        auto textureInfo = [&](const std::string& at, const nlohmann::json& owner,
                               const char* key) {
            if (!owner.contains(key))
                return;
            const auto& info = owner[key];
            if (!info.is_object() || !info.contains("index"))
                refuse(file, at + "." + key + ": an object with an index is expected");
            checkIndex(file, j, at + "." + key + ".index", info["index"], "textures");
            if (info.contains("texCoord") &&
                (!info["texCoord"].is_number_integer() || info["texCoord"].get<long long>() < 0))
                refuse(file, at + "." + key + ".texCoord: not a non-negative integer");
        };
        for (const char* key : {"normalTexture", "occlusionTexture", "emissiveTexture"})
            textureInfo(path, m, key);
        for (const auto& [name, key] :
             {std::pair{"KHR_materials_transmission", "transmissionTexture"},
              std::pair{"KHR_materials_volume", "thicknessTexture"}})
            if (m.contains("extensions") && m["extensions"].is_object() &&
                m["extensions"].contains(name)) {
                const auto& extension = m["extensions"][name];
                const std::string at = path + ".extensions." + name;
                if (!extension.is_object())
                    refuse(file, at + ": an object is expected");
                textureInfo(at, extension, key);
            }
        if (m.contains("pbrMetallicRoughness")) {
            const auto& pbr = m["pbrMetallicRoughness"];
            if (!pbr.is_object())
                refuse(file, path + ".pbrMetallicRoughness: wrong JSON type (object expected)");
            for (const char* key : {"baseColorTexture", "metallicRoughnessTexture"})
                textureInfo(path + ".pbrMetallicRoughness", pbr, key);
            // tinygltf drops a factor of any other length with a note nobody reads, and the
            // base colour texture with it: the material would load white and untextured.
            if (pbr.contains("baseColorFactor") &&
                (!pbr["baseColorFactor"].is_array() || pbr["baseColorFactor"].size() != 4))
                refuse(file, path + ".pbrMetallicRoughness.baseColorFactor: needs 4 numbers");
        }
    });
    each("textures", [&](const std::string& path, const nlohmann::json& t) {
        if (t.contains("source"))
            checkIndex(file, j, path + ".source", t["source"], "images");
        if (t.contains("sampler"))
            checkIndex(file, j, path + ".sampler", t["sampler"], "samplers");
    });
    each("images", [&](const std::string& path, const nlohmann::json& i) {
        if (i.contains("bufferView")) {
            checkIndex(file, j, path + ".bufferView", i["bufferView"], "bufferViews");
            if (!i.contains("mimeType"))
                refuse(file, path + ".mimeType: required with a bufferView");
        } else if (!i.contains("uri")) {
            refuse(file, path + ": neither uri nor bufferView");
        }
    });
    each("accessors", [&](const std::string& path, const nlohmann::json& a) {
        if (a.contains("bufferView"))
            checkIndex(file, j, path + ".bufferView", a["bufferView"], "bufferViews");
    });
    each("bufferViews", [&](const std::string& path, const nlohmann::json& v) {
        if (!v.contains("buffer"))
            refuse(file, path + ".buffer: missing");
        checkIndex(file, j, path + ".buffer", v["buffer"], "buffers");
        // tinygltf hands an image's bufferView to the decoder while it parses, before
        // validateModel sees a byte range, so each view must lie inside its buffer's declared
        // byteLength here (tinygltf then holds every buffer to exactly that length). Values
        // that are not unsigned integers are tinygltf's to refuse (or, byteOffset, to ignore).
        const auto& buffer = j["buffers"][v["buffer"].get<size_t>()];
        auto unsignedAt = [](const nlohmann::json& o, const char* key) {
            return o.is_object() && o.contains(key) && o[key].is_number_unsigned()
                       ? std::optional<uint64_t>(o[key].get<uint64_t>())
                       : std::nullopt;
        };
        const auto bufferLength = unsignedAt(buffer, "byteLength");
        const auto length = unsignedAt(v, "byteLength");
        const uint64_t offset = unsignedAt(v, "byteOffset").value_or(0);
        if (bufferLength && length && (offset > *bufferLength || *length > *bufferLength - offset))
            refuse(file, fmt::format("{}: bytes {}..{} run past buffer {} ({} bytes)", path, offset,
                                     offset + *length, v["buffer"].dump(), *bufferLength));
        if (v.contains("byteStride")) {
            if (!v["byteStride"].is_number_integer())
                refuse(file, path + ".byteStride: wrong JSON type");
            const long long s = v["byteStride"].get<long long>();
            if (s < 4 || s > 252 || s % 4)
                refuse(file, fmt::format("{}.byteStride: {} is not a multiple of 4 in [4, 252]",
                                         path, s));
        }
    });
}

// JSON Schema's "integer" admits 1.0; the parser wants an integer. A float that is a whole
// number inside +-2^53 becomes one (a float field reads an integer just as well). Not inside
// `extras`, free-form data the parser keeps as it is, except that it narrows an integer to 32
// bits there (tiny_gltf.h, ParseJsonAsValue): a light's `extras.radius` of 4294967297 would read
// as 1, so an integer past that range in `extras` becomes a float instead.
// (Iterative, as every walk of the whole document here: a hostile file nests arrays as deep as
// its length allows.)
void integralNumbersAsIntegers(nlohmann::json& root) {
    std::vector<std::pair<nlohmann::json*, bool>> pending{{&root, false}}; // in extras
    while (!pending.empty()) {
        const auto [node, inExtras] = pending.back();
        nlohmann::json& j = *node;
        pending.pop_back();
        if (j.is_object()) {
            for (auto it = j.begin(); it != j.end(); ++it)
                pending.emplace_back(&it.value(), inExtras || it.key() == "extras");
        } else if (j.is_array()) {
            for (auto& item : j)
                pending.emplace_back(&item, inExtras);
        } else if (inExtras && (j.is_number_integer() || j.is_number_unsigned())) {
            const double v = j.get<double>();
            if (v < -2147483648.0 || v > 2147483647.0)
                j = v;
        } else if (!inExtras && j.is_number_float()) {
            const double v = j.get<double>();
            if (std::isfinite(v) && v == std::floor(v) && std::abs(v) < 9007199254740992.0)
                j = v >= 0 ? nlohmann::json(static_cast<uint64_t>(v))
                           : nlohmann::json(static_cast<int64_t>(v));
        }
    }
}

// extensionsUsed or extensionsRequired as a set of names: an array of strings, else refused.
std::set<std::string> extensionList(const std::filesystem::path& file, const nlohmann::json& j,
                                    const char* key) {
    std::set<std::string> names;
    if (!j.contains(key))
        return names;
    if (!j[key].is_array())
        refuse(file, std::string(key) + ": not an array");
    for (const auto& e : j[key]) {
        if (!e.is_string())
            refuse(file, std::string(key) + ": not a string");
        names.insert(e.get<std::string>());
    }
    return names;
}

// Every extension an object carries is declared in extensionsUsed, and every required one is
// among them (the validator's UNDECLARED_EXTENSION and its required twin). Extras are the
// user's: not walked.
void checkDeclaredExtensions(const std::filesystem::path& file, const nlohmann::json& root) {
    const std::set<std::string> used = extensionList(file, root, "extensionsUsed");
    for (const std::string& name : extensionList(file, root, "extensionsRequired"))
        if (!used.contains(name))
            refuse(file, fmt::format("extensionsRequired: '{}' is not in extensionsUsed", name));
    std::vector<std::pair<const nlohmann::json*, std::string>> pending{{&root, ""}};
    while (!pending.empty()) {
        const auto [j, path] = pending.back();
        pending.pop_back();
        if (j->is_array()) {
            for (size_t i = 0; i < j->size(); ++i)
                pending.emplace_back(&(*j)[i], fmt::format("{}[{}]", path, i));
            continue;
        }
        if (!j->is_object())
            continue;
        for (const auto& [key, value] : j->items()) {
            const std::string at = path.empty() ? key : path + "." + key;
            if (key == "extras")
                continue;
            if (key == "extensions" && value.is_object())
                for (const auto& [name, body] : value.items()) {
                    if (!used.contains(name))
                        refuse(file, at + "." + name + ": not declared in extensionsUsed");
                    if (!body.is_object())
                        refuse(file, at + "." + name + ": wrong JSON type (an object is expected)");
                }
            pending.emplace_back(&value, at);
        }
    }
}

// A GLB's buffer 0 (no uri) is the BIN chunk; one declared longer than the chunk (a placeholder)
// is read as the chunk's bytes, and any view past them is refused later by its own path.
void glbBufferWithinItsChunk(const std::filesystem::path& file, const Container& c,
                             nlohmann::json& j, std::vector<std::string>* warnings) {
    if (!c.binary || !j.contains("buffers") || !j["buffers"].is_array() || j["buffers"].empty())
        return;
    nlohmann::json& buffer = j["buffers"][0];
    if (!buffer.is_object() || buffer.contains("uri") || !buffer.contains("byteLength") ||
        !buffer["byteLength"].is_number_unsigned())
        return;
    const uint64_t declared = buffer["byteLength"].get<uint64_t>();
    if (declared <= c.binChunkLength)
        return;
    if (warnings)
        warnings->push_back(fmt::format("{}: buffers[0].byteLength: {} bytes declared but the BIN "
                                        "chunk holds {}; read as {}",
                                        file.string(), declared, c.binChunkLength,
                                        c.binChunkLength));
    buffer["byteLength"] = c.binChunkLength;
}

} // namespace

std::vector<uint8_t> parserInput(const Container& c, const std::string& json) {
    if (!c.binary)
        return {json.begin(), json.end()};
    std::string padded = json;
    while (padded.size() % 4)
        padded += ' ';
    const uint64_t bin = c.binChunkOffset ? c.binChunkLength : 0;
    std::vector<uint8_t> out;
    auto u32 = [&](uint64_t v) {
        for (int k = 0; k < 4; ++k)
            out.push_back(static_cast<uint8_t>(v >> (8 * k)));
    };
    const uint64_t total = 12 + 8 + padded.size() + (bin ? 8 + bin : 0);
    if (total > std::numeric_limits<uint32_t>::max())
        throw InputError("GLB", "the rewritten container passes 4 GiB");
    out.reserve(total);
    u32(kGlbMagic), u32(2), u32(total);
    u32(padded.size()), u32(kChunkJson);
    out.insert(out.end(), padded.begin(), padded.end());
    if (bin) {
        u32(bin), u32(kChunkBin);
        out.insert(out.end(), c.bytes.begin() + static_cast<long>(c.binChunkOffset),
                   c.bytes.begin() + static_cast<long>(c.binChunkOffset + bin));
    }
    return out;
}

std::optional<std::string> percentDecode(std::string_view text) {
    auto hex = [](char c) -> int {
        if (c >= '0' && c <= '9')
            return c - '0';
        if (c >= 'a' && c <= 'f')
            return c - 'a' + 10;
        if (c >= 'A' && c <= 'F')
            return c - 'A' + 10;
        return -1;
    };
    std::string out;
    for (size_t i = 0; i < text.size(); ++i) {
        if (text[i] != '%') {
            out += text[i];
            continue;
        }
        if (i + 2 >= text.size())
            return std::nullopt;
        const int hi = hex(text[i + 1]), lo = hex(text[i + 2]);
        if (hi < 0 || lo < 0)
            return std::nullopt;
        out += static_cast<char>(hi * 16 + lo);
        i += 2;
    }
    return out;
}

bool decodeBase64(std::string_view text, std::vector<uint8_t>& out) {
    auto value = [](char c) -> int {
        if (c >= 'A' && c <= 'Z')
            return c - 'A';
        if (c >= 'a' && c <= 'z')
            return c - 'a' + 26;
        if (c >= '0' && c <= '9')
            return c - '0' + 52;
        if (c == '+')
            return 62;
        if (c == '/')
            return 63;
        return -1;
    };
    if (text.size() % 4 != 0)
        return false;
    out.clear();
    out.reserve(text.size() / 4 * 3);
    for (size_t i = 0; i < text.size(); i += 4) {
        int v[4];
        int padding = 0;
        for (int k = 0; k < 4; ++k) {
            const char c = text[i + k];
            if (c == '=' && i + 4 == text.size() && k >= 2) {
                v[k] = 0, ++padding;
            } else {
                if (padding)
                    return false; // data after '='
                v[k] = value(c);
                if (v[k] < 0)
                    return false;
            }
        }
        const uint32_t n = (uint32_t(v[0]) << 18) | (uint32_t(v[1]) << 12) | (uint32_t(v[2]) << 6) |
                           uint32_t(v[3]);
        out.push_back(static_cast<uint8_t>(n >> 16));
        if (padding < 2)
            out.push_back(static_cast<uint8_t>(n >> 8));
        if (padding < 1)
            out.push_back(static_cast<uint8_t>(n));
    }
    return true;
}

Container readContainer(const std::filesystem::path& file, uint64_t maxFileSize) {
    std::error_code ec;
    uint64_t size = std::filesystem::file_size(file, ec);
    if (ec)
        refuse(file, "cannot read: " + ec.message());
    if (size > maxFileSize)
        refuse(file, fmt::format("{} bytes is past the size cap of {} (--max-file-size)", size,
                                 maxFileSize));
    Container c;
    c.bytes.resize(size);
    std::ifstream in(file, std::ios::binary);
    if (!in.read(reinterpret_cast<char*>(c.bytes.data()), static_cast<std::streamsize>(size)))
        refuse(file, "cannot read the file");
    if (size >= 4 && readU32(c.bytes, 0) == kGlbMagic) {
        c.binary = true;
        if (size < 20)
            refuse(file, "GLB: truncated header");
        if (readU32(c.bytes, 4) != 2)
            refuse(file,
                   fmt::format("GLB: version {} is not supported (2 is)", readU32(c.bytes, 4)));
        // Bytes after the declared length are not the asset's (the validator's warning
        // GLB_EXTRA_DATA): read up to it. Fewer bytes than declared is a truncated file.
        if (readU32(c.bytes, 8) > size || readU32(c.bytes, 8) < 20)
            refuse(file, fmt::format("GLB: header length {} but the file has {} bytes",
                                     readU32(c.bytes, 8), size));
        c.trailingBytes = size - readU32(c.bytes, 8);
        c.bytes.resize(readU32(c.bytes, 8));
        size = c.bytes.size();
        const uint64_t jsonLength = readU32(c.bytes, 12);
        if (readU32(c.bytes, 16) != kChunkJson)
            refuse(file, "GLB: the first chunk is not JSON");
        if (jsonLength == 0 || 20 + jsonLength > size || jsonLength % 4 != 0)
            refuse(file, fmt::format("GLB: JSON chunk length {} is invalid", jsonLength));
        c.json.assign(reinterpret_cast<const char*>(c.bytes.data()) + 20, jsonLength);
        uint64_t at = 20 + jsonLength;
        if (at < size) {
            if (at + 8 > size)
                refuse(file, "GLB: truncated chunk header");
            c.binChunkLength = readU32(c.bytes, at);
            if (readU32(c.bytes, at + 4) != kChunkBin)
                refuse(file, "GLB: the second chunk is not BIN");
            if (at + 8 + c.binChunkLength > size)
                refuse(file, fmt::format("GLB: BIN chunk length {} runs past the file",
                                         c.binChunkLength));
            c.binChunkOffset = at + 8;
        }
    } else {
        c.json.assign(reinterpret_cast<const char*>(c.bytes.data()), size);
    }
    return c;
}

// How deep the JSON's arrays and objects nest (outside strings). Writing the JSON back out
// (json.dump(), for the parser) recurses once a level: 100000 levels overflowed the stack.
namespace {
size_t jsonNesting(const std::string& text) {
    size_t depth = 0, deepest = 0;
    bool inString = false;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (c == '\\')
                ++i; // the escaped character, whatever it is
            else if (c == '"')
                inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return deepest;
}
} // namespace

nlohmann::json checkJson(const std::filesystem::path& file, const Container& container,
                         std::vector<std::string>* warnings) {
    const std::string& text = container.json;
    if (text.rfind("\xEF\xBB\xBF", 0) == 0)
        refuse(file, "the JSON starts with a byte-order mark (glTF's JSON is UTF-8 without one)");
    const size_t first = text.find_first_not_of(" \t\r\n");
    if (first == std::string::npos || text[first] != '{')
        refuse(file, container.binary ? "GLB: the JSON chunk does not hold a JSON object"
                                      : "not a glTF file: neither a JSON object nor a GLB");
    // A glTF nests a dozen levels; extras may add some. Far past that is an attack on the stack.
    constexpr size_t kMaxNesting = 512;
    if (const size_t nesting = jsonNesting(text); nesting > kMaxNesting)
        refuse(file,
               fmt::format("the JSON nests {} levels deep (at most {})", nesting, kMaxNesting));
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        refuse(file, fmt::format("not valid JSON: a syntax error at byte {}", e.byte));
    } catch (const nlohmann::json::exception&) { // a number past double's range, ...
        refuse(file, "not valid JSON: a number out of range");
    }
    if (!j.is_object())
        refuse(file, "not a glTF file: neither a JSON object nor a GLB");
    integralNumbersAsIntegers(j);
    if (!j.contains("asset") || !j["asset"].is_object() || !j["asset"].contains("version") ||
        !j["asset"]["version"].is_string())
        refuse(file, "asset.version: missing");
    const std::string version = j["asset"]["version"];
    if (version.rfind("2.", 0) != 0)
        refuse(file, "asset.version: '" + version + "' is not supported (glTF 2.x is)");
    for (const std::string& name : extensionList(file, j, "extensionsRequired"))
        if (std::find(kSupportedRequired.begin(), kSupportedRequired.end(), name) ==
            kSupportedRequired.end())
            refuse(file, "extensionsRequired: '" + name + "' is not supported");
    glbBufferWithinItsChunk(file, container, j, warnings);
    if (container.trailingBytes > 0 && warnings)
        warnings->push_back(fmt::format("{}: GLB: {} bytes after the header's length {} are "
                                        "ignored",
                                        file.string(), container.trailingBytes,
                                        container.bytes.size()));
    checkDeclaredExtensions(file, j);
    checkRequiredProperties(file, j);
    checkReferences(file, j);
    leaveOutUnreadBuffers(file, container.binary, j, warnings);
    for (const char* array : {"buffers", "images"}) {
        if (!j.contains(array))
            continue;
        if (!j[array].is_array())
            refuse(file, std::string(array) + ": not an array");
        for (size_t i = 0; i < j[array].size(); ++i) {
            const auto& item = j[array][i];
            const std::string path = fmt::format("{}[{}].uri", array, i);
            if (item.is_object() && item.contains("uri")) {
                if (!item["uri"].is_string())
                    refuse(file, path + ": not a string");
                const std::string uri = item["uri"];
                checkUri(file, path, uri);
                if (uri.rfind("data:", 0) == 0) { // checkUri has checked its form
                    std::string error;
                    const DataUri data = *parseDataUri(uri, &error);
                    const bool image = std::string_view(array) == "images";
                    if (!image)
                        dataUriHoldsByteLength(file, path, data.bytes.size(), item["byteLength"]);
                    j[array][i]["uri"] = canonicalDataUri(data, image);
                }
                // (A missing image is refused by readTextures, only when a material uses it.
                // A name the file system cannot hold is a missing file, not a throw.)
                std::error_code ec;
                if (std::string_view(array) == "buffers" && uri.rfind("data:", 0) != 0 &&
                    !std::filesystem::is_regular_file(file.parent_path() / *percentDecode(uri), ec))
                    refuse(file, fmt::format("{}: '{}' is not a file beside the asset", path, uri));
            } else if (std::string_view(array) == "buffers" && (!container.binary || i > 0) &&
                       !isMeshoptFallback(item)) {
                refuse(file, path + ": missing, and a drawn primitive or an image reads the "
                                    "buffer (only a GLB's first buffer, its BIN chunk, may "
                                    "leave it out)");
            }
        }
    }
    return j;
}

} // namespace penumbra::gltf
