#include "libs/geometry/angle.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>

#include <gtest/gtest.h>

namespace ssl::geom {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(GeomAngleTest, DefaultAndZeroAreZeroRadians) {
  EXPECT_EQ(Angle().radians(), 0.0);
  EXPECT_EQ(Angle::zero().radians(), 0.0);
}

TEST(GeomAngleTest, NamedConstantsHaveTheirValues) {
  EXPECT_EQ(Angle::half_turn().radians(), kPi);
  EXPECT_EQ(Angle::quarter_turn().radians(), kPi / 2.0);
  EXPECT_EQ(Angle::half_turn().degrees(), 180.0);
  EXPECT_EQ(Angle::quarter_turn().degrees(), 90.0);
}

TEST(GeomAngleTest, FromRadiansKeepsValuesAlreadyInRangeExactly) {
  EXPECT_EQ(Angle::from_radians(0.5).radians(), 0.5);
  EXPECT_EQ(Angle::from_radians(-3.0).radians(), -3.0);
  EXPECT_EQ(Angle::from_radians(kPi).radians(), kPi);
}

TEST(GeomAngleTest, HalfTurnAlwaysWrapsToPositivePi) {
  EXPECT_EQ(Angle::from_radians(-kPi).radians(), kPi);
  EXPECT_EQ(Angle::from_radians(3.0 * kPi).radians(), kPi);
  EXPECT_EQ(Angle::from_radians(-3.0 * kPi).radians(), kPi);
  EXPECT_EQ(Angle::from_degrees(-180.0).radians(), kPi);
  EXPECT_EQ(Angle::from_degrees(540.0).radians(), kPi);
  EXPECT_EQ((-Angle::half_turn()).radians(), kPi);
}

TEST(GeomAngleTest, ValuesJustPastPiWrapToTheOtherSide) {
  EXPECT_NEAR(Angle::from_radians(kPi + 0.1).radians(), -kPi + 0.1, 1e-15);
  EXPECT_NEAR(Angle::from_radians(-kPi - 0.1).radians(), kPi - 0.1, 1e-15);
  EXPECT_NEAR(Angle::from_radians(2.0 * kPi + 0.25).radians(), 0.25, 1e-15);
  EXPECT_NEAR(Angle::from_radians(-2.0 * kPi).radians(), 0.0, 1e-15);
}

TEST(GeomAngleTest, LargeValuesWrapByWholeTurns) {
  // 100 - 16 * 2 pi = -0.530964914873...
  EXPECT_NEAR(Angle::from_radians(100.0).radians(), 100.0 - 32.0 * kPi, 1e-13);
  EXPECT_NEAR(Angle::from_radians(100.0).radians(), -0.5309649148733797, 1e-13);
  EXPECT_NEAR(Angle::from_radians(-1000.0).radians(), -1000.0 + 318.0 * kPi, 1e-12);
}

TEST(GeomAngleTest, FromDegreesConvertsWholeDegreesExactly) {
  EXPECT_EQ(Angle::from_degrees(90.0).radians(), kPi / 2.0);
  EXPECT_EQ(Angle::from_degrees(180.0).radians(), kPi);
  EXPECT_EQ(Angle::from_degrees(-90.0).radians(), -kPi / 2.0);
  EXPECT_EQ(Angle::from_degrees(270.0), Angle::from_degrees(-90.0));
  EXPECT_EQ(Angle::from_degrees(720.0).radians(), 0.0);
  EXPECT_EQ(Angle::from_degrees(90.0).degrees(), 90.0);
  EXPECT_NEAR(Angle::from_degrees(45.0).radians(), kPi / 4.0, 1e-16);
  EXPECT_NEAR(Angle::from_degrees(-30.0).degrees(), -30.0, 1e-13);
}

TEST(GeomAngleTest, FromVectorMeasuresCounterClockwiseFromPlusX) {
  EXPECT_EQ(Angle::from_vector({1.0, 0.0}).radians(), 0.0);
  EXPECT_EQ(Angle::from_vector({0.0, 2.0}).radians(), kPi / 2.0);
  EXPECT_EQ(Angle::from_vector({0.0, -2.0}).radians(), -kPi / 2.0);
  EXPECT_EQ(Angle::from_vector({-1.0, 0.0}).radians(), kPi);
  // atan2(-0.0, -1) is -pi; the type must still hold +pi.
  EXPECT_EQ(Angle::from_vector({-1.0, -0.0}).radians(), kPi);
  EXPECT_NEAR(Angle::from_vector({1.0, 1.0}).radians(), kPi / 4.0, 1e-16);
  EXPECT_NEAR(Angle::from_vector({-1.0, -1.0}).degrees(), -135.0, 1e-13);
  EXPECT_EQ(Angle::from_vector({0.0, 0.0}).radians(), 0.0);
}

TEST(GeomAngleTest, ToUnitVectorPointsInTheDirection) {
  const Eigen::Vector2d up = Angle::quarter_turn().to_unit_vector();
  EXPECT_NEAR(up.x(), 0.0, 1e-16);
  EXPECT_EQ(up.y(), 1.0);
  const Eigen::Vector2d v = Angle::from_degrees(-60.0).to_unit_vector();
  EXPECT_NEAR(v.x(), 0.5, 1e-15);
  EXPECT_NEAR(v.y(), -std::sqrt(3.0) / 2.0, 1e-15);
  EXPECT_NEAR(v.norm(), 1.0, 1e-15);
}

TEST(GeomAngleTest, AdditionAndSubtractionWrap) {
  EXPECT_NEAR((Angle::from_degrees(170.0) + Angle::from_degrees(20.0)).degrees(), -170.0, 1e-12);
  EXPECT_NEAR((Angle::from_degrees(-170.0) - Angle::from_degrees(20.0)).degrees(), 170.0, 1e-12);
  EXPECT_NEAR((Angle::from_degrees(30.0) + Angle::from_degrees(60.0)).radians(), kPi / 2.0, 1e-15);
  EXPECT_EQ(Angle::quarter_turn() + Angle::quarter_turn(), Angle::half_turn());
  EXPECT_EQ(Angle::zero() - Angle::half_turn(), Angle::half_turn());
}

TEST(GeomAngleTest, UnaryMinusNegatesExceptTheHalfTurn) {
  EXPECT_EQ((-Angle::from_radians(0.5)).radians(), -0.5);
  EXPECT_EQ((-Angle::from_radians(-2.0)).radians(), 2.0);
  EXPECT_EQ(-Angle::half_turn(), Angle::half_turn());
}

TEST(GeomAngleTest, ScalingWrapsTheResult) {
  EXPECT_NEAR((Angle::from_degrees(100.0) * 2.0).degrees(), -160.0, 1e-12);
  EXPECT_NEAR((3.0 * Angle::from_degrees(50.0)).degrees(), 150.0, 1e-12);
  EXPECT_NEAR((Angle::from_degrees(90.0) / 2.0).degrees(), 45.0, 1e-12);
  EXPECT_NEAR((Angle::from_degrees(-90.0) / -3.0).degrees(), 30.0, 1e-12);
}

TEST(GeomAngleTest, CompoundAssignmentMatchesBinaryOperators) {
  Angle a = Angle::from_degrees(170.0);
  a += Angle::from_degrees(20.0);
  EXPECT_NEAR(a.degrees(), -170.0, 1e-12);
  a -= Angle::from_degrees(20.0);
  EXPECT_NEAR(a.degrees(), 170.0, 1e-12);
  a *= 2.0;
  EXPECT_NEAR(a.degrees(), -20.0, 1e-12);
  a /= -4.0;
  EXPECT_NEAR(a.degrees(), 5.0, 1e-12);
}

TEST(GeomAngleTest, EqualityComparesWrappedValues) {
  EXPECT_EQ(Angle::from_degrees(450.0), Angle::from_degrees(90.0));
  EXPECT_EQ(Angle::from_degrees(-90.0), Angle::from_degrees(270.0));
  EXPECT_NE(Angle::from_degrees(10.0), Angle::from_degrees(20.0));
  // Exact comparison: two routes to "the same" angle may differ in the last bit; near() is for that.
  EXPECT_TRUE(near(Angle::from_radians(0.1 + 0.2), Angle::from_radians(0.3), Angle::from_radians(1e-15)));
}

TEST(GeomAngleTest, OrderingComparesWrappedRadians) {
  EXPECT_LT(Angle::from_degrees(10.0), Angle::from_degrees(20.0));
  EXPECT_GT(Angle::from_degrees(10.0), Angle::from_degrees(-20.0));
  EXPECT_LE(Angle::half_turn(), Angle::half_turn());
  // 350 degrees is -10 degrees once wrapped, so it orders below 10 degrees.
  EXPECT_LT(Angle::from_degrees(350.0), Angle::from_degrees(10.0));
}

TEST(GeomAngleTest, AbsIsTheMagnitude) {
  EXPECT_EQ(abs(Angle::from_radians(-0.5)).radians(), 0.5);
  EXPECT_EQ(abs(Angle::from_radians(0.5)).radians(), 0.5);
  EXPECT_EQ(abs(Angle::half_turn()), Angle::half_turn());
  EXPECT_EQ(abs(Angle::from_degrees(270.0)), Angle::quarter_turn());
}

TEST(GeomAngleTest, AngleDiffIsTheShortestSignedTurn) {
  EXPECT_NEAR(angle_diff(Angle::from_degrees(10.0), Angle::from_degrees(350.0)).degrees(), 20.0, 1e-12);
  EXPECT_NEAR(angle_diff(Angle::from_degrees(350.0), Angle::from_degrees(10.0)).degrees(), -20.0, 1e-12);
  EXPECT_NEAR(angle_diff(Angle::from_degrees(179.0), Angle::from_degrees(-179.0)).degrees(), -2.0, 1e-12);
  EXPECT_NEAR(angle_diff(Angle::from_degrees(-179.0), Angle::from_degrees(179.0)).degrees(), 2.0, 1e-12);
  EXPECT_EQ(angle_diff(Angle::from_radians(1.0), Angle::from_radians(1.0)).radians(), 0.0);
}

TEST(GeomAngleTest, AngleDiffOfOppositeDirectionsIsPositivePi) {
  EXPECT_EQ(angle_diff(Angle::half_turn(), Angle::zero()).radians(), kPi);
  EXPECT_EQ(angle_diff(Angle::zero(), Angle::half_turn()).radians(), kPi);
  EXPECT_EQ(angle_diff(Angle::quarter_turn(), -Angle::quarter_turn()).radians(), kPi);
}

TEST(GeomAngleTest, NearWorksAcrossTheWrap) {
  EXPECT_TRUE(near(Angle::from_degrees(179.0), Angle::from_degrees(-179.0), Angle::from_degrees(3.0)));
  EXPECT_FALSE(near(Angle::from_degrees(179.0), Angle::from_degrees(-179.0), Angle::from_degrees(1.0)));
  EXPECT_TRUE(near(Angle::half_turn(), Angle::from_radians(-kPi + 1e-12), Angle::from_radians(1e-9)));
  EXPECT_TRUE(near(Angle::zero(), Angle::from_degrees(-0.5), Angle::from_degrees(-1.0)));  // |tolerance|
  EXPECT_FALSE(near(Angle::zero(), Angle::from_degrees(2.0), Angle::from_degrees(1.0)));
}

TEST(GeomAngleTest, NonFiniteInputGivesNaN) {
  EXPECT_TRUE(std::isnan(Angle::from_radians(kNaN).radians()));
  EXPECT_TRUE(std::isnan(Angle::from_radians(kInf).radians()));
  EXPECT_TRUE(std::isnan(Angle::from_degrees(-kInf).radians()));
  EXPECT_TRUE(std::isnan(Angle::from_vector({kNaN, 1.0}).radians()));
  EXPECT_TRUE(std::isnan((Angle::quarter_turn() / 0.0).radians()));
  EXPECT_TRUE(std::isnan((Angle::from_radians(kNaN) + Angle::quarter_turn()).radians()));
}

TEST(GeomAngleTest, NaNIsUnequalAndNeverNear) {
  const Angle nan = Angle::from_radians(kNaN);
  EXPECT_FALSE(nan == nan);
  EXPECT_TRUE(nan != nan);
  EXPECT_FALSE(nan < Angle::zero());
  EXPECT_FALSE(near(nan, Angle::zero(), Angle::half_turn()));
  EXPECT_FALSE(near(Angle::zero(), Angle::zero(), nan));
}

TEST(GeomAngleTest, PrintsRadiansAndDegrees) {
  std::ostringstream out;
  out << Angle::quarter_turn();
  EXPECT_EQ(out.str(), "1.5708 rad (90 deg)");
}

TEST(GeomAngleTest, PropertyWrappedValueIsInHalfOpenRangeAndDiffersByWholeTurns) {
  std::mt19937 rng(20240601);
  std::uniform_real_distribution<double> radians(-200.0, 200.0);
  for (int i = 0; i < 10000; ++i) {
    const double x = radians(rng);
    const double wrapped = Angle::from_radians(x).radians();
    ASSERT_GT(wrapped, -kPi) << x;
    ASSERT_LE(wrapped, kPi) << x;
    const double turns = (x - wrapped) / (2.0 * kPi);
    ASSERT_NEAR(turns, std::round(turns), 1e-12) << x;
  }
}

TEST(GeomAngleTest, PropertyAngleDiffStaysInRangeAndUndoesTheDifference) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> radians(-50.0, 50.0);
  for (int i = 0; i < 10000; ++i) {
    const Angle a = Angle::from_radians(radians(rng));
    const Angle b = Angle::from_radians(radians(rng));
    const Angle diff = angle_diff(a, b);
    ASSERT_GT(diff.radians(), -kPi);
    ASSERT_LE(diff.radians(), kPi);
    ASSERT_TRUE(near(b + diff, a, Angle::from_radians(1e-12)));
    // Shortest: no other representative of the same turn is smaller in magnitude.
    ASSERT_LE(std::abs(diff.radians()), std::abs(diff.radians() - 2.0 * kPi) + 1e-15);
    ASSERT_LE(std::abs(diff.radians()), std::abs(diff.radians() + 2.0 * kPi) + 1e-15);
  }
}

TEST(GeomAngleTest, PropertyVectorRoundTripIsNear) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> radians(-kPi, kPi);
  for (int i = 0; i < 1000; ++i) {
    const Angle a = Angle::from_radians(radians(rng));
    ASSERT_TRUE(near(Angle::from_vector(3.5 * a.to_unit_vector()), a, Angle::from_radians(1e-14)));
  }
}

}  // namespace
}  // namespace ssl::geom
