#include "bias.h"
#include "params_moments.h"
#include "penumbra/error.h"
#include "penumbra/settings.h"
#include "shadows/technique.h"
#include "translucent.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <span>

using namespace penumbra;

TEST(Parameters, DefaultsComeFromTheTable) {
    const ParameterValues v;
    for (const ParameterInfo& p : allParameters())
        EXPECT_EQ(v.number(p.key), p.defaultValue);
}

TEST(Parameters, SetParsesAndRangeChecks) {
    ParameterValues v;
    v.assign("bias.slope=1.5");
    EXPECT_DOUBLE_EQ(v.number("bias.slope"), 1.5);
    EXPECT_THROW(v.assign("bias.slope=-1"), InputError);   // below range
    EXPECT_THROW(v.assign("bias.slope=1e9"), InputError);  // above range
    EXPECT_THROW(v.assign("bias.slope=abc"), InputError);  // not a number
    EXPECT_THROW(v.assign("bias.slope=1.5x"), InputError); // trailing junk
    EXPECT_THROW(v.assign("bias.slope=nan"), InputError);  // not finite
    EXPECT_THROW(v.assign("bias.slope="), InputError);     // empty
    EXPECT_THROW(v.assign("bias.slope"), InputError);      // no '='
    EXPECT_THROW(v.assign("pcf.nonsense=3"), InputError);  // unknown key
    EXPECT_DOUBLE_EQ(v.number("bias.slope"), 1.5);         // failures change nothing
}

TEST(Parameters, ErrorsNameTheOptionAndTheKey) {
    ParameterValues v;
    try {
        v.assign("bias.constant=7");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.subject(), "--set");
        EXPECT_NE(std::string(e.what()).find("bias.constant"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos);
    }
}

TEST(Techniques, LookupByName) {
    EXPECT_EQ(findTechnique("hard").id, Technique::Hard);
    EXPECT_THROW(findTechnique("nonsense"), InputError);
}

TEST(Techniques, ComparisonRowsNameEachRowOnce) {
    // "pcss" brings pcss and pcss[fast]; naming pcss[fast] again, or pcss twice, adds nothing.
    std::vector<std::string> names;
    for (const TechniqueRow& row : comparisonRows("pcss,pcss[fast],hard,pcss"))
        names.push_back(row.name);
    EXPECT_EQ(names, (std::vector<std::string>{"pcss", "pcss[fast]", "hard"}));
    names.clear();
    for (const TechniqueRow& row : comparisonRows("pcf[box7],pcf[box3]"))
        names.push_back(row.name);
    EXPECT_EQ(names, (std::vector<std::string>{"pcf[box7]", "pcf[box3]"}));
}

TEST(Techniques, ComparisonRowsCarryTheLayersNamedAfterThem) {
    const std::vector<TechniqueRow> rows = comparisonRows("pcf[box3]+contact,hard");
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[0].name, "pcf[box3]+contact");
    EXPECT_EQ(rows[0].layers, std::vector<std::string>{"contact"});
    EXPECT_EQ(rows[1].name, "hard");
    EXPECT_TRUE(rows[1].layers.empty());
    // A technique's name with a layer: each of its rows with the layer, its defaults' first.
    const std::vector<TechniqueRow> pcfRows = comparisonRows("pcf+contact");
    ASSERT_GT(pcfRows.size(), 2u);
    EXPECT_EQ(pcfRows[0].name, "pcf+contact");
    EXPECT_TRUE(pcfRows[0].sets.empty());
    for (size_t i = 1; i < pcfRows.size(); ++i) {
        EXPECT_TRUE(pcfRows[i].name.starts_with("pcf[")) << pcfRows[i].name;
        EXPECT_TRUE(pcfRows[i].name.ends_with("]+contact")) << pcfRows[i].name;
        EXPECT_EQ(pcfRows[i].layers, std::vector<std::string>{"contact"});
    }
    EXPECT_THROW(comparisonRows("hard+nonsense"), InputError);
    EXPECT_THROW(comparisonRows("hard+"), InputError);
    // The default list: every row, then each layer's own rows with it.
    std::vector<std::string> names;
    for (const TechniqueRow& row : comparisonRows(""))
        names.push_back(row.name);
    EXPECT_NE(std::find(names.begin(), names.end(), "hard+contact"), names.end());
    EXPECT_NE(std::find(names.begin(), names.end(), "pcf[box3]+contact"), names.end());
    EXPECT_EQ(std::find(names.begin(), names.end(), "hard+contact"), names.end() - 2);
}

TEST(Techniques, ARowRunsExactlyTheLayersItNames) {
    const TechniqueRow plain = comparisonRows("hard")[0];
    const TechniqueRow layered = comparisonRows("hard+contact")[0];
    // Named, the layer gets its row setting when the caller left it off (a share of the scene's
    // radius), and keeps the caller's otherwise; not named, it is off.
    ParameterValues v;
    applyRow(layered, v, 10.0);
    EXPECT_NEAR(v.number("contact.length"), 0.2, 1e-9);
    v.assign("contact.length=0.5");
    applyRow(layered, v, 10.0);
    EXPECT_EQ(v.number("contact.length"), 0.5);
    applyRow(plain, v, 10.0);
    EXPECT_EQ(v.number("contact.length"), 0.0);
    // The translucent layer's row: the coloured map (docs/translucency.md, "Which method"),
    // unless the caller names a method.
    const TechniqueRow translucent = comparisonRows("hard+translucent")[0];
    ParameterValues t;
    applyRow(translucent, t, 10.0);
    EXPECT_EQ(t.number("translucent.method"), TRANSLUCENT_COLOURED);
    t.assign("translucent.method=moments");
    applyRow(translucent, t, 10.0);
    EXPECT_EQ(t.number("translucent.method"), TRANSLUCENT_MOMENTS);
    applyRow(plain, t, 10.0);
    EXPECT_EQ(t.number("translucent.method"), TRANSLUCENT_OFF);
}

// The technique list's two roles (PENUMBRA_DEFAULT_TECHNIQUE, PENUMBRA_COMPARED_TECHNIQUE): the
// plain depth test where none is named, and beside it in the viewer's split a technique whose
// penumbra follows the light's size.
TEST(Techniques, TheDefaultIsThePlainDepthTestAndTheComparedOneIsSoft) {
    EXPECT_EQ(techniqueName(kDefaultTechnique), "hard");
    EXPECT_EQ(RenderOptions{}.technique, kDefaultTechnique);
    const shadows::TechniqueModule& compared = shadows::moduleOf(kComparedTechnique);
    EXPECT_TRUE(compared.modelsLightSize) << compared.info.name;
    EXPECT_FALSE(compared.blockerSearchKey.empty()) << compared.info.name << ": no blocker views";
    EXPECT_NE(kComparedTechnique, kDefaultTechnique);
}

TEST(RenderOptions, ValidateRefusesZeroSizes) {
    RenderOptions o;
    EXPECT_NO_THROW(validate(o));
    o.width = 0;
    EXPECT_THROW(validate(o), InputError);
    o = {};
    o.shadowMapSize = 0;
    EXPECT_THROW(validate(o), InputError);
    o = {};
    o.frames = 0;
    EXPECT_THROW(validate(o), InputError);
}

namespace {

std::string text(double v) {
    return fmt::format("{}", v);
}

} // namespace

TEST(Parameters, EveryRangeIsInclusiveAtBothEndsAndNoWider) {
    for (const ParameterInfo& p : allParameters()) {
        if (p.type != ParameterType::Float && p.type != ParameterType::Int)
            continue;
        // The smallest step past each end: one unit for integers (two for odd-only ones, whose
        // neighbours are refused as even anyway), a relative hair for floats.
        const double step = p.type == ParameterType::Int ? (p.oddOnly ? 2.0 : 1.0)
                                                         : std::max(1e-9, 1e-6 * (p.max - p.min));
        ParameterValues v;
        EXPECT_NO_THROW(v.set(p.key, text(p.min))) << p.key << " at its minimum " << p.min;
        EXPECT_EQ(v.number(p.key), p.min) << p.key;
        EXPECT_NO_THROW(v.set(p.key, text(p.max))) << p.key << " at its maximum " << p.max;
        EXPECT_EQ(v.number(p.key), p.max) << p.key;
        EXPECT_THROW(v.set(p.key, text(p.min - step)), InputError) << p.key << " below minimum";
        EXPECT_THROW(v.set(p.key, text(p.max + step)), InputError) << p.key << " above maximum";
        EXPECT_GE(p.defaultValue, p.min) << p.key;
        EXPECT_LE(p.defaultValue, p.max) << p.key;
        if (p.type == ParameterType::Int) {
            EXPECT_THROW(v.set(p.key, text(p.min + 0.5)), InputError) << p.key << ": integer";
        }
        if (p.oddOnly) {
            EXPECT_THROW(v.set(p.key, text(p.min + 1)), InputError) << p.key << ": odd only";
        }
    }
}

// A boolean's default is false or true (0 or 1), as `set` could store it: any other number
// would print as neither in `penumbra techniques` and docs/cli.md.
TEST(Parameters, EveryBooleanDefaultIsFalseOrTrue) {
    size_t booleans = 0;
    for (const ParameterInfo& p : allParameters())
        if (p.type == ParameterType::Bool) {
            ++booleans;
            EXPECT_TRUE(p.defaultValue == 0.0 || p.defaultValue == 1.0) << p.key;
        }
    EXPECT_GT(booleans, 10u);
}

TEST(Parameters, ChoicesAndBooleansAcceptTheirNamesOnly) {
    for (const ParameterInfo& p : allParameters()) {
        ParameterValues v;
        if (p.type == ParameterType::Choice) {
            for (size_t i = 0; i < p.choices.size(); ++i) {
                v.set(p.key, p.choices[i]);
                EXPECT_EQ(v.number(p.key), static_cast<double>(i)) << p.key;
                EXPECT_EQ(v.text(p.key), p.choices[i]) << p.key;
            }
            // Indices are not names (unless a choice is named so: evsm.components "2", "4").
            for (size_t i = 0; i <= p.choices.size(); ++i) {
                const std::string index = std::to_string(i);
                if (std::find(p.choices.begin(), p.choices.end(), index) == p.choices.end()) {
                    EXPECT_THROW(v.set(p.key, index), InputError) << p.key << " " << i;
                }
            }
            EXPECT_THROW(v.set(p.key, "nonsense"), InputError) << p.key;
        } else if (p.type == ParameterType::Bool) {
            for (const char* yes : {"true", "1", "on"}) {
                v.set(p.key, yes);
                EXPECT_EQ(v.text(p.key), "true") << p.key;
            }
            for (const char* no : {"false", "0", "off"}) {
                v.set(p.key, no);
                EXPECT_EQ(v.text(p.key), "false") << p.key;
            }
            EXPECT_THROW(v.set(p.key, "yes please"), InputError) << p.key;
        }
    }
}

TEST(RenderOptions, ValidateAcceptsTheLastValidValueAndRefusesTheFirstInvalid) {
    struct Case {
        const char* what;
        void (*valid)(RenderOptions&);
        void (*invalid)(RenderOptions&);
    };
    const Case cases[] = {
        {"width", [](RenderOptions& o) { o.width = 1; }, [](RenderOptions& o) { o.width = 0; }},
        {"height", [](RenderOptions& o) { o.height = 1; }, [](RenderOptions& o) { o.height = 0; }},
        {"shadow map", [](RenderOptions& o) { o.shadowMapSize = 16; },
         [](RenderOptions& o) { o.shadowMapSize = 15; }},
        {"frames low", [](RenderOptions& o) { o.frames = 1; },
         [](RenderOptions& o) { o.frames = 0; }},
        {"frames high", [](RenderOptions& o) { o.frames = 10000; },
         [](RenderOptions& o) { o.frames = 10001; }},
        {"light angle", [](RenderOptions& o) { o.lightAngleOverride = 30.0f; },
         [](RenderOptions& o) { o.lightAngleOverride = 30.001f; }},
        {"light radius", [](RenderOptions& o) { o.lightRadiusOverride = 1e30f; },
         [](RenderOptions& o) { o.lightRadiusOverride = INFINITY; }},
    };
    for (const Case& c : cases) {
        RenderOptions valid, invalid;
        c.valid(valid), c.invalid(invalid);
        EXPECT_NO_THROW(validate(valid)) << c.what;
        EXPECT_THROW(validate(invalid), InputError) << c.what;
    }
}

TEST(TechniqueModules, DeclarationsAreConsistent) {
    for (const shadows::TechniqueModule* m : shadows::allModules()) {
        const std::string name(m->info.name);
        // The blocker search's cap is one of its own parameters (the viewer reads it by this key)
        // and only a member that models the light's size searches.
        if (!m->blockerSearchKey.empty()) {
            EXPECT_TRUE(
                std::any_of(m->parameters.begin(), m->parameters.end(),
                            [&](const ParameterInfo& p) { return p.key == m->blockerSearchKey; }))
                << name << ": " << m->blockerSearchKey;
            EXPECT_TRUE(m->modelsLightSize) << name;
        }
        EXPECT_EQ(&shadows::moduleOf(m->info.id), m) << name;
        EXPECT_EQ(findTechnique(m->info.name).id, m->info.id) << name;
        // Every map a pass names is declared, and the visibility pass filters a declared one;
        // last frame's version of a map (`<map> (previous)`) where the map keeps history.
        auto declared = [&](std::string_view map) {
            const bool previous = map.ends_with(shadows::kPreviousMapSuffix);
            if (previous)
                map.remove_suffix(shadows::kPreviousMapSuffix.size());
            if (map == shadows::kDepthMap)
                return !previous;
            for (const shadows::MapDecl& d : m->maps)
                if (d.name == map)
                    return !previous || d.history;
            return false;
        };
        // A module reads maps unless it traces a field instead (then it reads none).
        EXPECT_EQ(m->visibilityMaps.empty(), m->tracedField.has_value()) << name;
        for (std::string_view map : m->visibilityMaps)
            EXPECT_TRUE(declared(map)) << name << ": " << map;
        for (const shadows::DepthPassDecl& pass : m->depthPasses) {
            EXPECT_TRUE(declared(pass.target) && declared(pass.reads)) << name;
            EXPECT_NE(pass.target, pass.reads) << name;
        }
        EXPECT_LE(m->postPasses.size(), shadows::kMaxPostPasses) << name << ": timer scopes";
        for (const shadows::PostPassDecl& pass : m->postPasses) {
            // A pass reads nothing it writes: a storage write over a sampled read races.
            for (std::string_view out : pass.outputs)
                for (std::string_view in : pass.inputs)
                    EXPECT_NE(out, in) << name << ": " << pass.shader;
            EXPECT_LE(pass.inputs.size(), size_t{POST_MAX_MAPS}) << name;
            EXPECT_LE(pass.outputs.size(), size_t{POST_MAX_MAPS}) << name;
            for (std::string_view map : pass.inputs)
                EXPECT_TRUE(declared(map)) << name << ": " << map;
            for (std::string_view map : pass.outputs)
                EXPECT_TRUE(declared(map)) << name << ": " << map;
        }
        // Its own parameters are of a family it lists.
        for (const ParameterInfo& p : m->parameters) {
            const std::string family(p.key.substr(0, p.key.find('.')));
            EXPECT_NE(std::find(m->info.families.begin(), m->info.families.end(), family),
                      m->info.families.end())
                << name << ": " << p.key;
        }
        // The pipeline key starts with the technique, the receiver plane and the horizon (by
        // default only where the technique models the light's size).
        const auto constants = shadows::visibilityConstants(*m, ParameterValues());
        ASSERT_GE(constants.size(), 3u) << name;
        EXPECT_EQ(constants[0].id, uint32_t{SPEC_TECHNIQUE});
        EXPECT_EQ(constants[0].value, static_cast<uint32_t>(m->info.id));
        EXPECT_EQ(constants[1].id, uint32_t{SPEC_RECEIVER});
        EXPECT_EQ(constants[1].value, uint32_t{RECEIVER_LIGHT}); // the default
        EXPECT_EQ(constants[2].id, uint32_t{SPEC_HORIZON});
        const bool sized = m->info.id == Technique::Pcss || m->info.id == Technique::Vssm ||
                           m->info.id == Technique::MsmSoft || m->info.id == Technique::Sdf ||
                           m->info.id == Technique::Smrt;
        EXPECT_EQ(constants[2].value, sized ? 1u : 0u) << name;
        ParameterValues everywhere, nowhere;
        everywhere.assign("bias.horizon=all");
        nowhere.assign("bias.horizon=off");
        EXPECT_EQ(shadows::visibilityConstants(*m, everywhere)[2].value, 1u) << name;
        EXPECT_EQ(shadows::visibilityConstants(*m, nowhere)[2].value, 0u) << name;
        // Then whether suns blend their cascades (no band, no second cascade to evaluate).
        ASSERT_GE(constants.size(), 4u) << name;
        EXPECT_EQ(constants[3].id, uint32_t{SPEC_CASCADE_BLEND});
        EXPECT_EQ(constants[3].value, 1u) << name;
        ParameterValues unblended;
        unblended.assign("csm.blend=0");
        EXPECT_EQ(shadows::visibilityConstants(*m, unblended)[3].value, 0u) << name;
        if (!shadows::drawsLightMaps(*m)) { // no shadow map: no texels to blur over, none to store
            EXPECT_TRUE(m->tracedField.has_value()) << name; // what it reads instead
            EXPECT_EQ(m->blurRadiusTexels(ParameterValues()), 0.0) << name;
            EXPECT_EQ(shadows::shadowMapBytes(*m, 1024, ParameterValues()), 0u) << name;
            EXPECT_TRUE(m->maps.empty() && m->postPasses.empty() && m->depthPasses.empty()) << name;
            EXPECT_EQ(shadows::drawnMapSize(*m, 1024), 1u) << name << ": 1x1 stand-ins";
        } else {
            EXPECT_GE(m->blurRadiusTexels(ParameterValues()), 0.5) << name;
            EXPECT_EQ(shadows::drawnMapSize(*m, 1024), 1024u) << name;
        }
    }
    // What the techniques keep per texel of a shadow view: depth, plus second-depth's second
    // layer and midpoint; the PCF kernel's filter constant in its key only.
    const ParameterValues defaults;
    EXPECT_EQ(shadows::shadowMapBytes(shadows::hardModule(), 1024, defaults), 4u * 1024 * 1024);
    EXPECT_EQ(shadows::shadowMapBytes(shadows::secondDepthModule(), 16, defaults), 12u * 16 * 16);
    // smrt: depth, and its bounds from half the size down (8, 4, 2, 1 texels a side; an odd-sized
    // map's half rounds down: 7, 3, 1).
    EXPECT_EQ(shadows::shadowMapBytes(shadows::smrtModule(), 16, defaults),
              4u * 16 * 16 + 4u * (64 + 16 + 4 + 1));
    EXPECT_EQ(shadows::shadowMapBytes(shadows::smrtModule(), 15, defaults),
              4u * 15 * 15 + 4u * (49 + 9 + 1));
    // A map kept with history is held twice (bench's memory.shadow_maps counted it once).
    shadows::TechniqueModule kept = shadows::smrtModule();
    ASSERT_EQ(kept.maps.size(), 1u);
    kept.maps.front().history = true;
    EXPECT_EQ(shadows::shadowMapBytes(kept, 16, defaults),
              4u * 16 * 16 + 2u * 4u * (64 + 16 + 4 + 1));
    ParameterValues poisson;
    poisson.assign("pcf.filter=poisson");
    poisson.assign("pcf.radius=6");
    const auto pcf = shadows::visibilityConstants(shadows::pcfModule(), poisson);
    ASSERT_EQ(pcf.size(), 7u);
    EXPECT_EQ(pcf[4].id, uint32_t{SPEC_ADAPTIVE_BIAS}); // every technique's: bias.mode
    EXPECT_EQ(pcf[4].value, ParameterValues().number("bias.mode") == BIAS_ADAPTIVE ? 1u : 0u);
    // Then virtual maps, then the module's own.
    EXPECT_EQ(pcf[5].id, uint32_t{SPEC_VIRTUAL});
    EXPECT_EQ(pcf[5].value, 0u);
    EXPECT_EQ(pcf[6].id, uint32_t{SPEC_FILTER});
    EXPECT_EQ(pcf[6].value, uint32_t{FILTER_POISSON});
    // Each capability is the module's own constant, and only the modules that need one set it:
    // the footprint (vsm.filter=mip), the blocker search across cascades (pcss), the field. A
    // constant left out is the shader's default, false; none is set twice.
    auto capability = [](const shadows::TechniqueModule& m, const ParameterValues& p, int id) {
        uint32_t value = 0, seen = 0;
        for (const shadows::SpecConstant& c : shadows::visibilityConstants(m, p))
            if (c.id == uint32_t(id)) {
                value = c.value;
                ++seen;
            }
        EXPECT_LE(seen, 1u) << m.info.name << " sets constant " << id << " twice";
        return value;
    };
    ParameterValues mipmapped;
    mipmapped.assign("vsm.filter=mip");
    ParameterValues virtualMaps;
    virtualMaps.assign("virtual.enabled=1");
    for (const shadows::TechniqueModule* m : shadows::allModules()) {
        const bool vsm = m == &shadows::vsmModule();
        EXPECT_EQ(capability(*m, defaults, SPEC_FOOTPRINT), 0u) << m->info.name;
        EXPECT_EQ(capability(*m, mipmapped, SPEC_FOOTPRINT), vsm ? 1u : 0u) << m->info.name;
        EXPECT_EQ(capability(*m, defaults, SPEC_BLOCKER_SEARCH),
                  m == &shadows::pcssModule() ? 1u : 0u)
            << m->info.name;
        EXPECT_EQ(capability(*m, defaults, SPEC_TRACES_FIELD), m->tracedField ? 1u : 0u)
            << m->info.name;
        // Virtual maps: only where asked for, and only for the modules that read them.
        EXPECT_EQ(capability(*m, defaults, SPEC_VIRTUAL), 0u) << m->info.name;
        EXPECT_EQ(capability(*m, virtualMaps, SPEC_VIRTUAL), m->readsVirtualMaps ? 1u : 0u)
            << m->info.name;
        EXPECT_EQ(m->readsVirtualMaps, m == &shadows::hardModule() || m == &shadows::pcfModule() ||
                                           m == &shadows::pcssModule() ||
                                           m == &shadows::smrtModule())
            << m->info.name;
        // The shared settings carry the blocker search's cap where there is one (the searching
        // members), else 0.
        const shadows::FilterSettings s = shadows::filterSettings(*m, defaults, false, 8);
        const bool searches = m == &shadows::pcssModule() || m == &shadows::vssmModule() ||
                              m == &shadows::msmSoftModule();
        EXPECT_EQ(s.frame.filterLimits.x,
                  searches ? static_cast<float>(defaults.number(m->blockerSearchKey)) : 0.0f)
            << m->info.name;
    }
    poisson.assign("bias.mode=adaptive");
    EXPECT_EQ(shadows::visibilityConstants(shadows::pcfModule(), poisson)[4].value, 1u);
    poisson.assign("bias.mode=fixed");
    EXPECT_EQ(shadows::visibilityConstants(shadows::pcfModule(), poisson)[4].value, 0u);
    // Blur radii: how far from the receiver the last texel a kernel reads lies (a bilinear tap
    // reaches one texel past its position).
    EXPECT_EQ(shadows::pcfModule().blurRadiusTexels(poisson), 7.0);
    ParameterValues box;
    box.assign("pcf.size=7");
    EXPECT_EQ(shadows::pcfModule().blurRadiusTexels(box), 4.0);
    box.assign("pcf.filter=bilinear");
    EXPECT_EQ(shadows::pcfModule().blurRadiusTexels(box), 1.0);
    EXPECT_EQ(shadows::pcssModule().blurRadiusTexels(box), 41.0); // pcss.maxRadius 40
    EXPECT_EQ(shadows::hardModule().blurRadiusTexels(box), 0.5);
    EXPECT_EQ(shadows::visibilityConstants(shadows::hardModule(), poisson).size(), 6u);
    // A module's constant may not set what the shared ones set (the pipeline would see it twice).
    shadows::TechniqueModule clashing = shadows::hardModule();
    clashing.constants = [](const ParameterValues&) {
        return std::vector<shadows::SpecConstant>{{SPEC_FOOTPRINT, 1u}, {SPEC_VIRTUAL, 1u}};
    };
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(shadows::visibilityConstants(clashing, poisson),
                 "hard sets a shared specialization constant, id " + std::to_string(SPEC_VIRTUAL));
    // The summed-area members' memory: two RG32UI maps (savsm, vssm) or two RGBA32UI maps
    // (msm-soft) beside the depth; their fixed-point scales keep the widest box exact.
    EXPECT_EQ(shadows::shadowMapBytes(shadows::vssmModule(), 16, defaults), (4u + 16u) * 16 * 16);
    EXPECT_EQ(shadows::shadowMapBytes(shadows::msmSoftModule(), 16, defaults),
              (4u + 32u) * 16 * 16);
    // msm.precision=16 keeps the blurred moments in 16-bit unorm (the row pass's stay 32-bit).
    ParameterValues sixteen;
    sixteen.assign("msm.precision=16");
    EXPECT_EQ(shadows::shadowMapBytes(shadows::msmModule(), 16, defaults), (4u + 32u) * 16 * 16);
    EXPECT_EQ(shadows::shadowMapBytes(shadows::msmModule(), 16, sixteen), (4u + 24u) * 16 * 16);
    // vsm.filter=mip: the blurred moments' map gains its chain (16, 8, 4, 2, 1: 341 texels of
    // 8 bytes), the row pass's map stays one level; the chain's reads are vsm.anisotropy taps.
    ParameterValues mip;
    mip.assign("vsm.filter=mip");
    EXPECT_EQ(shadows::shadowMapBytes(shadows::vsmModule(), 16, defaults), (4u + 16u) * 16 * 16);
    EXPECT_EQ(shadows::shadowMapBytes(shadows::vsmModule(), 16, mip),
              (4u + 8u) * 16 * 16 + 8u * 341);
    shadows::ParamBlock block;
    shadows::vsmModule().pack(mip, block);
    EXPECT_EQ(block.get<gpu::VsmParams>().anisotropy, 8.0f);
    shadows::vsmModule().pack(defaults, block);
    EXPECT_EQ(block.get<gpu::VsmParams>().anisotropy, 0.0f);
    // The soft members' one table serves every view: its scale holds the widest box of either cap
    // (a cube face's 96 by default, else a spot's when wider).
    ParameterValues spotWide;
    spotWide.assign("vssm.maxRadius=120");
    const ParameterValues& wideSpots = spotWide;
    for (const ParameterValues* p : {&defaults, &wideSpots}) {
        shadows::vssmModule().pack(*p, block);
        const gpu::SoftParams soft = block.get<gpu::SoftParams>();
        EXPECT_EQ(soft.tableScale,
                  shadows::fixedPointScale(
                      2.0 * std::max(p->number("vssm.maxRadius"), p->number("vssm.cubeRadius"))));
        EXPECT_EQ(soft.cubeRadius, 96.0f);
    }
    for (double widest : {1.0, 7.0, 40.0, 128.0, 512.0}) {
        const double scale = shadows::fixedPointScale(widest);
        const double hull = std::ceil(widest) + 2.0;
        EXPECT_LE(hull * hull * scale, 2147483647.0) << widest;
        EXPECT_GT(hull * hull * (scale + 1.0), 2147483647.0 * (scale < 16777216.0 ? 1.0 : 0.0))
            << widest << ": as many steps as fit";
        EXPECT_LE(scale, 16777216.0);
    }
}

// Lists in messages come from the modules: in registry order, commas and a last "and".
TEST(TechniqueModules, MessagesListTheTechniquesTheRegistryHolds) {
    using shadows::TechniqueModule;
    EXPECT_EQ(shadows::techniquesWhere([](const TechniqueModule&) { return false; }), "none");
    EXPECT_EQ(
        shadows::techniquesWhere([](const TechniqueModule& m) { return m.info.name == "pcf"; }),
        "pcf");
    EXPECT_EQ(shadows::techniquesWhere([](const TechniqueModule& m) {
                  return m.info.name == "pcf" || m.info.name == "hard";
              }),
              "hard and pcf");
    std::string all;
    const auto modules = shadows::allModules();
    for (size_t i = 0; i < modules.size(); ++i)
        all += std::string(i == 0                    ? ""
                           : i + 1 == modules.size() ? " and "
                                                     : ", ") +
               std::string(modules[i]->info.name);
    EXPECT_EQ(shadows::techniquesWhere([](const TechniqueModule&) { return true; }), all);
    // What the virtual maps' refusal names: every module that reads them, smrt too.
    const std::string virtualReaders =
        shadows::techniquesWhere([](const TechniqueModule& m) { return m.readsVirtualMaps; });
    for (const TechniqueModule* m : modules)
        EXPECT_EQ(virtualReaders.find(m->info.name) != std::string::npos, m->readsVirtualMaps)
            << m->info.name;
}

TEST(TechniqueModules, CubeGuardBandsHoldEveryKernel) {
    // A point light's face keeps, beyond its 90 degrees, every texel a kernel centred inside it
    // reads: the footprint, the bilinear tap's 1.5 texels, and the normal offset.
    for (const TechniqueRow& row : comparisonRows("")) {
        for (const char* normal : {"0", "1.5", "4"}) {
            ParameterValues p;
            for (const auto& [key, value] : row.sets)
                p.set(key, value);
            p.set("bias.normal", normal);
            const shadows::TechniqueModule& m = shadows::moduleOf(row.technique);
            const double reach = m.cubeRadiusTexels ? m.cubeRadiusTexels(p) : m.blurRadiusTexels(p);
            const double need = reach + 1.5 + p.number("bias.normal");
            const uint32_t guard = shadows::viewGuardTexels(m, p, true);
            EXPECT_GE(guard, need) << row.name << ", bias.normal " << normal;
            EXPECT_LE(guard, need + 3.0) << row.name << ": a wider band costs resolution";
        }
    }
    ParameterValues wide;
    wide.set("pcss.maxRadius", "100");
    EXPECT_EQ(shadows::viewGuardTexels(shadows::pcssModule(), wide), 101u + 2u + 1u); // normal 0.3
    // A point light's cube faces: the soft members' own cap (cubeRadius 96), the others' the same.
    wide.set("pcss.cubeRadius", "50");
    EXPECT_EQ(shadows::viewGuardTexels(shadows::pcssModule(), wide, true), 51u + 2u + 1u);
    EXPECT_EQ(shadows::widestRadiusTexels(shadows::pcssModule(), wide), 101.0);
    EXPECT_EQ(shadows::readReachTexels(shadows::pcssModule(), wide), 101.0);
    // What the visibility pass reads around a receiver: one texel at least, a search's cap where
    // it reaches past the footprint.
    EXPECT_EQ(shadows::readReachTexels(shadows::hardModule(), ParameterValues{}), 1.0);
    shadows::TechniqueModule searching = shadows::pcssModule(); // a search past its footprint
    searching.blurRadiusTexels = [](const ParameterValues&) { return 20.0; };
    EXPECT_EQ(shadows::readReachTexels(searching, wide), 100.0);
    EXPECT_EQ(shadows::searchCapTexels(searching, wide), 100.0);
    EXPECT_EQ(shadows::searchCapTexels(shadows::pcfModule(), wide), 0.0) << "no search";
    const ParameterValues defaults;
    for (const shadows::TechniqueModule* m : {&shadows::vssmModule(), &shadows::msmSoftModule()}) {
        EXPECT_EQ(shadows::viewGuardTexels(*m, defaults), 65u + 2u + 1u) << m->info.name;
        EXPECT_EQ(shadows::viewGuardTexels(*m, defaults, true), 97u + 2u + 1u) << m->info.name;
        EXPECT_EQ(shadows::blurRadii(*m, defaults), std::make_pair(65.0, 97.0)) << m->info.name;
    }
    EXPECT_EQ(shadows::viewGuardTexels(shadows::pcfModule(), defaults, true),
              shadows::viewGuardTexels(shadows::pcfModule(), defaults));
    EXPECT_EQ(shadows::blurRadii(shadows::hardModule(), defaults), std::make_pair(0.5, -1.0));
}

TEST(TechniqueModules, GuardBandsFollowTheLightOnlyWhereTheFootprintDoes) {
    const ParameterValues defaults; // bias.normal 0.3: one texel
    const Light sun{.type = LightType::Directional, .angularDiameter = 2.0f},
        noSun{.type = LightType::Directional}, bulb{.type = LightType::Point, .radius = 0.3f},
        noBulb{.type = LightType::Point};
    // smrt's rays stay in the light's cone: its band is the cone's, capped by its march, one
    // bilinear tap's (hard's) beyond it.
    const GuardBand smrtSun = shadows::viewGuardBand(shadows::smrtModule(), defaults, sun);
    EXPECT_EQ(smrtSun.texels, 257u + 2u + 1u);
    EXPECT_FLOAT_EQ(smrtSun.lightSize, std::tan(glm::radians(1.0f)));
    EXPECT_EQ(smrtSun.fixedTexels, shadows::viewGuardTexels(shadows::hardModule(), defaults));
    EXPECT_EQ(shadows::viewGuardBand(shadows::smrtModule(), defaults, noSun).lightSize, 0.0f);
    EXPECT_FLOAT_EQ(shadows::viewGuardBand(shadows::smrtModule(), defaults, bulb).lightSize, 0.3f);
    // A cube face: the widest under a bulb with size, one tap under a point.
    EXPECT_EQ(shadows::viewGuardBand(shadows::smrtModule(), defaults, bulb).cubeFaceTexels(1024),
              256.0f); // a quarter of the face at most
    EXPECT_EQ(shadows::viewGuardBand(shadows::smrtModule(), defaults, noBulb).cubeFaceTexels(1024),
              4.0f);
    // pcss filters at least half a texel and searches its cap: its band stays the widest.
    for (const Light& light : {sun, noSun, bulb, noBulb}) {
        const GuardBand pcss = shadows::viewGuardBand(shadows::pcssModule(), defaults, light);
        EXPECT_LT(pcss.lightSize, 0.0f);
        EXPECT_EQ(pcss.texels, shadows::viewGuardTexels(shadows::pcssModule(), defaults,
                                                        light.type == LightType::Point));
        EXPECT_EQ(pcss.cubeFaceTexels(1024), static_cast<float>(pcss.texels));
        EXPECT_EQ(pcss.cascadeTexels(10.0f, 50.0f, 1024), static_cast<float>(pcss.texels));
    }
}

TEST(TechniqueModules, ChoiceListsAreTheShadersOwnTables) {
    const std::pair<const char*, std::span<const char* const>> lists[] = {
        {"pcf.filter", gpu::kFilterChoices},
        {"pcf.rotation", gpu::kRotationChoices},
        {"pcss.rotation", gpu::kRotationChoices},
        {"bias.receiver", gpu::kReceiverChoices}};
    for (const auto& [key, names] : lists) {
        const auto params = allParameters();
        const auto it = std::find_if(params.begin(), params.end(),
                                     [&](const ParameterInfo& p) { return p.key == key; });
        ASSERT_NE(it, params.end()) << key;
        ASSERT_EQ(it->choices.size(), names.size()) << key;
        for (size_t i = 0; i < names.size(); ++i)
            EXPECT_EQ(it->choices[i], names[i]) << key << " choice " << i;
    }
    ParameterValues v;
    v.assign("pcf.filter=gaussian");
    EXPECT_EQ(v.number("pcf.filter"), double{FILTER_GAUSSIAN});
    v.assign("bias.receiver=screen");
    EXPECT_EQ(v.number("bias.receiver"), double{RECEIVER_SCREEN});
    v.assign("pcss.rotation=ign");
    EXPECT_EQ(v.number("pcss.rotation"), double{ROTATION_IGN});
}
