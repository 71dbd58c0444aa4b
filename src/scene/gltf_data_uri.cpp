// Data URIs (RFC 2397) in every form the glTF spec allows: `data:[<mediatype>][;<parameter>]*
// [;base64],<data>`, base64 or percent-encoded, with or without a media type. The parser knows
// only a few base64 prefixes, so checkJson hands it each one rewritten to a canonical base64
// form of the same bytes.
#include "core/base64.h"
#include "scene/gltf_container.h"

#include <array>

namespace penumbra::gltf {

std::optional<DataUri> parseDataUri(std::string_view uri, std::string* error) {
    const size_t comma = uri.find(',');
    if (uri.rfind("data:", 0) != 0 || comma == std::string_view::npos) {
        *error = "data URI without a comma before its data";
        return std::nullopt;
    }
    const std::string_view header = uri.substr(5, comma - 5);
    DataUri d;
    const bool base64 = header.size() >= 7 && header.substr(header.size() - 7) == ";base64";
    d.mediaType = std::string(header.substr(0, header.find(';')));
    const std::string_view data = uri.substr(comma + 1);
    if (base64) {
        if (!decodeBase64(data, d.bytes)) {
            *error = "data URI has malformed base64";
            return std::nullopt;
        }
        return d;
    }
    const std::optional<std::string> decoded = percentDecode(data);
    if (!decoded) {
        *error = "data URI has malformed percent-encoding";
        return std::nullopt;
    }
    d.bytes.assign(decoded->begin(), decoded->end());
    return d;
}

std::string canonicalDataUri(const DataUri& d, bool image) {
    // The prefixes the parser recognises; anything else is its bytes, which the image decoder
    // identifies by their signature.
    static constexpr std::array<std::string_view, 4> kImageTypes = {"image/png", "image/jpeg",
                                                                    "image/bmp", "image/gif"};
    std::string type = "application/octet-stream";
    for (std::string_view t : kImageTypes)
        if (image && d.mediaType == t)
            type = std::string(t);
    return "data:" + type + ";base64," + encodeBase64(d.bytes);
}

} // namespace penumbra::gltf
