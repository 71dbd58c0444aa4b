#pragma once
// Stored figures as data (docs/testing.md, "Baselines"): one JSON file per set-up under
// tests/baselines/TABLE/SETUP.json, {"setup": "...", "rows": {ROW: {FIGURE: value}}}. A test
// reads its set-up's figures from there; with PENUMBRA_WRITE_BASELINES=DIR it writes what it
// measured to DIR/TABLE/SETUP.json instead of comparing (`make baselines` does this, then
// tools/baselines.py shows every figure that moved and refuses a worse one nobody accepted).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <string>

namespace penumbra::test {

using Figures = std::map<std::string, double>;

class BaselineTable {
public:
    // `root`: the folder of the tables (tests/baselines of the source tree).
    BaselineTable(std::string table, std::string setup, std::string about,
                  const std::filesystem::path& root = std::filesystem::path(PENUMBRA_SOURCE_DIR) /
                                                      "tests/baselines")
        : table_(std::move(table)), setup_(std::move(setup)), about_(std::move(about)) {
        if (const char* dir = std::getenv("PENUMBRA_WRITE_BASELINES"))
            writeTo_ = std::filesystem::path(dir) / table_ / (setup_ + ".json");
        const std::filesystem::path stored = root / table_ / (setup_ + ".json");
        std::ifstream in(stored);
        if (!in) {
            if (!writeTo_)
                ADD_FAILURE() << stored << ": no stored figures (run `make baselines`)";
            return;
        }
        const nlohmann::json file = nlohmann::json::parse(in);
        for (const auto& [row, figures] : file.at("rows").items())
            for (const auto& [name, value] : figures.items())
                stored_[row][name] = value.get<double>();
    }

    BaselineTable(const BaselineTable&) = delete;
    BaselineTable& operator=(const BaselineTable&) = delete;

    // Writing: the figures go to the file and nothing is compared.
    bool writing() const { return writeTo_.has_value(); }

    // The stored figures of `row`, or nullptr (a failure unless writing: every measured row has
    // stored figures). Each row may be asked for once.
    const Figures* stored(const std::string& row) {
        asked_.insert(row);
        const auto it = stored_.find(row);
        if (it != stored_.end())
            return &it->second;
        if (!writing())
            ADD_FAILURE() << where() << ": row " << row
                          << " has no stored figures (run `make baselines`)";
        return nullptr;
    }

    void record(const std::string& row, const Figures& figures) { measured_[row] = figures; }

    // Writes the file when writing; otherwise a stored row nobody measured fails (the table
    // names every row).
    ~BaselineTable() {
        if (!writeTo_) {
            for (const auto& [row, figures] : stored_)
                if (!asked_.contains(row))
                    ADD_FAILURE() << where() << ": stored row " << row << " was not measured";
            return;
        }
        nlohmann::json rows = nlohmann::json::object();
        for (const auto& [row, figures] : measured_)
            for (const auto& [name, value] : figures)
                rows[row][name] = std::round(value * 1e6) / 1e6;
        std::filesystem::create_directories(writeTo_->parent_path());
        std::ofstream(*writeTo_) << nlohmann::json{{"setup", about_}, {"rows", rows}}.dump(1)
                                 << "\n";
    }

private:
    std::string where() const { return "tests/baselines/" + table_ + "/" + setup_ + ".json"; }

    std::string table_, setup_, about_;
    std::optional<std::filesystem::path> writeTo_;
    std::map<std::string, Figures> stored_, measured_;
    std::set<std::string> asked_;
};

} // namespace penumbra::test
