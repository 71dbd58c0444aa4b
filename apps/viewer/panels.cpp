// The viewer's interface, generated from the technique and parameter tables: every technique,
// every parameter of the families it reads with its range, the lights, the camera, what the
// window shows, the ground truth and the live timings.
#include "penumbra/error.h"
#include "viewer_state.h"

#include <fmt/format.h>
#include <glm/gtc/constants.hpp>
#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace penumbra::viewer {
namespace {

bool techniqueCombo(const char* label, Technique& technique) {
    bool changed = false;
    if (ImGui::BeginCombo(label, std::string(techniqueName(technique)).c_str())) {
        for (const TechniqueInfo& t : allTechniques()) {
            const bool selected = t.id == technique;
            if (ImGui::Selectable(std::string(t.name).c_str(), selected)) {
                technique = t.id;
                changed = true;
            }
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("%s", std::string(t.summary).c_str());
        }
        ImGui::EndCombo();
    }
    return changed;
}

void setNumber(ParameterValues& values, const ParameterInfo& p, double value) {
    try {
        values.set(p.key, fmt::format("{}", value));
    } catch (const InputError&) { // outside its range after rounding: keep the old value
    }
}

// One widget per parameter, by its type and range.
void parameterWidget(ParameterValues& values, const ParameterInfo& p) {
    const std::string key(p.key);
    const double value = values.number(p.key);
    switch (p.type) {
    case ParameterType::Bool: {
        bool on = value != 0.0;
        if (ImGui::Checkbox(key.c_str(), &on))
            values.set(p.key, on ? "true" : "false");
        break;
    }
    case ParameterType::Choice: {
        int index = static_cast<int>(value);
        if (ImGui::BeginCombo(key.c_str(), std::string(p.choices[index]).c_str())) {
            for (size_t i = 0; i < p.choices.size(); ++i)
                if (ImGui::Selectable(std::string(p.choices[i]).c_str(), int(i) == index))
                    values.set(p.key, p.choices[i]);
            ImGui::EndCombo();
        }
        break;
    }
    case ParameterType::Int: {
        int v = static_cast<int>(value);
        if (ImGui::SliderInt(key.c_str(), &v, static_cast<int>(p.min), static_cast<int>(p.max))) {
            if (p.oddOnly && v % 2 == 0)
                v += v + 1 <= p.max ? 1 : -1;
            setNumber(values, p, v);
        }
        break;
    }
    case ParameterType::Float: {
        auto v = static_cast<float>(value);
        // Wide positive ranges (sizes, exponents) are easier to set on a logarithmic slider.
        const ImGuiSliderFlags flags =
            p.min > 0.0 && p.max / p.min >= 100.0 ? ImGuiSliderFlags_Logarithmic : 0;
        if (ImGui::SliderFloat(key.c_str(), &v, static_cast<float>(p.min),
                               static_cast<float>(p.max), "%.4g", flags))
            setNumber(values, p, v);
        break;
    }
    }
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("%s%s%s", std::string(p.description).c_str(), p.unit.empty() ? "" : " (",
                          p.unit.empty() ? "" : (std::string(p.unit) + ")").c_str());
}

void parameterPanel(ViewerState& s) {
    std::vector<std::string_view> families;
    std::vector<Technique> shown{s.options.technique};
    if (s.compare)
        shown.push_back(s.techniqueB);
    for (Technique t : shown) {
        for (std::string_view f : findTechnique(techniqueName(t)).families)
            if (std::find(families.begin(), families.end(), f) == families.end())
                families.push_back(f);
    }
    for (std::string_view family : families) {
        if (!ImGui::TreeNodeEx(std::string(family).c_str(), ImGuiTreeNodeFlags_DefaultOpen))
            continue;
        for (const ParameterInfo& p : allParameters())
            if (p.key.substr(0, p.key.find('.')) == family)
                parameterWidget(s.options.parameters, p);
        ImGui::TreePop();
    }
    if (ImGui::Button("reset to defaults"))
        s.options.parameters = ParameterValues();
}

void lightPanel(ViewerState& s) {
    for (size_t i = 0; i < s.lights.size(); ++i) {
        Light& l = s.lights[i];
        const char* kind = l.type == LightType::Directional ? "directional"
                           : l.type == LightType::Spot      ? "spot"
                                                            : "point";
        ImGui::PushID(static_cast<int>(i));
        if (ImGui::TreeNodeEx("light", ImGuiTreeNodeFlags_DefaultOpen, "%zu: %s %s", i, kind,
                              l.name.c_str())) {
            if (l.type == LightType::Directional) {
                ImGui::SliderFloat("angular diameter (deg)", &l.angularDiameter, 0.0f, 30.0f,
                                   "%.3f");
            } else {
                ImGui::DragFloat("radius", &l.radius, 0.005f, 0.0f, 1e4f, "%.4g");
                ImGui::DragFloat3("position", &l.position.x, 0.02f);
            }
            if (l.type != LightType::Point) {
                // The direction the light points, as azimuth and elevation (drag to turn it).
                const glm::vec3 d = glm::normalize(l.direction);
                float azimuth = glm::degrees(std::atan2(d.x, d.z));
                float elevation = glm::degrees(std::asin(std::clamp(d.y, -1.0f, 1.0f)));
                bool turned = ImGui::DragFloat("azimuth (deg)", &azimuth, 0.5f, -180.0f, 180.0f);
                turned |= ImGui::DragFloat("elevation (deg)", &elevation, 0.5f, -89.9f, 89.9f);
                if (turned) {
                    const float a = glm::radians(azimuth), e = glm::radians(elevation);
                    l.direction = {std::cos(e) * std::sin(a), std::sin(e),
                                   std::cos(e) * std::cos(a)};
                }
            }
            ImGui::TreePop();
        }
        ImGui::PopID();
    }
}

void cameraPanel(ViewerState& s, const Scene& scene) {
    int mode = s.cameraMode == CameraMode::Orbit ? 0 : 1;
    ImGui::RadioButton("orbit (left drag, wheel)", &mode, 0);
    ImGui::RadioButton("fly (WASD QE, right drag, Shift)", &mode, 1);
    s.cameraMode = mode == 0 ? CameraMode::Orbit : CameraMode::Fly;
    const std::string current = s.sceneCamera < 0 ? "automatic" : scene.cameras[s.sceneCamera].name;
    if (ImGui::BeginCombo("scene camera", current.c_str())) {
        if (ImGui::Selectable("automatic", s.sceneCamera < 0))
            s.takeSceneCamera = -1;
        for (size_t i = 0; i < scene.cameras.size(); ++i) {
            ImGui::PushID(static_cast<int>(i));
            const std::string& name = scene.cameras[i].name;
            if (ImGui::Selectable(name.empty() ? "(unnamed)" : name.c_str(),
                                  s.sceneCamera == static_cast<int>(i)))
                s.takeSceneCamera = static_cast<int>(i);
            ImGui::PopID();
        }
        ImGui::EndCombo();
    }
}

void timingPanel(ViewerState& s) {
    auto plot = [](const char* label, const std::deque<float>& h) {
        if (h.empty())
            return;
        const std::vector<float> values(h.begin(), h.end());
        ImGui::PlotLines(label, values.data(), static_cast<int>(values.size()), 0,
                         fmt::format("{:.3f} ms", values.back()).c_str(), 0.0f, FLT_MAX,
                         ImVec2(0, 36));
    };
    plot("frame (CPU)", s.frameHistory);
    for (const auto& [pass, history] : s.gpuHistory)
        plot(pass.c_str(), history);
}

} // namespace

void pushHistory(std::deque<float>& history, float value) {
    history.push_back(value);
    while (history.size() > kHistoryFrames)
        history.pop_front();
}

void drawPanels(ViewerState& s, const Scene& scene, const ViewerLimits& limits) {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    const float height = ImGui::GetIO().DisplaySize.y - 16.0f;
    ImGui::SetNextWindowSize(ImVec2(440, std::min(height, 760.0f)), ImGuiCond_FirstUseEver);
    ImGui::Begin("penumbra");
    ImGui::PushItemWidth(-ImGui::GetFontSize() * 13.0f); // room for the longest parameter name
    ImGui::TextUnformatted(s.status.empty() ? "Tab hides this window" : s.status.c_str());
    techniqueCombo("technique", s.options.technique);
    ImGui::Checkbox("A/B: a second technique right of the split", &s.compare);
    if (s.compare) {
        techniqueCombo("technique B", s.techniqueB);
        ImGui::SliderFloat("split", &s.split, 0.0f, 1.0f);
    }
    if (ImGui::BeginCombo("shadow map", std::to_string(s.options.shadowMapSize).c_str())) {
        for (uint32_t n = 128; n <= limits.maxShadowMapSize; n *= 2)
            if (ImGui::Selectable(std::to_string(n).c_str(), n == s.options.shadowMapSize))
                s.options.shadowMapSize = n;
        ImGui::EndCombo();
    }
    ImGui::Checkbox("vsync", &s.vsync);
    if (ImGui::CollapsingHeader("parameters", ImGuiTreeNodeFlags_DefaultOpen))
        parameterPanel(s);
    if (ImGui::CollapsingHeader("lights"))
        lightPanel(s);
    if (ImGui::CollapsingHeader("camera"))
        cameraPanel(s, scene);
    if (s.animated && ImGui::CollapsingHeader("time", ImGuiTreeNodeFlags_DefaultOpen))
        timePanel(s);
    if (ImGui::CollapsingHeader("show", ImGuiTreeNodeFlags_DefaultOpen))
        showPanel(s);
    if (ImGui::CollapsingHeader("timings (ms)", ImGuiTreeNodeFlags_DefaultOpen))
        timingPanel(s);
    ImGui::PopItemWidth();
    ImGui::End();
}

} // namespace penumbra::viewer
