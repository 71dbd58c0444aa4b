// Buffers without data that nothing drawn reads. Outside a GLB's first buffer a buffer without a
// uri has no bytes; the validator calls such an asset valid (an application may supply them),
// and a renderer can too while no drawn primitive or image reads them: the buffer is left out
// with a warning, and the parser sees a one-byte stand-in, with every view on it emptied and
// every accessor on those views detached (the spec's zeros, which animations and skins, the
// only other readers, do not need here).
#include "penumbra/error.h"
#include "scene/gltf_compression.h"
#include "scene/gltf_container.h"

#include <fmt/format.h>

#include <set>

namespace penumbra::gltf {
namespace {

using Json = nlohmann::json;

const Json* member(const Json& object, const char* key) {
    return object.is_object() && object.contains(key) ? &object[key] : nullptr;
}

// An index field as checkReferences left it (an integer in range), or -1.
long long indexOf(const Json& object, const char* key) {
    const Json* v = member(object, key);
    return v && v->is_number_integer() ? v->get<long long>() : -1;
}

// The views a drawn primitive or an image reads: through the accessors of every primitive of a
// mesh some node places (attributes, indices, morph targets, sparse parts), draco's view, and
// every image's view (the parser decodes each image).
std::set<long long> viewsRead(const Json& j) {
    std::set<long long> accessors, views;
    std::set<long long> meshes;
    if (const Json* nodes = member(j, "nodes"))
        for (const Json& node : *nodes)
            if (indexOf(node, "mesh") >= 0)
                meshes.insert(indexOf(node, "mesh"));
    const Json* meshList = member(j, "meshes");
    for (long long mesh : meshes) {
        const Json* primitives = member((*meshList)[static_cast<size_t>(mesh)], "primitives");
        for (const Json& p : primitives && primitives->is_array() ? *primitives : Json::array()) {
            if (indexOf(p, "indices") >= 0)
                accessors.insert(indexOf(p, "indices"));
            std::vector<const Json*> sets{member(p, "attributes")};
            if (const Json* targets = member(p, "targets"); targets && targets->is_array())
                for (const Json& t : *targets)
                    sets.push_back(&t);
            for (const Json* set : sets)
                if (set && set->is_object())
                    for (const auto& [name, a] : set->items())
                        if (a.is_number_integer())
                            accessors.insert(a.get<long long>());
            if (const Json* ext = member(p, "extensions"))
                if (const Json* draco = member(*ext, "KHR_draco_mesh_compression"))
                    views.insert(indexOf(*draco, "bufferView"));
        }
    }
    const Json* accessorList = member(j, "accessors");
    for (long long a : accessors) {
        if (!accessorList || a < 0 || static_cast<size_t>(a) >= accessorList->size())
            continue;
        const Json& accessor = (*accessorList)[static_cast<size_t>(a)];
        views.insert(indexOf(accessor, "bufferView"));
        if (const Json* sparse = member(accessor, "sparse"))
            for (const char* part : {"indices", "values"})
                if (const Json* p = member(*sparse, part))
                    views.insert(indexOf(*p, "bufferView"));
    }
    if (const Json* images = member(j, "images"))
        for (const Json& image : *images)
            views.insert(indexOf(image, "bufferView"));
    views.erase(-1);
    return views;
}

} // namespace

void leaveOutUnreadBuffers(const std::filesystem::path& file, bool binary, Json& j,
                           std::vector<std::string>* warnings) {
    Json* buffers = j.contains("buffers") && j["buffers"].is_array() ? &j["buffers"] : nullptr;
    if (!buffers)
        return;
    std::set<long long> dataless;
    for (size_t i = 0; i < buffers->size(); ++i) {
        const Json& b = (*buffers)[i];
        if (b.is_object() && !b.contains("uri") && (!binary || i > 0) && !isMeshoptFallback(b))
            dataless.insert(static_cast<long long>(i));
    }
    if (dataless.empty())
        return;
    Json* views =
        j.contains("bufferViews") && j["bufferViews"].is_array() ? &j["bufferViews"] : nullptr;
    std::set<long long> read; // buffers
    for (long long v : viewsRead(j)) {
        if (!views || static_cast<size_t>(v) >= views->size())
            continue;
        const Json& view = (*views)[static_cast<size_t>(v)];
        read.insert(indexOf(view, "buffer"));
        if (const Json* ext = member(view, "extensions"))
            if (const Json* meshopt = member(*ext, "EXT_meshopt_compression"))
                read.insert(indexOf(*meshopt, "buffer"));
    }
    std::set<long long> emptied; // views
    for (long long b : dataless) {
        if (read.contains(b))
            continue; // refused by checkJson, naming the buffer
        if (warnings)
            warnings->push_back(fmt::format("{}: buffers[{}]: no uri and so no data; nothing drawn "
                                            "reads it, so it is left out",
                                            file.string(), b));
        (*buffers)[static_cast<size_t>(b)] = {{"byteLength", 1},
                                              {"uri", "data:application/octet-stream;base64,AA=="}};
        for (size_t v = 0; views && v < views->size(); ++v)
            if (indexOf((*views)[v], "buffer") == b) {
                (*views)[v] = {{"buffer", b}, {"byteLength", 1}};
                emptied.insert(static_cast<long long>(v));
            }
    }
    if (emptied.empty() || !j.contains("accessors") || !j["accessors"].is_array())
        return;
    for (Json& accessor : j["accessors"]) {
        if (!accessor.is_object())
            continue;
        if (emptied.contains(indexOf(accessor, "bufferView"))) {
            accessor.erase("bufferView");
            accessor.erase("byteOffset");
        }
        if (const Json* sparse = member(accessor, "sparse"))
            for (const char* part : {"indices", "values"})
                if (const Json* p = member(*sparse, part);
                    p && emptied.contains(indexOf(*p, "bufferView"))) {
                    accessor.erase("sparse");
                    break;
                }
    }
}

} // namespace penumbra::gltf
