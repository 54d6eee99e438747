// ssl::bt: behaviour trees for the planner and the coach, namespace ssl::bt. Include this header for all
// of it.
//
//   node.h        Node, NodeStatus, TickContext: the tick/halt contract
//   composites.h  Sequence, Selector (with memory and reactive), Parallel
//   decorators.h  Inverter, Succeeder, Failer, Repeater, RetryUntilSuccessful, Timeout
//   leaves.h      Action, Condition and the LeafContext their callables get
//   blackboard.h  Key<T>, ports (reads/writes) and the typed Blackboard
//   tree.h        Tree: owns the nodes and the blackboard; tick(now), halt(), snapshot(), port listing
//   builders.h    sequence(...), selector(...), action(...), timeout(...) ...
//   render.h      to_ascii / to_dot
//
// A whole example:
//
//   namespace bt = ssl::bt;
//   using namespace std::chrono_literals;
//   inline constexpr bt::Key<bool> kHaveBall{"have_ball"};
//   inline constexpr bt::Key<geom::Vec2> kKickTarget{"kick_target"};
//
//   bt::Tree tree(bt::reactive_selector("Striker", {
//       bt::sequence("Shoot", {
//           bt::condition("HaveBall?", [](const bt::LeafContext& leaf) {
//             ssl::Result<bool> have_ball = leaf.get(kHaveBall);
//             return have_ball && *have_ball;
//           }, {bt::reads(kHaveBall)}),
//           bt::timeout(bt::action("Kick", kick, {bt::writes(kKickTarget)}), 2s),
//       }),
//       bt::action("GoToBall", go_to_ball),
//   }));
//
//   // every planner cycle:
//   if (!tree.blackboard().set(kHaveBall, world.we_have_ball())) { ... }   // Status: a typo'd key fails
//   tree.tick(now);
//   publish(tree.snapshot());                 // or log bt::to_ascii(tree.root())
//
// Rules the library keeps: no globals, no threads, no clocks (time is `now`), no allocation while ticking;
// errors while ticking are values (Result/Status), construction errors throw std::invalid_argument.
#pragma once

#include "libs/behavior_tree/blackboard.h"
#include "libs/behavior_tree/builders.h"
#include "libs/behavior_tree/composites.h"
#include "libs/behavior_tree/decorators.h"
#include "libs/behavior_tree/leaves.h"
#include "libs/behavior_tree/node.h"
#include "libs/behavior_tree/render.h"
#include "libs/behavior_tree/tree.h"
