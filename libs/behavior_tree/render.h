// Drawings of a tree with its latest statuses: an ASCII tree for logs and terminals, Graphviz DOT for
// pictures (`dot -Tsvg tree.dot > tree.svg`). Both only read the nodes; they allocate and are meant for
// debugging, not for every tick.
//
// ASCII uses the legend of our behaviour-tree design notes, one node per line. A striker that was kicking
// at tick 1 and lost the ball at tick 2, drawn after tick 2:
//
//   (?*) Root                           RUNNING
//   |--(S*) Shoot                       FAILURE
//   |  |--{ HaveBall? } <-- ball_owner  FAILURE
//   |  `--<Timeout 2s>                  IDLE (tick 1)
//   |     `--[ Kick ] --> kick_target   IDLE (tick 1)
//   `--[ GoToBall ] <-- ball_position   RUNNING
//
//   (?)  Selector            (?*) reactive Selector          [ name ]  Action
//   (S)  Sequence            (S*) reactive Sequence          { name }  Condition
//   (P)  Parallel, with its policy after the name: "(P) Both (success on one)"
//   <Type parameters> name   a decorator, e.g. "<Repeater 3 times> ThreeKicks"; the name is left out when it
//                            is the type's name: "<Inverter>"
//   <-- keys                 the blackboard keys the node reads;  --> keys  the keys it writes
//
// The status column holds the node's status(): IDLE if it was never ticked or was halted. When the node
// was last ticked before the latest tick (the root's last tick), its tick number follows: "SUCCESS (tick 3)"
// is history, not the present.
//
// DOT draws the same tree top-down. Shape by type: Sequence box, Selector octagon, Parallel parallelogram,
// Action rounded box, Condition ellipse, Decorator hexagon (reactive composites have a double outline).
// Fill by last status: RUNNING amber, SUCCESS green, FAILURE red, IDLE white; nodes the latest tick did not
// reach have a dashed outline. Each label holds the name, the type with its parameters (on the name's line
// when the name is the type's name, e.g. "Timeout: 2s"), the ports and the status text.
#pragma once

#include <string>

#include "libs/behavior_tree/node.h"

namespace ssl::bt {

struct RenderOptions {
  bool show_status = true;  ///< false: the structure only (no status column, no colours)
  bool show_ports = true;
};

/// The subtree under `root` as ASCII art, one line per node, each ending in '\n'.
std::string to_ascii(const Node& root, const RenderOptions& options = {});

/// The subtree under `root` as a Graphviz digraph.
std::string to_dot(const Node& root, const RenderOptions& options = {});

}  // namespace ssl::bt
