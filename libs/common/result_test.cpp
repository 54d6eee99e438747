#include "libs/common/result.h"

#include <gtest/gtest.h>

#include <memory>

#include "libs/common/team.h"

namespace ssl {
namespace {

Result<int> parse_positive(int value) {
  if (value <= 0) return Error{"value must be positive, got " + std::to_string(value)};
  return value;
}

TEST(ResultTest, HoldsValueOrError) {
  const auto good = parse_positive(3);
  ASSERT_TRUE(good.ok());
  EXPECT_EQ(*good, 3);

  const auto bad = parse_positive(-1);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().message, "value must be positive, got -1");
}

TEST(ResultTest, MoveOnlyValuesCanBeTakenOut) {
  Result<std::unique_ptr<int>> holder(std::make_unique<int>(7));
  std::unique_ptr<int> taken = std::move(holder).value();
  ASSERT_NE(taken, nullptr);
  EXPECT_EQ(*taken, 7);
}

TEST(StatusTest, DefaultIsSuccessAndErrorCarriesMessage) {
  EXPECT_TRUE(Status::success().ok());
  const Status failed = Error{"disk full"};
  EXPECT_FALSE(failed.ok());
  EXPECT_EQ(failed.error().message, "disk full");
}

TEST(TeamTest, ParsesOnlyExactNamesAndRoundTrips) {
  EXPECT_EQ(parse_team("blue"), TeamColor::kBlue);
  EXPECT_EQ(parse_team("yellow"), TeamColor::kYellow);
  EXPECT_EQ(parse_team("Blue"), std::nullopt);
  EXPECT_EQ(parse_team(""), std::nullopt);
  EXPECT_EQ(to_string(TeamColor::kYellow), "yellow");
  EXPECT_EQ(opponent(TeamColor::kBlue), TeamColor::kYellow);
}

}  // namespace
}  // namespace ssl
