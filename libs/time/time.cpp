#include "libs/time/time.h"

#include <cmath>
#include <cstdio>

namespace ssl::time {
namespace {

constexpr std::int64_t kNanosPerSecond = 1'000'000'000;
constexpr double kNanosPerSecondDouble = 1e9;
// Every int64 below 2^53 is exactly representable as a double.
constexpr std::int64_t kExactDoubleLimit = std::int64_t{1} << 53;

// Formats a signed nanosecond count as seconds with 9 decimals, without going through a double.
std::string format_seconds(std::int64_t ns) {
  const bool negative = ns < 0;
  const std::uint64_t magnitude =
      negative ? std::uint64_t{0} - static_cast<std::uint64_t>(ns) : static_cast<std::uint64_t>(ns);
  char text[48];
  std::snprintf(text, sizeof text, "%s%llu.%09llu", negative ? "-" : "",
                static_cast<unsigned long long>(magnitude / kNanosPerSecond),
                static_cast<unsigned long long>(magnitude % kNanosPerSecond));
  return text;
}

}  // namespace

std::optional<std::int64_t> try_unix_seconds_to_ns(double seconds) noexcept {
  if (!std::isfinite(seconds)) return std::nullopt;
  // Split into whole seconds and a fraction in [0, 1) so that the multiplication by 1e9 only touches the
  // fraction: multiplying a Unix-era value directly would lose ~256 ns to double rounding.
  const double whole = std::floor(seconds);
  const double fraction = seconds - whole;
  // int64 nanoseconds cover [-9223372036.854775808, 9223372036.854775807] seconds.
  if (whole < -9223372037.0 || whole > 9223372036.0) return std::nullopt;
  const auto whole_s = static_cast<std::int64_t>(whole);
  const std::int64_t fraction_ns = std::llround(fraction * kNanosPerSecondDouble);  // [0, 1e9]
  std::int64_t ns = 0;
  if (__builtin_mul_overflow(whole_s, kNanosPerSecond, &ns)) return std::nullopt;
  if (__builtin_add_overflow(ns, fraction_ns, &ns)) return std::nullopt;
  return ns;
}

std::int64_t unix_seconds_to_ns(double seconds) noexcept {
  if (std::isnan(seconds)) return 0;
  if (std::optional<std::int64_t> ns = try_unix_seconds_to_ns(seconds)) return *ns;
  return seconds < 0 ? std::numeric_limits<std::int64_t>::min() : std::numeric_limits<std::int64_t>::max();
}

double ns_to_unix_seconds(std::int64_t nanoseconds) noexcept {
  if (nanoseconds > -kExactDoubleLimit && nanoseconds < kExactDoubleLimit) {
    // One correctly rounded division: the nearest double to the exact value.
    return static_cast<double>(nanoseconds) / kNanosPerSecondDouble;
  }
  // Whole seconds are exact in a double; the remainder adds well below the double's resolution here.
  const std::int64_t whole = nanoseconds / kNanosPerSecond;
  const std::int64_t remainder = nanoseconds % kNanosPerSecond;
  return static_cast<double>(whole) + static_cast<double>(remainder) / kNanosPerSecondDouble;
}

std::string to_string(Timestamp t) { return format_seconds(t.nanoseconds()); }

std::string to_string(Duration d) { return format_seconds(d.count()) + "s"; }

}  // namespace ssl::time
