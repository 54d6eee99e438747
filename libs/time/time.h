// Strong time types for the whole stack: `Duration` (a span of time) and `Timestamp` (a point in time on a
// named clock), both with nanosecond resolution in a signed 64-bit count (range about +-292 years).
//
// The clocks we use. A Timestamp does not carry its clock at run time, so every variable, field and
// parameter that holds one names its clock (e.g. `t_capture_vision`, `received_wall`, `deadline_mono`):
//
//   * SSL-Vision capture clock: `t_capture` / `t_sent` in SSL_DetectionFrame, Unix seconds (double) read
//     from the VISION HOST's wall clock. Compare only with other vision times unless the offset to our
//     host is estimated; never subtract it from our own clock to get a "latency" without that offset.
//   * Host wall clock: Unix time on this host, CLOCK_REALTIME (`RealClock`). Used to stamp messages and
//     compare them across processes on one host (and across hosts when NTP/PTP keeps them in sync).
//     It can jump when the time is set, so do not use it for timeouts.
//   * Host monotonic clock: CLOCK_MONOTONIC (`MonotonicClock`), epoch = boot. Never jumps; use it for
//     timeouts, periods and measuring elapsed time. Meaningless across hosts and reboots.
//   * Simulated clock: `SimulatedClock`, advanced only by the simulator or a test (lockstep runs, CI).
//     Production code takes a `Clock&` so that the same code runs on real and simulated time.
//
// Conversions from the double seconds of SSL-Vision round to the NEAREST nanosecond of the double's exact
// value, so double -> Timestamp -> double is exact for Unix-era times (a double then resolves ~240 ns).
//
//   using namespace std::chrono_literals;
//   ssl::time::Timestamp t_capture_vision = ssl::time::Timestamp::from_seconds(frame.t_capture());
//   ssl::time::Timestamp expires_vision = t_capture_vision + 100ms;
//   ssl::time::Duration age = now_vision - t_capture_vision;          // Timestamp - Timestamp = Duration
//   double seconds = ssl::time::to_seconds(age);
#pragma once

#include <chrono>
#include <compare>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

namespace ssl::time {

/// A signed span of time in nanoseconds. Build it with std::chrono literals (`16ms`) or
/// `duration_from_seconds`; read it with `to_seconds` or std::chrono::duration_cast.
using Duration = std::chrono::nanoseconds;

/// Nanoseconds for a double number of seconds, rounded to nearest; NaN gives 0 and values outside the
/// int64 range saturate to its limits. Use `try_unix_seconds_to_ns` when the input comes from the network.
std::int64_t unix_seconds_to_ns(double seconds) noexcept;

/// Like `unix_seconds_to_ns`, but nullopt for NaN, infinities and values outside about +-292 years.
std::optional<std::int64_t> try_unix_seconds_to_ns(double seconds) noexcept;

/// Seconds for a nanosecond count, as the double nearest to the exact value (exact up to 2^53 ns).
double ns_to_unix_seconds(std::int64_t nanoseconds) noexcept;

/// Duration for a double number of seconds, rounded to the nearest nanosecond (saturating, NaN -> 0).
inline Duration duration_from_seconds(double seconds) noexcept {
  return Duration(unix_seconds_to_ns(seconds));
}

/// Seconds in a Duration, as a double.
inline double to_seconds(Duration duration) noexcept { return ns_to_unix_seconds(duration.count()); }

/// A point in time: nanoseconds since the epoch of the clock it came from (Unix epoch for the vision,
/// wall and usually the simulated clock; boot for the monotonic clock). A plain value: cheap to copy,
/// totally ordered, default-constructed to the epoch. Arithmetic does not check for overflow.
class Timestamp {
 public:
  constexpr Timestamp() noexcept = default;

  static constexpr Timestamp from_nanoseconds(std::int64_t nanoseconds) noexcept {
    return Timestamp(nanoseconds);
  }
  static constexpr Timestamp from_microseconds(std::int64_t microseconds) noexcept {
    return Timestamp(microseconds * 1'000);
  }
  static constexpr Timestamp from_milliseconds(std::int64_t milliseconds) noexcept {
    return Timestamp(milliseconds * 1'000'000);
  }
  /// Rounded to the nearest nanosecond; NaN gives the epoch and out-of-range values saturate.
  static Timestamp from_seconds(double seconds) noexcept { return Timestamp(unix_seconds_to_ns(seconds)); }
  /// nullopt for NaN, infinities and values outside the representable range (for untrusted input).
  static std::optional<Timestamp> try_from_seconds(double seconds) noexcept {
    std::optional<std::int64_t> ns = try_unix_seconds_to_ns(seconds);
    if (!ns) return std::nullopt;
    return Timestamp(*ns);
  }
  static constexpr Timestamp from_since_epoch(Duration since_epoch) noexcept {
    return Timestamp(since_epoch.count());
  }
  static constexpr Timestamp min() noexcept { return Timestamp(std::numeric_limits<std::int64_t>::min()); }
  static constexpr Timestamp max() noexcept { return Timestamp(std::numeric_limits<std::int64_t>::max()); }

  constexpr std::int64_t nanoseconds() const noexcept { return ns_; }
  /// Truncated toward zero, like std::chrono::duration_cast.
  constexpr std::int64_t microseconds() const noexcept { return ns_ / 1'000; }
  constexpr Duration since_epoch() const noexcept { return Duration(ns_); }
  double to_seconds() const noexcept { return ns_to_unix_seconds(ns_); }

  constexpr Timestamp& operator+=(Duration d) noexcept {
    ns_ += d.count();
    return *this;
  }
  constexpr Timestamp& operator-=(Duration d) noexcept {
    ns_ -= d.count();
    return *this;
  }
  friend constexpr Timestamp operator+(Timestamp t, Duration d) noexcept { return t += d; }
  friend constexpr Timestamp operator+(Duration d, Timestamp t) noexcept { return t += d; }
  friend constexpr Timestamp operator-(Timestamp t, Duration d) noexcept { return t -= d; }
  friend constexpr Duration operator-(Timestamp a, Timestamp b) noexcept { return Duration(a.ns_ - b.ns_); }
  friend constexpr auto operator<=>(Timestamp, Timestamp) noexcept = default;
  friend constexpr bool operator==(Timestamp, Timestamp) noexcept = default;

 private:
  constexpr explicit Timestamp(std::int64_t ns) noexcept : ns_(ns) {}
  std::int64_t ns_ = 0;
};

/// "1700000000.123456789" (seconds with 9 decimals) for logs and test failure messages.
std::string to_string(Timestamp t);
/// "0.016000000s".
std::string to_string(Duration d);

}  // namespace ssl::time
