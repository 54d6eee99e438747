// Test helpers for the behaviour-tree tests (not part of the library): leaves whose answers the test
// scripts before each tick, and a shared log of what happened to them, in order.
//
//   ScriptedLeaves leaves;
//   Tree tree(sequence("Root", {leaves.make("A"), leaves.make("B", NodeStatus::kRunning)}));
//   tree.tick(at(1));
//   EXPECT_THAT(leaves.take_log(), ElementsAre("tick A", "tick B"));
//   leaves["B"].answer(NodeStatus::kSuccess);
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "libs/behavior_tree/leaves.h"
#include "libs/behavior_tree/node.h"
#include "libs/time/time.h"

namespace ssl::bt::testing {

// Short names for the statuses the tests compare with.
inline constexpr NodeStatus kIdle = NodeStatus::kIdle;
inline constexpr NodeStatus kRunning = NodeStatus::kRunning;
inline constexpr NodeStatus kSuccess = NodeStatus::kSuccess;
inline constexpr NodeStatus kFailure = NodeStatus::kFailure;

/// A timestamp `ms` milliseconds after the epoch.
inline time::Timestamp at_ms(std::int64_t ms) { return time::Timestamp::from_milliseconds(ms); }

/// An action that answers what the test told it, appending "tick <name>" / "halt <name>" to a log.
class ScriptedAction final : public Action {
 public:
  ScriptedAction(std::string name, NodeStatus answer, std::vector<std::string>& log)
      : Action(std::move(name)), answer_(answer), log_(log) {}

  /// The answer to the following ticks.
  void answer(NodeStatus status) { answer_ = status; }
  int ticks() const { return ticks_; }
  int halts() const { return halts_; }

 private:
  NodeStatus on_tick(const TickContext&) override {
    ++ticks_;
    log_.push_back("tick " + name());
    return answer_;
  }
  void on_halt() override {
    ++halts_;
    log_.push_back("halt " + name());
  }

  NodeStatus answer_;
  std::vector<std::string>& log_;
  int ticks_ = 0;
  int halts_ = 0;
};

/// Makes scripted actions and keeps a handle to each by name (the tree owns them).
class ScriptedLeaves {
 public:
  NodePtr make(const std::string& name, NodeStatus answer = NodeStatus::kSuccess) {
    auto leaf = std::make_unique<ScriptedAction>(name, answer, log_);
    leaves_[name] = leaf.get();
    return leaf;
  }

  ScriptedAction& operator[](const std::string& name) { return *leaves_.at(name); }

  /// The log since the last call, then clears it.
  std::vector<std::string> take_log() { return std::exchange(log_, {}); }

 private:
  std::vector<std::string> log_;
  std::map<std::string, ScriptedAction*> leaves_;
};

}  // namespace ssl::bt::testing
