// Builders: short functions that make nodes, so that a tree written in C++ reads like its drawing.
//
//   using namespace std::chrono_literals;
//   namespace bt = ssl::bt;
//
//   bt::NodePtr attacker = bt::reactive_selector("Attacker", {
//       bt::sequence("Shoot", {
//           bt::condition("HaveBall?", have_ball, {bt::reads(kBallOwner)}),
//           bt::timeout(bt::action("AimAndKick", aim_and_kick, {bt::reads(kGoalTarget)}), 2s),
//       }),
//       bt::action("GoToBall", go_to_ball, {bt::reads(kBallPosition)}),
//   });
//
// Children go in braces. (A std::initializer_list cannot hand out move-only std::unique_ptr, so the braces
// build a `Children`, which takes each node over; a std::vector<NodePtr> works too, for generated trees.)
// Decorators are named after their type unless given a name. Invalid arguments throw
// std::invalid_argument (see the node classes).
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "libs/behavior_tree/blackboard.h"
#include "libs/behavior_tree/composites.h"
#include "libs/behavior_tree/decorators.h"
#include "libs/behavior_tree/leaves.h"
#include "libs/behavior_tree/node.h"
#include "libs/time/time.h"

namespace ssl::bt {

/// The children of a composite: `{node, node, ...}` or a std::vector<NodePtr>.
class Children {
 public:
  /// One node of a braced list. Holding the pointer `mutable` lets `Children` move it out of the
  /// (const) initializer_list; each slot is taken exactly once.
  struct Slot {
    Slot(NodePtr child) : node(std::move(child)) {}  // NOLINT: implicit, so that braces take plain NodePtr
    mutable NodePtr node;
  };

  Children(std::initializer_list<Slot> slots);
  Children(std::vector<NodePtr> nodes) : nodes_(std::move(nodes)) {}  // NOLINT: implicit by design

  std::vector<NodePtr> take() && { return std::move(nodes_); }

 private:
  std::vector<NodePtr> nodes_;
};

NodePtr sequence(std::string name, Children children);
NodePtr reactive_sequence(std::string name, Children children);
NodePtr selector(std::string name, Children children);
NodePtr reactive_selector(std::string name, Children children);
NodePtr parallel(std::string name, ParallelPolicy policy, Children children);

/// An action from a callable `NodeStatus(LeafContext&)`; `on_halt` (optional) stops work in progress.
NodePtr action(std::string name, ActionFunction on_tick, Ports ports = {}, HaltFunction on_halt = {});
/// A condition from a callable `bool(const LeafContext&)`; its ports must all be reads.
NodePtr condition(std::string name, ConditionFunction check, Ports ports = {});

NodePtr inverter(NodePtr child, std::string name = "Inverter");
NodePtr succeeder(NodePtr child, std::string name = "Succeeder");
NodePtr failer(NodePtr child, std::string name = "Failer");
NodePtr repeater(NodePtr child, std::uint32_t times, std::string name = "Repeater");
NodePtr repeat_forever(NodePtr child, std::string name = "Repeater");
NodePtr retry_until_successful(NodePtr child, std::uint32_t attempts,
                               std::string name = "RetryUntilSuccessful");
NodePtr timeout(NodePtr child, time::Duration limit, std::string name = "Timeout");

}  // namespace ssl::bt
