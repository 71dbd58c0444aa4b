#pragma once
// The sub-commands of the `penumbra` CLI (design.md §1). Each registers its options on the app
// and returns the action to run when it was chosen.
#include <CLI/CLI.hpp>

#include <functional>

namespace penumbra::cli {

struct GlobalOptions {
    int device = -1;
    bool validation = false; // also PENUMBRA_VALIDATION=1
};

using Action = std::function<int()>;

Action addRenderCommand(CLI::App& app, const GlobalOptions& global);
Action addInfoCommand(CLI::App& app, const GlobalOptions& global);
Action addTechniquesCommand(CLI::App& app);

} // namespace penumbra::cli
