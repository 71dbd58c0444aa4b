#pragma once
// A layer on a light's evaluation: a screen-space pass that runs after the light's base technique
// (PerLight phase, src/render/frame_graph.h), reads the G-buffer and the light's visibility so
// far and multiplies in what it finds (screen-space contact shadows, the first). A light is
// evaluated by one base technique and the layers whose parameters switch them on; every layer
// works on top of every technique and for every light type. Each layer is one module in this
// folder, its shader in shaders/ and a line in allLayers() (docs/architecture.md).
#include "shadows/technique.h"

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace penumbra::shadows {

struct LayerModule {
    std::string_view name;                 // "contact": compare rows "<row>+contact"; its
                                           // GPU timestamp scope
    std::string_view summary, reference;   // one line; the paper or text it implements
    std::vector<ParameterInfo> parameters; // its own family (`contact.*`)
    bool (*enabled)(const ParameterValues&) = nullptr; // on for these parameters
    std::pair<std::string_view, std::string_view> off; // the setting that switches it off
    std::string_view shader; // in shaders/: one dispatch per shadow-casting light
    // Writes its parameters into its block (LAYER_PARAMS; its struct in shaders/include).
    void (*pack)(const ParameterValues&, ParamBlock&) = nullptr;
    // What a compare row "<row>+<name>" sets where the row's own settings leave the layer off:
    // sizes from the scene's bounding radius (world units), so the row means the same on any
    // scene.
    std::vector<std::pair<std::string, std::string>> (*rowSettings)(double sceneRadius) = nullptr;
    // The rows `compare` shows with this layer by default ("pcf[box3]": "pcf[box3]+contact").
    std::vector<std::string_view> rows;
    // A layer that keeps a history per light (the temporal layer's), in this format: the frame
    // declares it (Lifetime::History) and the G-buffer's motion vectors, and runs the layer on a
    // layout of its own that binds them (LAYER_MOTION, LAYER_HISTORY_PREVIOUS, LAYER_HISTORY),
    // with the frame, the G-buffer's depth and normals, the visibility and its block; the
    // techniques then turn their per-pixel rotations every frame (FrameData::motion.y).
    std::optional<MapFormat> history;
    // The frames a render draws before its timed ones while this layer is on (what its history
    // needs to hold a pose's steady state); null: the one warm-up frame every render draws.
    uint32_t (*warmUpFrames)(const ParameterValues&) = nullptr;
    // A layer that reads the translucent casters' maps (the translucent layer): the method
    // (TRANSLUCENT_*, translucent.h) whose maps the frame draws from the light, the translucent
    // casters then left out of the depth map. It runs only on scenes with translucent casters,
    // on its own layout (TRANSLUCENT_LAYER_*, with the LAYER_* bindings but the trace list and
    // the results).
    uint32_t (*translucentMethod)(const ParameterValues&) = nullptr;
};

// The registered layers, in the order a light's evaluation runs them.
std::span<const LayerModule* const> allLayers();
// Where `layer` stands in allLayers(): its block's place in the slot's layer buffer.
size_t layerIndex(const LayerModule& layer);
// The layer called `name`, or null.
const LayerModule* findLayer(std::string_view name);
// The layers these parameters switch on, in order.
std::vector<const LayerModule*> enabledLayers(const ParameterValues& params);

const LayerModule& contactLayer();
const LayerModule& temporalLayer();
const LayerModule& translucentLayer();
// Whether a layer these parameters switch on keeps a history (LayerModule::history).
bool keepsHistory(const ParameterValues& params);

// The warm-up frames of a render that does not continue the last: one (first-use costs), two for
// virtual maps whose pages the host decides, or what a layer that keeps a history needs to show
// its steady state (temporal.frames), the most of these. The renderer draws them; stats.json and
// the CLI say how many.
uint32_t warmUpFrames(const ParameterValues& params, bool virtualMaps);

} // namespace penumbra::shadows
