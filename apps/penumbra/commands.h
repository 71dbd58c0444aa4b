#pragma once
// The sub-commands of the `penumbra` CLI (docs/cli.md). Each registers its options on the app
// (the shared groups from cli_options.h) and returns the action to run when it was chosen.
#include "cli_options.h"

#include <functional>

namespace penumbra::cli {

using Action = std::function<int()>;

Action addRenderCommand(CLI::App& app, const GlobalOptions& global);
Action addReferenceCommand(CLI::App& app, const GlobalOptions& global);
Action addCompareCommand(CLI::App& app, const GlobalOptions& global);
Action addBenchCommand(CLI::App& app, const GlobalOptions& global);
Action addViewCommand(CLI::App& app, const GlobalOptions& global);
Action addInfoCommand(CLI::App& app, const GlobalOptions& global);
Action addTechniquesCommand(CLI::App& app);
Action addTuneCommand(CLI::App& app, const GlobalOptions& global);
Action addSweepCommand(CLI::App& app, const GlobalOptions& global);
Action addMergeCommand(CLI::App& app, const GlobalOptions& global);

} // namespace penumbra::cli
