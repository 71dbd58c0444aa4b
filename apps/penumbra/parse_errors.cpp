#include "parse_errors.h"

#include <fmt/format.h>
#include <regex>

namespace penumbra::cli {
namespace {

std::string values(const std::string& count) {
    return count + (count == "1" ? " value" : " values");
}

} // namespace

std::string parseErrorLine(std::string_view what) {
    const std::string text(what);
    std::smatch m;
    // CLI11's wording (CLI/Error.hpp): ConversionError, ArgumentMismatch::AtMost and AtLeast,
    // ExtrasError.
    if (std::regex_match(text, m, std::regex("Could not convert: (\\S+) = (.*)")))
        return fmt::format("{}: '{}' is not a value it takes (--help gives its kind)", m[1].str(),
                           m[2].str());
    // CLI::PositiveNumber's range ends at the largest double, printed in full.
    if (std::regex_match(text, m,
                         std::regex("(\\S+): Value (.*) not in range \\S+ to \\d{100,}\\.\\d*")))
        return fmt::format("{}: '{}' is not a number above zero", m[1].str(), m[2].str());
    if (std::regex_match(text, m, std::regex("(\\S+): Value (.*) not in range (\\S+) to (\\S+)")))
        return fmt::format("{}: '{}' is outside {}..{}", m[1].str(), m[2].str(), m[3].str(),
                           m[4].str());
    // CLI::CheckedTransformer: "Check xyz value in {both->2,exr->1} OR {2,1} FAILED".
    if (std::regex_match(text, m,
                         std::regex("(\\S+): Check (.*) value in \\{(.*)\\} OR \\{.*\\} FAILED"))) {
        std::string names;
        const std::string pairs = m[3].str();
        const std::regex pair("([^,]+)->[^,]*");
        for (std::sregex_iterator it(pairs.begin(), pairs.end(), pair), end; it != end; ++it)
            names += (names.empty() ? "" : ", ") + (*it)[1].str();
        return fmt::format("{}: '{}' is not one of {}", m[1].str(), m[2].str(), names);
    }
    if (std::regex_match(text, m, std::regex("(\\S+): (.*) not in \\{(.*)\\}")))
        return fmt::format("{}: '{}' is not one of {}", m[1].str(), m[2].str(),
                           std::regex_replace(m[3].str(), std::regex(","), ", "));
    if (std::regex_match(text, m, std::regex("(\\S+): At Most 1 required but received (\\d+)")))
        return fmt::format("{}: given {}; it takes one", m[1].str(), values(m[2].str()));
    if (std::regex_match(text, m,
                         std::regex("(\\S+): At Most (\\d+) required but received (\\d+)")))
        return fmt::format("{}: given {}; it takes at most {}", m[1].str(), values(m[3].str()),
                           m[2].str());
    if (std::regex_match(text, m,
                         std::regex("(\\S+): At least (\\d+) required but received (\\d+)")))
        return fmt::format("{}: given {}; it takes at least {}", m[1].str(), values(m[3].str()),
                           m[2].str());
    if (std::regex_match(text, m, std::regex("The following argument was not expected: (.*)")))
        return fmt::format("{}: not an argument of this command (--help lists them)", m[1].str());
    if (std::regex_match(text, m, std::regex("The following arguments were not expected: (.*)")))
        return fmt::format("not arguments of this command: {} (--help lists them)", m[1].str());
    return text;
}

std::string missingCommandLine(std::string_view given, const std::vector<std::string>& commands) {
    std::string list;
    for (const std::string& c : commands)
        list += (list.empty() ? "" : ", ") + c;
    return given.empty() ? fmt::format("a command is required: {} (penumbra --help)", list)
                         : fmt::format("'{}' is not a command: {} (penumbra --help)", given, list);
}

} // namespace penumbra::cli
