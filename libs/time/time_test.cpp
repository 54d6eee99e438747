#include "libs/time/time.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace ssl::time {
namespace {

using namespace std::chrono_literals;

TEST(TimestampTest, DefaultIsTheEpoch) {
  EXPECT_EQ(Timestamp{}.nanoseconds(), 0);
  EXPECT_EQ(Timestamp{}, Timestamp::from_nanoseconds(0));
}

TEST(TimestampTest, FactoriesAgreeOnUnits) {
  EXPECT_EQ(Timestamp::from_microseconds(1'500), Timestamp::from_nanoseconds(1'500'000));
  EXPECT_EQ(Timestamp::from_milliseconds(2), Timestamp::from_nanoseconds(2'000'000));
  EXPECT_EQ(Timestamp::from_seconds(1.5), Timestamp::from_nanoseconds(1'500'000'000));
  EXPECT_EQ(Timestamp::from_since_epoch(3s), Timestamp::from_nanoseconds(3'000'000'000));
  EXPECT_EQ(Timestamp::from_nanoseconds(1'234'567).microseconds(), 1'234);
}

TEST(TimestampTest, ArithmeticWithDurations) {
  const Timestamp t = Timestamp::from_seconds(10.0);
  EXPECT_EQ(t + 16ms, Timestamp::from_nanoseconds(10'016'000'000));
  EXPECT_EQ(16ms + t, t + 16ms);
  EXPECT_EQ(t - 1s, Timestamp::from_seconds(9.0));
  EXPECT_EQ((t + 250us) - t, Duration(250'000));
  EXPECT_EQ(t - (t + 1ms), -1ms);

  Timestamp u = t;
  u += 2s;
  u -= 500ms;
  EXPECT_EQ(u, Timestamp::from_seconds(11.5));
}

TEST(TimestampTest, ComparisonsAreTotal) {
  const Timestamp a = Timestamp::from_nanoseconds(1);
  const Timestamp b = Timestamp::from_nanoseconds(2);
  EXPECT_LT(a, b);
  EXPECT_LE(a, a);
  EXPECT_GT(b, a);
  EXPECT_NE(a, b);
  EXPECT_LT(Timestamp::min(), Timestamp{});
  EXPECT_GT(Timestamp::max(), Timestamp{});
}

TEST(TimestampTest, ToSecondsOfSmallValuesIsExact) {
  EXPECT_DOUBLE_EQ(Timestamp::from_nanoseconds(1'500'000'000).to_seconds(), 1.5);
  EXPECT_EQ(Timestamp::from_nanoseconds(-250'000'000).to_seconds(), -0.25);
  EXPECT_EQ(to_seconds(16ms), 0.016);
}

TEST(ConversionTest, DoubleSecondsRoundToNearestNanosecond) {
  EXPECT_EQ(unix_seconds_to_ns(1e-9), 1);
  EXPECT_EQ(unix_seconds_to_ns(1.4e-9), 1);
  EXPECT_EQ(unix_seconds_to_ns(1.6e-9), 2);
  EXPECT_EQ(unix_seconds_to_ns(0.1), 100'000'000);  // 0.1 is 0.1000000000000000055... in binary
  EXPECT_EQ(unix_seconds_to_ns(-0.1), -100'000'000);
  EXPECT_EQ(unix_seconds_to_ns(-1.5), -1'500'000'000);
  EXPECT_EQ(unix_seconds_to_ns(0.9999999999), 1'000'000'000);  // fraction rounds up into the next second
}

TEST(ConversionTest, UnixEraVisionTimeIsConvertedFromTheExactDoubleValue) {
  // A typical SSL-Vision t_capture. The double nearest to 1700000000.123456789 is
  // 1700000000.1234567165374755859375, so the nearest nanosecond is ...123456717.
  const double t_capture = 1700000000.123456789;
  EXPECT_EQ(unix_seconds_to_ns(t_capture), 1'700'000'000'123'456'717);
}

TEST(ConversionTest, DoubleToNanosecondsToDoubleRoundTripsExactlyForUnixEraTimes) {
  for (double t : {1700000000.123456789, 1700000000.0, 1712345678.999999, 1e9 + 0.5, 0.016, 123.456}) {
    const Timestamp ts = Timestamp::from_seconds(t);
    EXPECT_EQ(ts.to_seconds(), t) << to_string(ts);
  }
}

TEST(ConversionTest, NanosecondsToDoubleToNanosecondsIsExactBelowAboutFourMillionSeconds) {
  for (std::int64_t ns : {std::int64_t{1}, std::int64_t{999'999'999}, std::int64_t{-123'456'789},
                          std::int64_t{4'000'000'123'456'789}}) {
    EXPECT_EQ(unix_seconds_to_ns(ns_to_unix_seconds(ns)), ns);
  }
}

TEST(ConversionTest, NanosecondsToDoubleToNanosecondsIsWithinHalfADoubleStepForUnixEraTimes) {
  // At 1.7e9 s a double resolves 2^-22 s (~238 ns): the round trip stays within half of that.
  const std::int64_t ns = 1'700'000'000'123'456'789;
  EXPECT_LE(std::abs(unix_seconds_to_ns(ns_to_unix_seconds(ns)) - ns), 120);
}

TEST(ConversionTest, NonFiniteAndOutOfRangeSecondsAreRejectedOrSaturated) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(try_unix_seconds_to_ns(nan).has_value());
  EXPECT_FALSE(try_unix_seconds_to_ns(inf).has_value());
  EXPECT_FALSE(try_unix_seconds_to_ns(1e10).has_value());
  EXPECT_FALSE(try_unix_seconds_to_ns(-1e10).has_value());
  EXPECT_TRUE(try_unix_seconds_to_ns(9.2e9).has_value());
  EXPECT_FALSE(Timestamp::try_from_seconds(nan).has_value());
  EXPECT_EQ(Timestamp::try_from_seconds(2.0), Timestamp::from_seconds(2.0));

  EXPECT_EQ(unix_seconds_to_ns(nan), 0);
  EXPECT_EQ(unix_seconds_to_ns(inf), std::numeric_limits<std::int64_t>::max());
  EXPECT_EQ(unix_seconds_to_ns(-inf), std::numeric_limits<std::int64_t>::min());
  EXPECT_EQ(unix_seconds_to_ns(1e300), std::numeric_limits<std::int64_t>::max());
}

TEST(ConversionTest, DurationFromSeconds) {
  EXPECT_EQ(duration_from_seconds(0.016), 16ms);
  EXPECT_EQ(duration_from_seconds(-2.5), -2500ms);
}

TEST(ToStringTest, PrintsSecondsWithNineDecimals) {
  EXPECT_EQ(to_string(Timestamp::from_nanoseconds(1'700'000'000'000'000'001)), "1700000000.000000001");
  EXPECT_EQ(to_string(Timestamp::from_nanoseconds(-500'000'000)), "-0.500000000");
  EXPECT_EQ(to_string(Timestamp::min()), "-9223372036.854775808");
  EXPECT_EQ(to_string(Duration(16ms)), "0.016000000s");
}

}  // namespace
}  // namespace ssl::time
