#include "scene/timeline_range.h"

#include "penumbra/error.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>

namespace penumbra {
namespace {

double number(std::string_view text, std::string_view whole) {
    double value = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc{} || end != text.data() + text.size() || !std::isfinite(value))
        throw InputError("--timeline",
                         fmt::format("'{}' is not START:END:STEP in seconds ('{}' is not a "
                                     "finite number)",
                                     whole, text));
    return value;
}

} // namespace

double Timeline::at(size_t frame) const {
    const double exact = start + step * static_cast<double>(frame);
    return std::strtod(fmt::format("{:.12g}", exact).c_str(), nullptr);
}

Timeline parseTimeline(std::string_view text) {
    const size_t a = text.find(':'), b = a == std::string_view::npos ? a : text.find(':', a + 1);
    if (b == std::string_view::npos || text.find(':', b + 1) != std::string_view::npos)
        throw InputError("--timeline", fmt::format("'{}' is not START:END:STEP in seconds", text));
    Timeline t{.start = number(text.substr(0, a), text),
               .end = number(text.substr(a + 1, b - a - 1), text),
               .step = number(text.substr(b + 1), text)};
    if (t.start < 0.0 || t.end < t.start || !(t.step > 0.0))
        throw InputError("--timeline",
                         fmt::format("'{}': START must be 0 or more, END at least START and STEP "
                                     "above 0",
                                     text));
    const double frames = std::floor((t.end - t.start) / t.step + 1e-6) + 1.0;
    if (!(frames <= static_cast<double>(kMaxTimelineFrames)))
        throw InputError("--timeline", fmt::format("'{}' is {} frames; at most {}", text, frames,
                                                   kMaxTimelineFrames));
    t.frames = static_cast<size_t>(frames);
    return t;
}

} // namespace penumbra
