// The progress line's arithmetic: durations as it prints them, and the time left it estimates.
#include "console.h"

#include <gtest/gtest.h>

namespace rad::cli {
namespace {

TEST(Console, DurationsReadAsTheProgressLinePrintsThem) {
  EXPECT_EQ(durationText(0.4), "0 s");
  EXPECT_EQ(durationText(42.4), "42 s");
  EXPECT_EQ(durationText(185.0), "3 min 05 s");  // 3 * 60 + 5
  EXPECT_EQ(durationText(3599.4), "59 min 59 s");
  EXPECT_EQ(durationText(7620.0), "2 h 07 min");  // 2 * 3600 + 7 * 60
  EXPECT_EQ(durationText(-3.0), "0 s");
}

TEST(Console, TimeLeftFollowsThePaceSinceTheFirstReport) {
  // From 5% to 25% in 10 s: 2% a second, so the 75% left take 37.5 s; the setup before the
  // first report (5% already done) does not slow the estimate down.
  EXPECT_DOUBLE_EQ(secondsLeft(0.05, 0.25, 10.0), 37.5);
  EXPECT_DOUBLE_EQ(secondsLeft(0.0, 1.0, 30.0), 0.0);
  EXPECT_LT(secondsLeft(0.0, 0.005, 10.0), 0.0);  // too little done to judge
  EXPECT_LT(secondsLeft(0.0, 0.5, 0.5), 0.0);     // too soon to judge
}

}  // namespace
}  // namespace rad::cli
