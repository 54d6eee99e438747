// Angle: a plane angle, stored in radians and always wrapped to the half-open interval (-pi, pi].
//
// A strong type, so degrees, radians and "a double that happens to be an angle" cannot be mixed up
// (SI inside: build from degrees only at the wire edge). Every factory and every arithmetic result is
// wrapped, so Angle::from_degrees(270) == Angle::from_degrees(-90) and the half turn is always +pi.
//
// Equality compares the wrapped values exactly; use near() to compare with a tolerance. The ordering
// (<, <=, ...) compares the wrapped radians on the number line, not around the circle: it is there for
// sorting and containers. For "which way and how far to turn" use angle_diff().
//
//   Angle heading = Angle::from_degrees(170) + Angle::from_degrees(20);  // wraps to -170 degrees
//   Angle turn = angle_diff(target, heading);                            // shortest signed turn
//
// Non-finite input (NaN, +-inf, division by zero) gives a NaN angle. NaN propagates through arithmetic,
// compares unequal to everything and is never near() anything.
#pragma once

#include <cmath>
#include <compare>
#include <numbers>
#include <ostream>

#include <Eigen/Core>

namespace ssl::geom {

class Angle {
 public:
  // Zero radians.
  constexpr Angle() = default;

  // The angle `radians` wrapped to (-pi, pi].
  static Angle from_radians(double radians) { return Angle(wrap(radians)); }
  // The angle `degrees` wrapped to (-180, 180] degrees. Whole degrees convert exactly at 90 and 180.
  static Angle from_degrees(double degrees) {
    double wrapped = std::remainder(degrees, 360.0);  // exact; in [-180, 180]
    if (wrapped <= -180.0) wrapped += 360.0;
    return from_radians(wrapped / 180.0 * std::numbers::pi);
  }
  // Direction of the vector (x, y) measured counter-clockwise from +x; the zero vector gives zero.
  static Angle from_vector(const Eigen::Vector2d& v) { return from_radians(std::atan2(v.y(), v.x())); }

  // Zero.
  static constexpr Angle zero() { return Angle(0.0); }
  // pi radians (180 degrees), the largest value an Angle holds.
  static constexpr Angle half_turn() { return Angle(std::numbers::pi); }
  // pi/2 radians (90 degrees).
  static constexpr Angle quarter_turn() { return Angle(std::numbers::pi / 2.0); }

  // Radians in (-pi, pi].
  constexpr double radians() const { return radians_; }
  // Degrees in (-180, 180].
  constexpr double degrees() const { return radians_ / std::numbers::pi * 180.0; }
  // Unit vector (cos, sin) pointing in this direction.
  Eigen::Vector2d to_unit_vector() const { return {std::cos(radians_), std::sin(radians_)}; }

  // Arithmetic wraps after each operation, so (a * 2) / 2 need not equal a.
  Angle operator-() const { return from_radians(-radians_); }
  Angle& operator+=(Angle other) { return *this = from_radians(radians_ + other.radians_); }
  Angle& operator-=(Angle other) { return *this = from_radians(radians_ - other.radians_); }
  Angle& operator*=(double scale) { return *this = from_radians(radians_ * scale); }
  Angle& operator/=(double divisor) { return *this = from_radians(radians_ / divisor); }
  friend Angle operator+(Angle a, Angle b) { return a += b; }
  friend Angle operator-(Angle a, Angle b) { return a -= b; }
  friend Angle operator*(Angle a, double scale) { return a *= scale; }
  friend Angle operator*(double scale, Angle a) { return a *= scale; }
  friend Angle operator/(Angle a, double divisor) { return a /= divisor; }

  // Exact comparison of the wrapped radians (see the header comment; NaN is unordered).
  friend constexpr bool operator==(Angle a, Angle b) = default;
  friend constexpr std::partial_ordering operator<=>(Angle a, Angle b) = default;

  // Magnitude in [0, pi].
  friend Angle abs(Angle a) { return Angle(std::abs(a.radians_)); }

  // Prints "1.5708 rad (90 deg)".
  friend std::ostream& operator<<(std::ostream& out, Angle a) {
    return out << a.radians_ << " rad (" << a.degrees() << " deg)";
  }

 private:
  constexpr explicit Angle(double wrapped_radians) : radians_(wrapped_radians) {}

  static double wrap(double radians) {
    constexpr double kPi = std::numbers::pi;
    if (radians > -kPi && radians <= kPi) return radians;       // the common case, and exact
    const double wrapped = std::remainder(radians, 2.0 * kPi);  // exact; in [-pi, pi]; NaN stays NaN
    return wrapped <= -kPi ? wrapped + 2.0 * kPi : wrapped;
  }

  double radians_ = 0.0;
};

// Shortest signed rotation that takes `from` to `to`, in (-pi, pi]; positive is counter-clockwise.
// Opposite directions give +pi.
inline Angle angle_diff(Angle to, Angle from) { return to - from; }

// True when a and b are within |tolerance| of each other around the circle (so -pi and pi are near).
inline bool near(Angle a, Angle b, Angle tolerance) {
  return abs(angle_diff(a, b)).radians() <= abs(tolerance).radians();
}

}  // namespace ssl::geom
