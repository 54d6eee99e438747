// The league's two divisions, and the rule numbers that depend only on the division. One enum for every
// service (config files spell it "a" / "b"; field dimensions by division: field.h).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace ssl {

enum class Division { kA, kB };

/// "a" or "b": the spelling of flags (--division) and config files.
constexpr std::string_view to_string(Division division) { return division == Division::kA ? "a" : "b"; }

constexpr std::optional<Division> parse_division(std::string_view text) {
  if (text == "a") return Division::kA;
  if (text == "b") return Division::kB;
  return std::nullopt;
}

/// Robots a team may have on the field (rules: 11 in division A, 6 in B).
constexpr std::uint32_t max_robots_per_team(Division division) { return division == Division::kA ? 11 : 6; }

/// A time limit the rules give per division, in seconds (e.g. free kick 5 s in A, 10 s in B).
struct DivisionSeconds {
  double a = 0;
  double b = 0;
  constexpr double of(Division division) const { return division == Division::kA ? a : b; }
};

}  // namespace ssl
