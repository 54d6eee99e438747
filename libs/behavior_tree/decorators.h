// Decorator nodes: exactly one child, whose answer they transform. RUNNING always passes through, so a
// decorator runs exactly while its child runs (except Timeout, which may stop its child), and halting a
// decorator halts its child.
//
//   Inverter              SUCCESS <-> FAILURE.
//   Succeeder             any finished answer becomes SUCCESS ("try it, but carry on anyway").
//   Failer                any finished answer becomes FAILURE.
//   Repeater(n)           runs the child to completion n times in a row: each child SUCCESS counts one run
//                         and answers RUNNING until the n-th, which answers SUCCESS. A child FAILURE fails
//                         the repeater at once. Repeater::forever() never succeeds (it only stops by failing
//                         or by being halted). At most one run of the child completes per tick, so a child
//                         that succeeds at once cannot make a tick loop.
//   RetryUntilSuccessful(n)  gives the child up to n attempts: child SUCCESS answers SUCCESS; a child FAILURE
//                         answers RUNNING and tries again on the next tick, until the n-th failure, which
//                         answers FAILURE. One attempt per tick at most.
//   Timeout(limit)        FAILURE if the child is still running when `TickContext::now` reaches the start of
//                         the run + limit: at that tick the child is halted instead of ticked. The run starts
//                         at the first tick after the timeout node was idle or finished, and the child is
//                         always ticked then. Time only comes from `now`; if `now` goes backwards, the
//                         timeout simply fires later.
//
// Counters (repeats, attempts) and the timeout's start belong to one run: they restart whenever the
// decorator starts a new run (after it finished or was halted).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "libs/behavior_tree/node.h"
#include "libs/time/time.h"

namespace ssl::bt {

/// Base of the decorators: exactly one child.
class Decorator : public Node {
 protected:
  /// @throws std::invalid_argument if `child` is null or `name` is invalid.
  Decorator(std::string name, NodePtr child);

  Node& decorated() noexcept { return mutable_child(0); }
};

class Inverter final : public Decorator {
 public:
  explicit Inverter(NodePtr child, std::string name = "Inverter");
  std::string_view type_name() const override { return "Inverter"; }

 private:
  NodeStatus on_tick(const TickContext& context) override;
};

class Succeeder final : public Decorator {
 public:
  explicit Succeeder(NodePtr child, std::string name = "Succeeder");
  std::string_view type_name() const override { return "Succeeder"; }

 private:
  NodeStatus on_tick(const TickContext& context) override;
};

class Failer final : public Decorator {
 public:
  explicit Failer(NodePtr child, std::string name = "Failer");
  std::string_view type_name() const override { return "Failer"; }

 private:
  NodeStatus on_tick(const TickContext& context) override;
};

class Repeater final : public Decorator {
 public:
  /// @throws std::invalid_argument if `times` is 0.
  Repeater(NodePtr child, std::uint32_t times, std::string name = "Repeater");
  /// A repeater that never succeeds.
  static std::unique_ptr<Repeater> forever(NodePtr child, std::string name = "Repeater");

  std::string_view type_name() const override { return "Repeater"; }
  /// "3 times" / "forever".
  std::string parameters() const override;

 private:
  Repeater(NodePtr child, std::optional<std::uint32_t> times, std::string name);
  NodeStatus on_tick(const TickContext& context) override;

  std::optional<std::uint32_t> times_;  ///< nullopt: forever
  std::uint32_t completed_runs_ = 0;
};

class RetryUntilSuccessful final : public Decorator {
 public:
  /// @throws std::invalid_argument if `attempts` is 0.
  RetryUntilSuccessful(NodePtr child, std::uint32_t attempts, std::string name = "RetryUntilSuccessful");
  std::string_view type_name() const override { return "RetryUntilSuccessful"; }
  /// "3 attempts".
  std::string parameters() const override;

 private:
  NodeStatus on_tick(const TickContext& context) override;

  std::uint32_t attempts_;
  std::uint32_t failed_attempts_ = 0;
};

class Timeout final : public Decorator {
 public:
  /// @throws std::invalid_argument if `limit` is not positive.
  Timeout(NodePtr child, time::Duration limit, std::string name = "Timeout");
  std::string_view type_name() const override { return "Timeout"; }
  /// The limit, compactly: "2s", "150ms", "250us", "10ns".
  std::string parameters() const override;

 private:
  NodeStatus on_tick(const TickContext& context) override;

  time::Duration limit_;
  time::Timestamp deadline_;  ///< start of the current run + limit_
};

/// "2s", "1500ms", "250us", "10ns": the largest unit that shows `duration` exactly.
std::string compact_duration(time::Duration duration);

}  // namespace ssl::bt
