// Role assignment: which robot takes which position of a formation.
//
// `optimal_assignment` solves the linear assignment problem (Hungarian method, O(n^3), n <= 16) on a cost
// matrix, with ties broken by index so that the answer is deterministic. `StableAssigner` wraps it with
// hysteresis: for the same formation (same key, same robots, same number of slots) it keeps last tick's
// assignment unless the optimal one is cheaper by more than `hysteresis` metres AND 10 %, so roles do not
// flap when two robots are about equally good. Single-robot roles (the kicker, the placer) use
// `StableChoice`: keep the current robot while it is within `hysteresis` of the best.
//
//   StableAssigner assigner(0.3);
//   std::span<const int> slot_of_robot = assigner.assign(key, robot_ids, robot_positions, slot_positions);
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "libs/domain/world.h"

namespace ssl::planner {

inline constexpr std::size_t kMaxSlots = wm::kMaxRobotsPerTeam;

/// cost[r][s] for r < rows, s < cols (rows <= cols); returns for each row its column.
using CostMatrix = std::array<std::array<double, kMaxSlots>, kMaxSlots>;
std::array<int, kMaxSlots> optimal_assignment(const CostMatrix& cost, std::size_t rows, std::size_t cols);

class StableAssigner {
 public:
  explicit StableAssigner(double hysteresis = 0.3) : hysteresis_(hysteresis) {}

  /// For each robot (same order as `ids`), the slot it takes; slots beyond the robot count stay empty and
  /// robots beyond the slot count get -1. Costs are distances.
  std::span<const int> assign(std::uint32_t key, std::span<const std::uint32_t> ids,
                              std::span<const wm::Vec2> robots, std::span<const wm::Vec2> slots);
  /// The same over given costs: cost[r][s] of robot r (order of `ids`) in slot s < `slots` (any unit: the
  /// hysteresis is in that unit, e.g. seconds to reach plus a role's misfit).
  std::span<const int> assign_costs(std::uint32_t key, std::span<const std::uint32_t> ids, const CostMatrix& cost,
                                    std::size_t slots);

  void reset() { valid_ = false; }

 private:
  double hysteresis_;
  bool valid_ = false;
  std::uint32_t key_ = 0;
  std::size_t slot_count_ = 0;
  std::array<std::uint32_t, kMaxSlots> ids_{};
  std::size_t id_count_ = 0;
  std::array<int, kMaxSlots> result_{};
};

/// One robot chosen by a score (lower is better) that changes only when another is clearly better.
class StableChoice {
 public:
  explicit StableChoice(double hysteresis = 0.3) : hysteresis_(hysteresis) {}

  /// Among `ids` with `scores`, the chosen id; nullopt when `ids` is empty.
  std::optional<std::uint32_t> choose(std::span<const std::uint32_t> ids, std::span<const double> scores);
  void reset() { current_.reset(); }

 private:
  double hysteresis_;
  std::optional<std::uint32_t> current_;
};

}  // namespace ssl::planner
