// Composite nodes: they tick their children in order and combine the answers. Every composite needs at
// least one child (std::invalid_argument otherwise).
//
//   (S)  Sequence          AND / checklist. Ticks children left to right while they succeed; fails at the
//                          first failure; succeeds when all succeeded. With MEMORY: a child that answers
//                          RUNNING makes the sequence answer RUNNING, and the next tick resumes at that child
//                          (the children before it are not re-checked).
//   (S*) ReactiveSequence  The same, but every tick starts again at the first child, so earlier children
//                          (typically conditions) are re-checked. When an earlier child now fails or runs,
//                          a later child that was running is halted.
//   (?)  Selector          OR / fallback. Ticks children left to right while they fail; succeeds at the
//                          first success; fails when all failed. With MEMORY: resumes at the running child.
//   (?*) ReactiveSelector  The same, but every tick starts again at the first child. When an earlier child
//                          now succeeds or runs, a later child that was running is halted (higher priority
//                          plans pre-empt lower ones).
//   (P)  Parallel          Ticks every unfinished child on every tick, in order; a child that finished
//                          (success or failure) is not ticked again until the parallel node finishes or is
//                          halted. The policy decides when it finishes:
//                            kSuccessOnOne: SUCCESS as soon as one child succeeds; FAILURE once all failed.
//                            kSuccessOnAll: SUCCESS once all succeeded; FAILURE as soon as one child fails.
//                          Once the outcome is decided, the children after the deciding one are not ticked
//                          in that tick, and every child still running is halted.
//
// When any composite finishes (SUCCESS or FAILURE), none of its children is left running.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "libs/behavior_tree/node.h"

namespace ssl::bt {

/// Base of the composites: checks that there is at least one child.
class Composite : public Node {
 protected:
  /// @throws std::invalid_argument if `children` is empty or holds a null node.
  Composite(std::string name, NodeKind kind, std::vector<NodePtr> children);
};

class Sequence final : public Composite {
 public:
  Sequence(std::string name, std::vector<NodePtr> children);
  std::string_view type_name() const override { return "Sequence"; }

 private:
  NodeStatus on_tick(const TickContext& context) override;

  std::size_t current_ = 0;  ///< the child to resume at, valid while continues_run()
};

class ReactiveSequence final : public Composite {
 public:
  ReactiveSequence(std::string name, std::vector<NodePtr> children);
  std::string_view type_name() const override { return "ReactiveSequence"; }

 private:
  NodeStatus on_tick(const TickContext& context) override;
};

class Selector final : public Composite {
 public:
  Selector(std::string name, std::vector<NodePtr> children);
  std::string_view type_name() const override { return "Selector"; }

 private:
  NodeStatus on_tick(const TickContext& context) override;

  std::size_t current_ = 0;  ///< the child to resume at, valid while continues_run()
};

class ReactiveSelector final : public Composite {
 public:
  ReactiveSelector(std::string name, std::vector<NodePtr> children);
  std::string_view type_name() const override { return "ReactiveSelector"; }

 private:
  NodeStatus on_tick(const TickContext& context) override;
};

enum class ParallelPolicy { kSuccessOnOne, kSuccessOnAll };

class Parallel final : public Composite {
 public:
  Parallel(std::string name, ParallelPolicy policy, std::vector<NodePtr> children);
  std::string_view type_name() const override { return "Parallel"; }
  /// "success on one" / "success on all".
  std::string parameters() const override;
  ParallelPolicy policy() const noexcept { return policy_; }

 private:
  NodeStatus on_tick(const TickContext& context) override;
  /// Halts the children still running and answers `outcome`.
  NodeStatus finish(NodeStatus outcome);

  ParallelPolicy policy_;
  std::vector<NodeStatus> outcomes_;  ///< per child in the current run: kIdle until it finished
};

}  // namespace ssl::bt
