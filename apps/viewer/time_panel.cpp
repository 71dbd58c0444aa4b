// The "time" section of the viewer's interface, for an animated scene: play and pause (Space
// does the same), and a slider that scrubs the time (moving it pauses, so that the pose holds
// where it is put). The session poses the scene at whatever time the state then holds.
#include "viewer_state.h"

#include <imgui.h>

#include <algorithm>

namespace penumbra::viewer {

void timePanel(ViewerState& s) {
    if (ImGui::Button(s.playing ? "pause" : "play"))
        s.playing = !s.playing;
    ImGui::SameLine();
    if (ImGui::Button("to the start"))
        s.time = 0.0;
    // Without an animation's length (lights that orbit), the slider covers a minute.
    const float end = static_cast<float>(s.duration > 0.0 ? s.duration : 60.0);
    float time = static_cast<float>(std::min(s.time, double(end)));
    if (ImGui::SliderFloat("time (s)", &time, 0.0f, end, "%.3f")) {
        s.time = time;
        s.playing = false;
    }
    if (s.animation.empty())
        ImGui::TextUnformatted("lights that orbit; no animation");
    else
        ImGui::Text("animation '%s', %.3f s", s.animation.c_str(), s.duration);
}

} // namespace penumbra::viewer
