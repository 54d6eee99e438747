// Leaf nodes: where the work happens.
//
//   [ ] Action     does something; answers SUCCESS, FAILURE or RUNNING (work that takes several ticks).
//                  When its parent stops ticking it while it runs, it is halted and must stop that work.
//   { } Condition  asks a question about the world without changing anything; answers SUCCESS (true) or
//                  FAILURE (false) in the same tick, never RUNNING. It may only declare read ports.
//
// Both are usually built from callables (builders.h); a callable receives a `LeafContext` that gives the
// tick's time and the node's checked blackboard access. A stateful action can instead derive from Action:
//
//   class DriveTo final : public bt::Action {
//    public:
//     explicit DriveTo(Motion& motion) : Action("DriveTo", {bt::reads(kTarget)}), motion_(motion) {}
//    private:
//     bt::NodeStatus on_tick(const bt::TickContext& tick) override {
//       ssl::Result<geom::Vec2> target = get(kTarget);
//       if (!target) return bt::NodeStatus::kFailure;
//       return motion_.drive_to(*target, tick.now) ? bt::NodeStatus::kSuccess : bt::NodeStatus::kRunning;
//     }
//     void on_halt() override { motion_.stop(); }
//     Motion& motion_;
//   };
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "libs/behavior_tree/blackboard.h"
#include "libs/behavior_tree/node.h"
#include "libs/common/result.h"
#include "libs/time/time.h"

namespace ssl::bt {

/// What a leaf's callable sees during a tick: the time, and the blackboard through the leaf's ports
/// (same checks and errors as `Node::get`/`Node::set`). Valid only during that call.
class LeafContext {
 public:
  LeafContext(Node& node, const TickContext& tick) noexcept : node_(node), tick_(tick) {}

  time::Timestamp now() const noexcept { return tick_.now; }
  std::uint64_t tick_number() const noexcept { return tick_.tick_number; }
  /// The path of the leaf being ticked, for log messages.
  const std::string& node_path() const noexcept { return node_.path(); }

  template <typename T>
  Result<T> get(const Key<T>& key) const {
    return node_.get(key);
  }
  template <typename T>
  Status set(const Key<T>& key, const std::type_identity_t<T>& value) {
    return node_.set(key, value);
  }
  template <typename T>
  Status set(const Key<T>& key, std::type_identity_t<T>&& value) {
    return node_.set(key, std::move(value));
  }

 private:
  Node& node_;
  const TickContext& tick_;
};

using ActionFunction = std::function<NodeStatus(LeafContext&)>;
using HaltFunction = std::function<void()>;
using ConditionFunction = std::function<bool(const LeafContext&)>;

/// Base of actions. Derive from it for actions with state, overriding `on_tick` and `on_halt`.
class Action : public Node {
 public:
  std::string_view type_name() const override { return "Action"; }

 protected:
  explicit Action(std::string name, Ports ports = {});
};

/// An action made of callables.
class FunctionAction final : public Action {
 public:
  /// `on_halt` may be empty (nothing to stop).
  /// @throws std::invalid_argument if `on_tick` is empty.
  FunctionAction(std::string name, ActionFunction on_tick, Ports ports = {}, HaltFunction on_halt = {});

 private:
  NodeStatus on_tick(const TickContext& context) override;
  void on_halt() override;

  ActionFunction tick_function_;
  HaltFunction halt_function_;
};

class Condition final : public Node {
 public:
  /// @throws std::invalid_argument if `check` is empty or a port is a write port.
  Condition(std::string name, ConditionFunction check, Ports ports = {});
  std::string_view type_name() const override { return "Condition"; }

 private:
  NodeStatus on_tick(const TickContext& context) override;

  ConditionFunction check_;
};

}  // namespace ssl::bt
