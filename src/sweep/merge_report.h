#pragma once
// report.html of `penumbra merge`: one offline page (inline CSS and SVG, no script, no network)
// over a sweep: per scene and over the corpus, each technique setting's RMSE against its shadow
// passes' GPU time with the Pareto front, and a table of every metric with its 95% interval and
// rank, the costs and the devices; failed tasks listed with why.
#include "sweep/merge.h"

#include <string>

namespace penumbra::sweep {

std::string mergeHtml(const MergeResult& merged, const std::string& title);

} // namespace penumbra::sweep
