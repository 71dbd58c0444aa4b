// The "show" section of the viewer's interface: the lit image, one light's visibility, a layer
// of the shadow maps, the cascades, or the error against the ground truth of this view.
#include "shadows/technique.h"
#include "viewer_state.h"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>

namespace penumbra::viewer {
namespace {

const char* const kModes[] = {
    "lit image",     "visibility",     "shadow map",      "cascades",      "error vs ground truth",
    "blocker depth", "penumbra width", "contact shadows", "virtual pages", "page pool"};

// The virtual-map views: the level to show, the legend and the last frame's page counts.
void pagesPanel(ViewerState& s) {
    const std::optional<VirtualMapInfo>& v = s.lastFrame.virtualMaps;
    if (!v) {
        ImGui::TextWrapped("the technique reads no virtual maps: set virtual.enabled (%s)",
                           shadows::techniquesWhere([](const shadows::TechniqueModule& m) {
                               return m.readsVirtualMaps;
                           }).c_str());
        return;
    }
    if (s.display == DisplayMode::Pages && !s.levelNames.empty()) {
        const int shown = std::clamp(s.shownLevel, 0, static_cast<int>(s.levelNames.size()) - 1);
        const std::string current =
            s.displayLevel < 0 ? "finest with pages: " + s.levelNames[shown] : s.levelNames[shown];
        if (ImGui::BeginCombo("level", current.c_str())) {
            if (ImGui::Selectable("the finest with pages", s.displayLevel < 0))
                s.displayLevel = -1;
            for (size_t i = 0; i < s.levelNames.size(); ++i)
                if (ImGui::Selectable(s.levelNames[i].c_str(),
                                      static_cast<int>(i) == s.displayLevel))
                    s.displayLevel = static_cast<int>(i);
            ImGui::EndCombo();
        }
        ImGui::Checkbox("whole table", &s.wholeTable);
        ImGui::Text("pages %u..%u, %u..%u", s.pageWindow.x, s.pageWindow.x + s.pageWindow.z - 1,
                    s.pageWindow.y, s.pageWindow.y + s.pageWindow.z - 1);
        ImGui::TextWrapped("one cell per page: red rendered this frame, green asked for and "
                           "cached, blue kept from earlier frames, yellow asked for but the pool "
                           "was full, dark not in the pool");
    } else if (s.display == DisplayMode::Pool) {
        ImGui::TextWrapped("one cell per physical page, tinted by the level it holds (finest "
                           "red to coarsest blue), bright if rendered this frame; grey: a page "
                           "no level shows now; dark: free");
    }
    ImGui::Text("pages asked for %u, cached %u, rendered %u, dropped %u", v->requested, v->cached,
                v->rendered, v->dropped);
    ImGui::Text("pool %u of %u pages (%.1f%%), %.0f MiB", v->resident, v->poolPages,
                v->poolPages ? 100.0 * v->resident / v->poolPages : 0.0,
                double(v->poolBytes) / (1 << 20));
}

// "light 0", or for a layer "light 0 +x" / "light 1 cascade 2".
std::vector<std::string> layerNames(const RenderResult& frame) {
    std::vector<std::string> names;
    for (const LightShadow& l : frame.lights) {
        uint32_t cascade = 0;
        for (const ShadowViewInfo& v : l.views) {
            std::string name = fmt::format("light {}", l.sceneLight);
            if (v.cascade)
                name += fmt::format(" cascade {}", cascade++);
            else if (!v.name.empty())
                name += " " + v.name;
            names.push_back(name);
        }
    }
    return names;
}

void metricsTable(const ErrorMetrics& m) {
    if (!ImGui::BeginTable("metrics", 2))
        return;
    auto row = [](const char* name, const std::string& value) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(name);
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(value.c_str());
    };
    row("RMSE", fmt::format("{:.4f}", m.rmse));
    row("misclassified", fmt::format("{:.3f}%", 100.0 * m.misclassified));
    row("  away from edges", fmt::format("{:.3f}%", 100.0 * m.misclassifiedOutsideEdges));
    row("acne", fmt::format("{:.3f}%", 100.0 * m.acne));
    row("leak", fmt::format("{:.3f}%", 100.0 * m.leak));
    row("pixels", fmt::format("{}", m.pixels));
    ImGui::EndTable();
}

} // namespace

bool hasBlockerSearch(Technique technique) {
    return !shadows::moduleOf(technique).blockerSearchKey.empty();
}

void showPanel(ViewerState& s) {
    int mode = static_cast<int>(s.display);
    ImGui::Combo("show", &mode, kModes, IM_ARRAYSIZE(kModes));
    s.display = static_cast<DisplayMode>(mode);
    int shadowLights = 0;
    for (const LightShadow& l : s.lastFrame.lights)
        shadowLights += l.visibilityIndex >= 0;
    const bool search =
        s.display == DisplayMode::BlockerDepth || s.display == DisplayMode::Penumbra;
    if (search && !hasBlockerSearch(s.options.technique))
        ImGui::TextWrapped("%s has no blocker search: %s do",
                           std::string(techniqueName(s.options.technique)).c_str(),
                           shadows::techniquesWhere([](const shadows::TechniqueModule& m) {
                               return !m.blockerSearchKey.empty();
                           }).c_str());
    else if (s.display == DisplayMode::BlockerDepth)
        ImGui::TextWrapped("the average blocker's depth in the light's view (grey; dark blue: "
                           "no blocker found)");
    else if (s.display == DisplayMode::Penumbra)
        ImGui::TextWrapped(
            "the filter's radius in texels: blue 0 to yellow at the largest "
            "(%s); dark blue: no blocker found",
            std::string(shadows::moduleOf(s.options.technique).blockerSearchKey).c_str());
    const bool contact = s.display == DisplayMode::Contact;
    if (contact && s.options.parameters.number("contact.length") <= 0.0)
        ImGui::TextWrapped("the contact layer is off: set contact.length (world units) under "
                           "\"contact\"");
    else if (contact)
        ImGui::TextWrapped("what the contact layer finds: black where a surface within "
                           "contact.length hides the light, multiplied into the visibility");
    if (s.display == DisplayMode::Visibility || s.display == DisplayMode::Error || search ||
        contact) {
        if (shadowLights == 0)
            ImGui::TextUnformatted("no light casts a shadow");
        else
            ImGui::SliderInt("shadow-casting light", &s.displayLight, 0, shadowLights - 1);
    }
    if (s.display == DisplayMode::Cascades) {
        bool cascaded = false;
        for (const LightShadow& l : s.lastFrame.lights)
            for (const ShadowViewInfo& v : l.views)
                cascaded = cascaded || v.cascade;
        ImGui::TextWrapped(cascaded ? "the cascade each pixel reads: red, green, blue, yellow "
                                      "from near to far"
                                    : "no light has cascades (csm.cascades > 1 for a sun)");
    }
    if (s.display == DisplayMode::ShadowMap) {
        const std::vector<std::string> names = layerNames(s.lastFrame);
        if (names.empty() || !shadows::drawsLightMaps(shadows::moduleOf(s.options.technique))) {
            ImGui::TextUnformatted("this technique draws no shadow map");
        } else {
            s.displayLayer = std::min(s.displayLayer, static_cast<int>(names.size()) - 1);
            if (ImGui::BeginCombo("layer", names[s.displayLayer].c_str())) {
                for (size_t i = 0; i < names.size(); ++i)
                    if (ImGui::Selectable(names[i].c_str(), static_cast<int>(i) == s.displayLayer))
                        s.displayLayer = static_cast<int>(i);
                ImGui::EndCombo();
            }
        }
    }
    if (s.display == DisplayMode::Pages || s.display == DisplayMode::Pool)
        pagesPanel(s);
    if (s.display != DisplayMode::Error)
        return;
    ImGui::SliderInt("rays per pixel", &s.truthSamples, 1, 1024, "%d",
                     ImGuiSliderFlags_Logarithmic);
    if (ImGui::Button("compute the ground truth for this view"))
        s.truthRequested = true;
    if (s.truthProgress >= 0.0 && s.truthProgress < 1.0)
        ImGui::ProgressBar(static_cast<float>(s.truthProgress));
    if (!s.truthStatus.empty())
        ImGui::TextWrapped("%s", s.truthStatus.c_str());
    if (s.errorMetrics) {
        ImGui::TextWrapped("visibility - truth: blue too dark, red too bright, grey not counted");
        metricsTable(*s.errorMetrics);
    }
}

} // namespace penumbra::viewer
