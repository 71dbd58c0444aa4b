#include "penumbra/error.h"
#include "penumbra/settings.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

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

TEST(Parameters, ChoicesAndBooleansAcceptTheirNamesOnly) {
    for (const ParameterInfo& p : allParameters()) {
        ParameterValues v;
        if (p.type == ParameterType::Choice) {
            for (size_t i = 0; i < p.choices.size(); ++i) {
                v.set(p.key, p.choices[i]);
                EXPECT_EQ(v.number(p.key), static_cast<double>(i)) << p.key;
                EXPECT_EQ(v.text(p.key), p.choices[i]) << p.key;
            }
            EXPECT_THROW(v.set(p.key, std::to_string(p.choices.size())), InputError) << p.key;
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
