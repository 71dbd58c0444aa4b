// The maps a technique's visibility pass reads (shadows::visibilitySlots): the module lists them,
// float ones fill shadowMaps' slots and integer ones shadowTables', each kind in the order
// listed; what is left holds the depth map or a placeholder. The frame and the probe bind exactly
// these (render::FilteredBindings::of).
#include "penumbra/settings.h"
#include "shadows/technique.h"

#include <gtest/gtest.h>

using namespace penumbra;
using namespace penumbra::shadows;

namespace {

// A module of maps only: what visibilitySlots reads.
TechniqueModule mapsOnly(std::vector<std::string_view> listed) {
    return {.info = {.name = "scratch"},
            .maps = {{.name = "a", .format = MapFormat::R32F},
                     {.name = "table", .format = MapFormat::RG32UI},
                     {.name = "b", .format = MapFormat::RGBA16},
                     {.name = "c", .format = MapFormat::RG32F},
                     {.name = "d", .format = MapFormat::RGBA32F},
                     // its format follows a parameter: integers under the default
                     {.name = "follows",
                      .format = MapFormat::R32F,
                      .formatFor = [](const ParameterValues&) { return MapFormat::R32UI; }}},
            .visibilityMaps = std::move(listed)};
}

} // namespace

TEST(VisibilitySlots, FloatAndIntegerMapsFillTheirOwnSlotsInTheOrderListed) {
    const ParameterValues defaults;
    const VisibilitySlots slots =
        visibilitySlots(mapsOnly({"table", "b", kDepthMap, "a", "follows"}), defaults);
    EXPECT_EQ(slots.floats[0], "b");
    EXPECT_EQ(slots.floats[1], kDepthMap);
    EXPECT_EQ(slots.floats[2], "a");
    EXPECT_EQ(slots.floats[3], kDepthMap) << "a float slot left holds the depth map";
    EXPECT_EQ(slots.integers[0], "table");
    EXPECT_EQ(slots.integers[1], "follows") << "the format its parameters give, not the default";
    EXPECT_EQ(slots.integers[2], "");
    EXPECT_EQ(slots.integers[3], "") << "an integer slot left holds the placeholder";
}

TEST(VisibilitySlots, AModuleThatReadsNoDepthMapRepeatsItsFirstMap) {
    // Its depth map is then free once its own passes have read it (transient memory).
    const VisibilitySlots slots = visibilitySlots(mapsOnly({"b", "table", "a"}), ParameterValues{});
    EXPECT_FALSE(slots.readsDepthMap);
    EXPECT_EQ(slots.floats, (std::array<std::string_view, TECH_MAX_MAPS>{"b", "a", "b", "b"}));
    EXPECT_TRUE(visibilitySlots(mapsOnly({"a", kDepthMap}), ParameterValues{}).readsDepthMap);
    EXPECT_TRUE(visibilitySlots(mapsOnly({kDepthMap, "a"}), ParameterValues{}).readsDepthMap);
    EXPECT_TRUE(visibilitySlots(mapsOnly({"table"}), ParameterValues{}).readsDepthMap)
        << "no float map: shadowMap is the depth map";
    for (const TechniqueModule* m : allModules()) { // pcf's comparison sampler reads it
        const std::string_view name = m->info.name;
        const bool reads = visibilitySlots(*m, ParameterValues{}).readsDepthMap;
        if (name == "hard" || name == "pcf" || name == "pcss" || name == "smrt") {
            EXPECT_TRUE(reads) << name;
        }
        if (name == "vsm" || name == "second-depth") {
            EXPECT_FALSE(reads) << name;
        }
    }
}

TEST(VisibilitySlots, OneIntegerMapLeavesTheDepthMapFirst) {
    // smrt's bounds, the summed-area tables: the depth map stays at shadowMaps[0].
    const VisibilitySlots slots = visibilitySlots(mapsOnly({"table"}), ParameterValues{});
    for (std::string_view f : slots.floats)
        EXPECT_EQ(f, kDepthMap);
    EXPECT_EQ(slots.integers[0], "table");
}

TEST(VisibilitySlots, EveryModuleFitsItsSlots) {
    const ParameterValues defaults;
    for (const TechniqueModule* m : allModules()) {
        const VisibilitySlots slots = visibilitySlots(*m, defaults);
        if (m->visibilityMaps.empty()) { // a field's tracer: the 1x1 depth map stands in
            EXPECT_TRUE(slots.readsDepthMap) << m->info.name;
            EXPECT_EQ(slots.floats[0], kDepthMap) << m->info.name;
            continue;
        }
        // What the module lists is where the shaders look first.
        const std::string_view first = m->visibilityMaps.front();
        EXPECT_TRUE(slots.floats[0] == first || slots.integers[0] == first) << m->info.name;
    }
}

TEST(VisibilitySlots, TooManyMapsOrAnUndeclaredOneIsAProgrammerError) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(visibilitySlots(mapsOnly({"a", "b", "c", "d", kDepthMap}), ParameterValues{}),
                 "reads more maps of a kind than TECH_MAX_MAPS");
    EXPECT_DEATH(visibilitySlots(mapsOnly({"a", "e"}), ParameterValues{}),
                 "reads a map it does not declare: e");
}

// Screen passes (ScreenPassDecl): every registered module's run as declared; one the frame
// cannot run is refused where the module is read, not when a frame is built.
namespace {

ScreenPassDecl screenPass(bool fills, std::string_view parameter = "x",
                          std::string_view results = {}) {
    ScreenPassDecl pass;
    pass.name = "pass";
    pass.shader = "pass.comp";
    pass.results = results;
    pass.fillsCheckerboard = fills;
    pass.parameter = parameter;
    return pass;
}

std::vector<ScreenPassDecl> fillSecond(const ParameterValues&) {
    std::vector<ScreenPassDecl> passes;
    passes.push_back(screenPass(false));
    passes.push_back(screenPass(true));
    return passes;
}
std::vector<ScreenPassDecl> fillUnnamed(const ParameterValues&) {
    return std::vector<ScreenPassDecl>(1, screenPass(true, ""));
}
std::vector<ScreenPassDecl> fillChoosy(const ParameterValues&) {
    ScreenPassDecl pass = screenPass(true);
    pass.runsFor = [](const ParameterValues&, uint32_t) { return false; };
    return std::vector<ScreenPassDecl>(1, pass);
}
std::vector<ScreenPassDecl> resultsElsewhere(const ParameterValues&) {
    return std::vector<ScreenPassDecl>(1, screenPass(false, "x", "rows"));
}
std::vector<ScreenPassDecl> fillThenScratch(const ParameterValues&) {
    std::vector<ScreenPassDecl> passes;
    passes.push_back(screenPass(true));
    passes.push_back(screenPass(false, "x", kScreenScratch));
    return passes;
}

TechniqueModule withScreenPasses(std::vector<ScreenPassDecl> (*passes)(const ParameterValues&)) {
    return {.info = {.name = "scratch"}, .screenPasses = passes};
}

} // namespace

TEST(ScreenPasses, EveryModulesAreSoundAndBadDeclarationsAreProgrammerErrors) {
    for (const TechniqueModule* m : allModules()) {
        const std::vector<ScreenPassDecl> passes = screenPassesOf(*m, ParameterValues{});
        const ScreenPassDecl* fill = checkerboardFill(passes);
        EXPECT_TRUE(fill == nullptr || fill == &passes.front()) << m->info.name;
    }
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(screenPassesOf(withScreenPasses(fillSecond), ParameterValues{}),
                 "a checkerboard's fill comes first");
    EXPECT_DEATH(screenPassesOf(withScreenPasses(fillUnnamed), ParameterValues{}),
                 "names its parameter");
    EXPECT_DEATH(screenPassesOf(withScreenPasses(fillChoosy), ParameterValues{}),
                 "runs for every light");
    EXPECT_DEATH(screenPassesOf(withScreenPasses(resultsElsewhere), ParameterValues{}),
                 "does not make: rows");
    // A fill first, then a pass on the scratch: sound, and the fill is found.
    const std::vector<ScreenPassDecl> passes =
        screenPassesOf(withScreenPasses(fillThenScratch), ParameterValues{});
    ASSERT_EQ(passes.size(), 2u);
    EXPECT_EQ(checkerboardFill(passes), &passes[0]);
    EXPECT_EQ(checkerboardFill(std::span(passes).subspan(1)), nullptr);
}
