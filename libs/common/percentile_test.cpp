#include "libs/common/percentile.h"

#include <gtest/gtest.h>

namespace ssl {
namespace {

TEST(CommonPercentile, NearestRankBelowOfUnsortedSamples) {
  std::vector<double> values{5, 1, 4, 2, 3, 10, 9, 8, 7, 6, 11};  // 1..11
  EXPECT_DOUBLE_EQ(percentile(values, 0.5), 6);
  EXPECT_DOUBLE_EQ(percentile(values, 0.0), 1);
  EXPECT_DOUBLE_EQ(percentile(values, 1.0), 11);
  EXPECT_DOUBLE_EQ(percentile(values, 0.99), 10);  // index floor(0.99 * 10) = 9
}

TEST(CommonPercentile, EmptyIsZeroAndOutOfRangeQuantilesClamp) {
  std::vector<double> none;
  EXPECT_DOUBLE_EQ(percentile(none, 0.5), 0);
  std::vector<double> values{3, 1, 2};
  EXPECT_DOUBLE_EQ(percentile(values, 2.0), 3);
  EXPECT_DOUBLE_EQ(percentile(values, -1.0), 1);
}

}  // namespace
}  // namespace ssl
