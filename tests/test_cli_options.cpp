// The CLI's shared options (apps/penumbra/cli_options.cpp): list splitting, sweeps and their
// products, `--set` assembly onto a row, the row one `--technique` names and the frames of
// `--timeline`.
#include "cli_options.h"
#include "parse_errors.h"
#include "penumbra/error.h"
#include "scene/timeline_range.h"

#include <gtest/gtest.h>

using namespace penumbra;
using namespace penumbra::cli;

namespace {

// The subject of the InputError `f` throws ("" when it throws none).
template <class F>
std::string subjectOf(F&& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.subject();
    }
    return "";
}

} // namespace

TEST(CliOptions, ListsSplitAtEveryCommaAndRefuseEmptyItems) {
    EXPECT_EQ(splitList("hard", "--x"), std::vector<std::string>{"hard"});
    EXPECT_EQ(splitList("hard,pcf,pcss", "--x"), (std::vector<std::string>{"hard", "pcf", "pcss"}));
    for (const char* bad : {"", ",", "hard,", ",hard", "hard,,pcf"})
        EXPECT_EQ(subjectOf([&] { splitList(bad, "--techniques"); }), "--techniques") << bad;
}

TEST(CliOptions, SweepsAreCheckedAgainstTheParameterTableBeforeAnyRun) {
    const Sweep s = parseSweep("pcf.size=3,7,11");
    EXPECT_EQ(s.key, "pcf.size");
    EXPECT_EQ(s.values, (std::vector<std::string>{"3", "7", "11"}));
    for (const char* bad : {"pcf.size", "pcf.size=", "=3", "pcf.size=3,,7", "pcf.size=3,4",
                            "pcf.nope=3", "bias.constant=1"})
        EXPECT_EQ(subjectOf([&] { parseSweep(bad); }), "--sweep") << bad;
}

TEST(CliOptions, TheSweepProductHoldsEveryCombinationOnceTheFirstSweepSlowest) {
    EXPECT_EQ(sweepProduct({}), std::vector<Assignment>{{}});
    const Sweep sweeps[] = {{.key = "a", .values = {"1", "2"}},
                            {.key = "b", .values = {"x", "y", "z"}}};
    const std::vector<Assignment> runs = sweepProduct(sweeps);
    ASSERT_EQ(runs.size(), 6u);
    for (size_t i = 0; i < runs.size(); ++i) {
        ASSERT_EQ(runs[i].size(), 2u);
        EXPECT_EQ(runs[i][0].first, "a");
        EXPECT_EQ(runs[i][0].second, i < 3 ? "1" : "2") << i;
        EXPECT_EQ(runs[i][1].second, std::string(1, "xyz"[i % 3])) << i;
    }
}

TEST(CliOptions, ARowsOwnSettingsWinOverTheUsersSets) {
    const TechniqueRow row = rowNamed("pcf[box3]", "--technique");
    const std::string sets[] = {"pcf.size=7", "bias.slope=1.5"};
    const RenderOptions o = optionsFor({}, row, sets);
    EXPECT_EQ(o.technique, Technique::Pcf);
    EXPECT_EQ(o.parameters.number("pcf.size"), 3.0); // the row is what its name says
    EXPECT_EQ(o.parameters.number("bias.slope"), 1.5);
    const std::string bad[] = {"bias.slope=-1"};
    EXPECT_EQ(subjectOf([&] { optionsFor({}, row, bad); }), "--set");
    RenderOptions zero;
    zero.width = 0;
    EXPECT_THROW(optionsFor(zero, row, {}), InputError);
}

TEST(CliOptions, OneTechniqueNamesOneRowWithItsLayers) {
    const TechniqueRow plain = rowNamed("pcf", "--technique");
    EXPECT_EQ(plain.technique, Technique::Pcf);
    EXPECT_TRUE(plain.sets.empty()); // the technique at its defaults, not its first variant
    const TechniqueRow layered = rowNamed("pcf[box3]+contact", "--technique");
    EXPECT_EQ(layered.name, "pcf[box3]+contact");
    EXPECT_EQ(layered.layers, std::vector<std::string>{"contact"});
    EXPECT_FALSE(layered.sets.empty());
    EXPECT_EQ(rowNamed("hard+contact", "--technique").layers, std::vector<std::string>{"contact"});
    // "pcf+contact" is pcf's defaults row with the layer, as "hard+contact" is hard's.
    const TechniqueRow pcfLayered = rowNamed("pcf+contact", "--technique");
    EXPECT_TRUE(pcfLayered.sets.empty());
    EXPECT_EQ(pcfLayered.layers, std::vector<std::string>{"contact"});
    for (const char* bad : {"nope", "pcf[nope]", "hard+nope", "pcf[box3]+", "hard,pcf"})
        EXPECT_EQ(subjectOf([&] { rowNamed(bad, "--tech"); }), "--tech") << bad;
}

// CLI11's messages reworded: the option first, then what is wrong; any other message unchanged.
TEST(CliOptions, ParseErrorsNameTheOptionFirst) {
    EXPECT_EQ(parseErrorLine("Could not convert: --width = abc"),
              "--width: 'abc' is not a value it takes (--help gives its kind)");
    EXPECT_EQ(parseErrorLine("--max-triangles: Value 0 not in range 0.000000 to 1" +
                             std::string(308, '7') + ".000000"),
              "--max-triangles: '0' is not a number above zero");
    EXPECT_EQ(parseErrorLine("--path-frames: Value 1 not in range 2 to 64"),
              "--path-frames: '1' is outside 2..64");
    EXPECT_EQ(parseErrorLine("--format: Check xyz value in {both->2,exr->1,pfm->0} OR {2,1,0} "
                             "FAILED"),
              "--format: 'xyz' is not one of both, exr, pfm");
    EXPECT_EQ(parseErrorLine("--emit: pbs not in {slurm,kubernetes}"),
              "--emit: 'pbs' is not one of slurm, kubernetes");
    EXPECT_EQ(parseErrorLine("--frames: At Most 1 required but received 2"),
              "--frames: given 2 values; it takes one");
    EXPECT_EQ(parseErrorLine("--pair: At Most 2 required but received 3"),
              "--pair: given 3 values; it takes at most 2");
    EXPECT_EQ(parseErrorLine("--pair: At least 2 required but received 1"),
              "--pair: given 1 value; it takes at least 2");
    EXPECT_EQ(parseErrorLine("The following argument was not expected: --scene"),
              "--scene: not an argument of this command (--help lists them)");
    EXPECT_EQ(parseErrorLine("The following arguments were not expected: a b"),
              "not arguments of this command: a b (--help lists them)");
    EXPECT_EQ(parseErrorLine("--output is required"), "--output is required");
}

TEST(CliOptions, AMissingOrUnknownCommandListsTheCommands) {
    const std::vector<std::string> commands{"render", "compare"};
    EXPECT_EQ(missingCommandLine("", commands),
              "a command is required: render, compare (penumbra --help)");
    EXPECT_EQ(missingCommandLine("rendr", commands),
              "'rendr' is not a command: render, compare (penumbra --help)");
}

TEST(CliOptions, ATimelineHoldsItsEndsAndAtMostItsFrameLimit) {
    const Timeline t = parseTimeline("0.5:1.5:0.25");
    EXPECT_EQ(t.start, 0.5);
    EXPECT_EQ(t.end, 1.5);
    EXPECT_EQ(t.step, 0.25);
    EXPECT_EQ(t.frames, 5u); // 0.5, 0.75, 1, 1.25, 1.5
    EXPECT_EQ(t.at(0), 0.5);
    EXPECT_EQ(t.at(4), 1.5);
    // Steps that do not add up exactly in binary still reach END, and are written as typed.
    const Timeline tenths = parseTimeline("0:0.3:0.1");
    EXPECT_EQ(tenths.frames, 4u);
    EXPECT_EQ(tenths.at(3), 0.3);
    EXPECT_EQ(parseTimeline("2:2:1").frames, 1u);
    EXPECT_EQ(parseTimeline("0:9999:1").frames, kMaxTimelineFrames);
    for (const char* bad :
         {"0:10000:1", "-1:1:0.5", "1:0.5:0.1", "0:1:0", "0:1:-0.5", "0:1x:0.5", "0:1:0.5s",
          " 0:1:0.5", "0:1", "0:1:0.5:1", "0::0.5", "0:inf:1", "0x1:2:1"})
        EXPECT_EQ(subjectOf([&] { parseTimeline(bad); }), "--timeline") << bad;
}
