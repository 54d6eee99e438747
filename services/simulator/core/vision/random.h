// The simulator's source of randomness (the vision model's draws, and the robot response's in streams of
// their own): std::mt19937_64 (fully specified by the standard) plus our own distributions, so the same seed
// and the same calls give the same numbers with any standard library (the std distributions are not
// specified bit for bit). Not thread-safe; each owner has its own.
//
//   VisionRandom random(42);
//   double noise = random.normal() * stddev;
//   if (random.bernoulli(0.05)) drop();
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

namespace ssl::sim {

class VisionRandom {
 public:
  explicit VisionRandom(std::uint64_t seed) : engine_(seed) {}

  /// Uniform in [0, 1), 53 random bits.
  double uniform01() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

  /// Uniform in [low, high).
  double uniform(double low, double high) { return low + (high - low) * uniform01(); }

  /// Standard normal (mean 0, variance 1), Box-Muller; every second call returns the cached partner.
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = 1.0 - uniform01();  // (0, 1]: log is finite
    const double u2 = uniform01();
    const double radius = std::sqrt(-2.0 * std::log(u1));
    const double angle = 2.0 * std::numbers::pi * u2;
    spare_ = radius * std::sin(angle);
    has_spare_ = true;
    return radius * std::cos(angle);
  }

  /// True with probability p. Draws a number only when 0 < p < 1, so a disabled effect (p = 0) leaves the
  /// stream untouched.
  bool bernoulli(double p) {
    if (p <= 0.0) return false;
    if (p >= 1.0) return true;
    return uniform01() < p;
  }

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace ssl::sim
