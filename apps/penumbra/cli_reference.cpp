#include "cli_reference.h"

#include "penumbra/settings.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <set>
#include <vector>

namespace penumbra::cli {
namespace {

// Markdown table cells hold no '|' and no line breaks.
std::string cell(std::string text) {
    std::string out;
    for (char c : text)
        out += c == '|' ? std::string("\\|") : c == '\n' ? std::string(" ") : std::string(1, c);
    return out;
}

// "-o, --output DIR": the option's names and, when it takes a value, its placeholder (the type
// name given at registration, e.g. DIR; CLI11's own, e.g. UINT, otherwise).
std::string optionNames(const CLI::Option& o) {
    if (!o.nonpositional()) {
        std::string name = o.get_name(true);
        std::transform(name.begin(), name.end(), name.begin(),
                       [](unsigned char c) { return char(std::toupper(c)); });
        return "`" + name + "`";
    }
    std::string names;
    for (const std::string& s : o.get_snames())
        names += (names.empty() ? "-" : ", -") + s;
    for (const std::string& l : o.get_lnames())
        names += (names.empty() ? "--" : ", --") + l;
    if (o.get_expected_max() != 0) {
        // CLI11 appends what a transform accepts ("FORMAT:value in {...}"); a placeholder's own
        // optional part ("AXIS[:POS]") stays.
        const std::string type = o.get_type_name();
        names += " " + type.substr(0, type.find(":value"));
    }
    return "`" + names + "`";
}

std::string defaultCell(const CLI::Option& o) {
    if (o.get_required())
        return "required";
    const std::string value = o.get_default_str();
    return value.empty() ? "" : "`" + value + "`";
}

void table(std::string& out, const std::vector<const CLI::Option*>& options) {
    out += "| option | default | meaning |\n| --- | --- | --- |\n";
    for (const CLI::Option* o : options)
        out += fmt::format("| {} | {} | {} |\n", optionNames(*o), cell(defaultCell(*o)),
                           cell(o->get_description()));
}

void region(std::string& out, const std::string& name, const std::string& body) {
    out += fmt::format("<!-- generated: {} -->\n{}<!-- end generated -->\n", name, body);
}

std::string anchorOf(const std::string& group) {
    std::string anchor;
    for (char c : group)
        if (std::isalnum(static_cast<unsigned char>(c)))
            anchor += char(std::tolower(static_cast<unsigned char>(c)));
        else if (c == ' ')
            anchor += '-';
    return anchor + "-options";
}

bool visible(const CLI::Option* o) {
    return !o->get_group().empty() && o->get_name() != "--help" && o->get_name() != "-h" &&
           o->get_lnames() != std::vector<std::string>{"help"};
}

// Every parameter `--set` takes, in the registry's order: its default, its range or choices, what
// it does and its unit.
std::string parameterTable() {
    std::string out =
        "| key | default | range | unit | meaning |\n| --- | --- | --- | --- | --- |\n";
    for (const ParameterInfo& p : allParameters()) {
        std::string value, range;
        if (p.type == ParameterType::Choice) {
            value = std::string(p.choices[static_cast<size_t>(p.defaultValue)]);
            for (std::string_view choice : p.choices)
                range += (range.empty() ? "" : ", ") + std::string(choice);
        } else if (p.type == ParameterType::Bool) {
            value = p.defaultValue != 0.0 ? "true" : "false";
            range = "true, false";
        } else {
            value = fmt::format("{}", p.defaultValue);
            range = fmt::format("{} .. {}", p.min, p.max);
        }
        out += fmt::format("| `{}` | {} | {} | {} | {} |\n", p.key, value, cell(range),
                           cell(std::string(p.unit)), cell(std::string(p.description)));
    }
    return out;
}

} // namespace

std::string cliReferenceMarkdown(const CLI::App& app) {
    const std::vector<std::string> shared = {kSceneGroup, kTechniqueGroup, kTruthGroup};
    std::string out;
    std::vector<const CLI::Option*> global;
    for (const CLI::Option* o : app.get_options(visible))
        if (o->get_lnames() != std::vector<std::string>{"version"})
            global.push_back(o);
    std::string body;
    table(body, global);
    region(out, "global", body);

    std::vector<std::pair<std::string, std::vector<const CLI::Option*>>> groups;
    for (const CLI::App* cmd : app.get_subcommands([](const CLI::App*) { return true; })) {
        if (cmd->get_group().empty())
            continue; // hidden, like this command
        std::vector<const CLI::Option*> own;
        std::vector<std::string> usedGroups, differing; // differing: "`--frames 20`"
        for (const CLI::Option* o : cmd->get_options(visible)) {
            const std::string& group = o->get_group();
            if (std::find(shared.begin(), shared.end(), group) == shared.end()) {
                own.push_back(o);
                continue;
            }
            if (std::find(usedGroups.begin(), usedGroups.end(), group) == usedGroups.end())
                usedGroups.push_back(group);
            auto known = std::find_if(groups.begin(), groups.end(),
                                      [&](const auto& g) { return g.first == group; });
            if (known == groups.end()) {
                groups.push_back({group, {}});
                known = groups.end() - 1;
            }
            const auto first =
                std::find_if(known->second.begin(), known->second.end(),
                             [&](const auto* k) { return k->get_name() == o->get_name(); });
            if (first == known->second.end())
                known->second.push_back(o); // documented with the first command's default
            else if ((*first)->get_default_str() != o->get_default_str())
                differing.push_back(fmt::format("`{} {}`", o->get_name(), o->get_default_str()));
        }
        body.clear();
        if (!own.empty())
            table(body, own);
        if (!usedGroups.empty()) {
            std::string links;
            for (size_t i = 0; i < usedGroups.size(); ++i) {
                std::string name = usedGroups[i];
                name[0] = char(std::tolower(static_cast<unsigned char>(name[0])));
                links += (i == 0                       ? ""
                          : i + 1 == usedGroups.size() ? " and "
                                                       : ", ") +
                         fmt::format("[{} options](#{})", name, anchorOf(usedGroups[i]));
            }
            std::string defaults;
            for (size_t i = 0; i < differing.size(); ++i)
                defaults += (i == 0 ? "; here the defaults are " : ", ") + differing[i];
            body += (own.empty() ? "" : "\n") + fmt::format("Also the {}{}.\n", links, defaults);
        }
        if (body.empty())
            body = "No options.\n";
        region(out, cmd->get_name(), body);
    }
    for (const auto& [group, options] : groups) {
        body.clear();
        table(body, options);
        region(out, anchorOf(group), body);
    }
    region(out, "parameters", parameterTable());
    return out;
}

Action addCliReferenceCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("cli-reference", "docs/cli.md's option tables");
    cmd->group(""); // hidden: a tool for the docs, not for users
    return [&app] {
        std::fputs(cliReferenceMarkdown(app).c_str(), stdout);
        return 0;
    };
}

} // namespace penumbra::cli
