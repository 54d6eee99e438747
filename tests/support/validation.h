// Validation functions of the simulated tests (seeds/003): checks of the simulator's ground truth made at every
// tick or camera frame of a lockstep match, never of what a world model believes. Two kinds:
//   - Always: "for all time", a predicate that must hold every time it is evaluated (a phase, a match);
//   - Eventually: "must happen", a predicate that must become true, and stay so for a hold time, by a deadline.
// Each counts its evaluations and keeps the first failure (time and what failed), so that a report says how
// often and where; report() turns it into gtest expectations (call it from the test body, or later from a
// TEST that reads a match played once).
//
//   ssl::testing::Always apart("no two robots closer than 0.19 m");
//   apart.require(closest >= 0.19, t, [&] { return "robots 3 and 5 " + Always::fmt(closest) + " m apart"; });
//   ssl::testing::Eventually kicked("the kicker kicks", /*deadline=*/3.0);
//   kicked.update(ball_speed > 1.0, t);
//   apart.report();
//   kicked.report();
#pragma once

#include <functional>
#include <limits>
#include <optional>
#include <string>

namespace ssl::testing {

class Always {
 public:
  explicit Always(std::string name) : name_(std::move(name)) {}
  /// One evaluation at `t` (s); `detail` says what failed (called for the first failure only).
  void require(bool holds, double t, const std::function<std::string()>& detail);
  /// Expectations: evaluated at least once, never failed (else how often, and the first failure).
  void report() const;

  int evaluated() const { return evaluated_; }
  int failures() const { return failures_; }
  /// "%.4f", for details.
  static std::string fmt(double value);

 private:
  std::string name_;
  int evaluated_ = 0;
  int failures_ = 0;
  std::string first_;
};

class Eventually {
 public:
  /// `deadline` (s, on the caller's clock) by which the predicate must have become true, staying true for
  /// `hold` s.
  Eventually(std::string name, double deadline, double hold = 0)
      : name_(std::move(name)), deadline_(deadline), hold_(hold) {}
  /// One evaluation at `t`; true once satisfied.
  bool update(bool now_true, double t);
  bool done() const { return done_; }
  /// When it became true (the start of the hold), NaN before.
  double at() const { return at_; }
  /// Expectation: it happened; `detail` is added to the failure message.
  void report(const std::string& detail = {}) const;

 private:
  std::string name_;
  double deadline_;
  double hold_;
  bool done_ = false;
  double at_ = std::numeric_limits<double>::quiet_NaN();
  std::optional<double> since_;
};

}  // namespace ssl::testing
