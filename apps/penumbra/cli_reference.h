#pragma once
// `penumbra cli-reference`: docs/cli.md's option tables, made from the options as the commands
// register them, so the reference cannot drift from the CLI (tools/cli_docs.py splices them
// into the page; a test fails when the page is stale).
#include "commands.h"

#include <string>

namespace penumbra::cli {

// Every generated region of docs/cli.md, each between `<!-- generated: NAME -->` and
// `<!-- end generated -->` lines: "global", each command's own options, each shared group.
std::string cliReferenceMarkdown(const CLI::App& app);

// The hidden command that prints cliReferenceMarkdown of the whole app.
Action addCliReferenceCommand(CLI::App& app);

} // namespace penumbra::cli
