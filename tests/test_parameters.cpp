#include "penumbra/error.h"
#include "penumbra/settings.h"

#include <gtest/gtest.h>

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
