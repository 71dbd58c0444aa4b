// Lag and pop-in (src/report/lag.h): a frame in motion lags when its error exceeds the one at
// rest by more than 10%; the longest run of such frames, the worst excess and the worst ratio.
#include "report/lag.h"

#include <gtest/gtest.h>

using penumbra::Lag;
using penumbra::measureLag;

TEST(Lag, AFrameInMotionEqualToItsRestDoesNotLag) {
    const Lag lag = measureLag({0.02, 0.03, 0.0}, {0.02, 0.03, 0.0});
    EXPECT_EQ(lag.popIn, 0.0);
    EXPECT_EQ(lag.popInRatio, 1.0);
    EXPECT_EQ(lag.lagFrames, 0u);
    EXPECT_EQ(lag.laggingFrames, 0u);
}

TEST(Lag, TenPercentWorseIsWithinTheSteadyStateAndMoreIsNot) {
    // 0.11 / 0.1 is a hair over 1.1 in double: 0.1099 is within, 0.1101 is not.
    EXPECT_EQ(measureLag({0.1}, {0.1099}).laggingFrames, 0u);
    EXPECT_EQ(measureLag({0.1}, {0.1101}).laggingFrames, 1u);
    EXPECT_EQ(measureLag({1.0}, {1.1}).laggingFrames, 0u) << "exactly 10% is within";
    // Better in motion than at rest is not a lag, and no excess.
    const Lag better = measureLag({0.1, 0.1}, {0.05, 0.1});
    EXPECT_EQ(better.laggingFrames, 0u);
    EXPECT_EQ(better.popIn, 0.0);
    EXPECT_EQ(better.popInRatio, 1.0);
}

TEST(Lag, TheLongestRunOfLaggingFramesCounts) {
    //                       0    1    2    3    4    5    6
    const Lag lag =
        measureLag({0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1}, {0.1, 0.3, 0.2, 0.1, 0.2, 0.2, 0.2});
    EXPECT_EQ(lag.lagFrames, 3u) << "frames 4 to 6; frame 3 ended the first run";
    EXPECT_EQ(lag.laggingFrames, 5u);
    EXPECT_NEAR(lag.popIn, 0.2, 1e-12) << "frame 1";
    EXPECT_NEAR(lag.popInRatio, 3.0, 1e-12);
    // A run at the start counts as well as one at the end.
    EXPECT_EQ(measureLag({0.1, 0.1, 0.1}, {0.5, 0.5, 0.1}).lagFrames, 2u);
}

TEST(Lag, ARestErrorOfZeroLagsOnAnyErrorButHasNoRatio) {
    const Lag lag = measureLag({0.0, 0.2}, {0.01, 0.3});
    EXPECT_EQ(lag.laggingFrames, 2u);
    EXPECT_EQ(lag.lagFrames, 2u);
    EXPECT_NEAR(lag.popIn, 0.1, 1e-12) << "frame 1's 0.1 is more than frame 0's 0.01";
    EXPECT_NEAR(lag.popInRatio, 1.5, 1e-12) << "frame 0 has no ratio";
}
