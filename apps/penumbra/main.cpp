// penumbra: the command-line front end. Errors from user input end as one line,
// `error: <subject>: <what>`, and a non-zero exit code; nothing partial is left behind.
#include "cli_reference.h"
#include "commands.h"
#include "parse_errors.h"
#include "penumbra/error.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>

int main(int argc, char** argv) {
    using namespace penumbra;
    CLI::App app{"Penumbra: a real-time shadow renderer and shadow-technique lab (Vulkan 1.3)",
                 "penumbra"};
    app.set_version_flag("--version", PENUMBRA_VERSION);
    app.require_subcommand(1);
    app.fallthrough();
    cli::GlobalOptions global;
    const char* env = std::getenv("PENUMBRA_VALIDATION");
    global.validation = env && std::strcmp(env, "0") != 0 && *env;
    app.add_option("--device", global.device,
                   "Vulkan device index from `penumbra info` (default: a GPU if any, else the "
                   "software rasterizer)")
        ->type_name("N");
    app.add_option("--max-file-size", global.maxFileSize,
                   "largest glTF file, and file it references, that is read (default 1 GiB)")
        ->type_name("BYTES")
        ->check(CLI::PositiveNumber);
    app.add_option("--max-triangles", global.maxTriangles,
                   "most triangles a glTF scene may have once instanced meshes are copied per "
                   "node")
        ->type_name("N")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_flag("--validation", global.validation,
                 "the Khronos validation layer and a debug messenger; any validation error fails "
                 "the command and writes nothing (`PENUMBRA_VALIDATION=1` does the same)");

    const std::pair<const char*, cli::Action> commands[] = {
        {"render", cli::addRenderCommand(app, global)},
        {"reference", cli::addReferenceCommand(app, global)},
        {"compare", cli::addCompareCommand(app, global)},
        {"bench", cli::addBenchCommand(app, global)},
        {"tune", cli::addTuneCommand(app, global)},
        {"sweep", cli::addSweepCommand(app, global)},
        {"merge", cli::addMergeCommand(app, global)},
        {"view", cli::addViewCommand(app, global)},
        {"info", cli::addInfoCommand(app, global)},
        {"techniques", cli::addTechniquesCommand(app)},
        {"cli-reference", cli::addCliReferenceCommand(app)}};
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::RequiredError& e) {
        std::vector<std::string> names;
        for (const auto& [name, action] : commands)
            names.emplace_back(name);
        // What was left unparsed: the first word that is not an option names the command meant.
        std::string given;
        for (const std::string& word : app.remaining())
            if (given.empty() && word.rfind('-', 0) != 0)
                given = word;
        const bool noCommand = std::string_view(e.what()) == "A subcommand is required";
        std::fprintf(stderr, "error: %s\n",
                     noCommand ? cli::missingCommandLine(given, names).c_str()
                               : cli::parseErrorLine(e.what()).c_str());
        return 2;
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "error: %s\n", cli::parseErrorLine(e.what()).c_str());
        return 2;
    }
    try {
        for (const auto& [name, action] : commands)
            if (app.got_subcommand(name))
                return action();
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 3;
    }
    return 2;
}
