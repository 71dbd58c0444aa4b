// The layer list (src/shadows/layer.h): one line per layer, in the order a light's evaluation
// runs them. The translucent layer goes last: the light per channel it writes is then the light's
// final one, which the composite shades with (composite.comp).
#include "shadows/layer.h"

#include "core/virtual_maps.h"

#include <algorithm>

namespace penumbra::shadows {

std::span<const LayerModule* const> allLayers() {
    static const LayerModule* const layers[] = {&contactLayer(), &temporalLayer(),
                                                &translucentLayer()};
    return layers;
}

size_t layerIndex(const LayerModule& layer) {
    const auto all = allLayers();
    return static_cast<size_t>(std::find(all.begin(), all.end(), &layer) - all.begin());
}

const LayerModule* findLayer(std::string_view name) {
    for (const LayerModule* layer : allLayers())
        if (layer->name == name)
            return layer;
    return nullptr;
}

std::vector<const LayerModule*> enabledLayers(const ParameterValues& params) {
    std::vector<const LayerModule*> on;
    for (const LayerModule* layer : allLayers())
        if (layer->enabled && layer->enabled(params))
            on.push_back(layer);
    return on;
}

bool keepsHistory(const ParameterValues& params) {
    const std::vector<const LayerModule*> on = enabledLayers(params);
    return std::any_of(on.begin(), on.end(),
                       [](const LayerModule* layer) { return layer->history.has_value(); });
}

uint32_t warmUpFrames(const ParameterValues& params, bool virtualMaps) {
    uint32_t frames = virtualMaps ? VirtualSettings::of(params).warmUpFrames() : 1;
    for (const LayerModule* layer : enabledLayers(params))
        if (layer->warmUpFrames)
            frames = std::max(frames, layer->warmUpFrames(params));
    return frames;
}

} // namespace penumbra::shadows
