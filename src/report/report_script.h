#pragma once
// report.html's interactive parts, inline (the page stays one offline file): the table sorted
// by a clicked header, and the image comparer (two of the truth, each row's visibility, heat map
// and lit image, a slider between them, zoom to pixels around a clicked point, the values under
// the cursor). The comparer reads the images the page already holds, so nothing is embedded
// twice; without scripts the page still shows every table, plot and image.
#include <string_view>

namespace penumbra {

// The comparer's markup (its controls and canvas; the script fills the choices).
extern const std::string_view kComparerHtml;
// The script, for a <script> element at the end of the body.
extern const std::string_view kReportScript;
// The styles of the table's groups, the plots' switch and legend, and the comparer.
extern const std::string_view kReportInteractiveStyle;

} // namespace penumbra
