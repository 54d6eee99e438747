#include "libs/behavior_tree/composites.h"

#include <algorithm>
#include <stdexcept>

namespace ssl::bt {

Composite::Composite(std::string name, NodeKind kind, std::vector<NodePtr> children)
    : Node(std::move(name), kind, std::move(children)) {
  if (child_count() == 0) {
    throw std::invalid_argument("composite node '" + this->name() + "' has no children");
  }
}

Sequence::Sequence(std::string name, std::vector<NodePtr> children)
    : Composite(std::move(name), NodeKind::kSequence, std::move(children)) {}

NodeStatus Sequence::on_tick(const TickContext& context) {
  if (!continues_run()) current_ = 0;
  for (; current_ < child_count(); ++current_) {
    const NodeStatus answer = mutable_child(current_).tick(context);
    if (answer != NodeStatus::kSuccess) return answer;
  }
  return NodeStatus::kSuccess;
}

ReactiveSequence::ReactiveSequence(std::string name, std::vector<NodePtr> children)
    : Composite(std::move(name), NodeKind::kReactiveSequence, std::move(children)) {}

NodeStatus ReactiveSequence::on_tick(const TickContext& context) {
  for (std::size_t i = 0; i < child_count(); ++i) {
    const NodeStatus answer = mutable_child(i).tick(context);
    if (answer != NodeStatus::kSuccess) {
      halt_children_from(i + 1);
      return answer;
    }
  }
  return NodeStatus::kSuccess;
}

Selector::Selector(std::string name, std::vector<NodePtr> children)
    : Composite(std::move(name), NodeKind::kSelector, std::move(children)) {}

NodeStatus Selector::on_tick(const TickContext& context) {
  if (!continues_run()) current_ = 0;
  for (; current_ < child_count(); ++current_) {
    const NodeStatus answer = mutable_child(current_).tick(context);
    if (answer != NodeStatus::kFailure) return answer;
  }
  return NodeStatus::kFailure;
}

ReactiveSelector::ReactiveSelector(std::string name, std::vector<NodePtr> children)
    : Composite(std::move(name), NodeKind::kReactiveSelector, std::move(children)) {}

NodeStatus ReactiveSelector::on_tick(const TickContext& context) {
  for (std::size_t i = 0; i < child_count(); ++i) {
    const NodeStatus answer = mutable_child(i).tick(context);
    if (answer != NodeStatus::kFailure) {
      halt_children_from(i + 1);
      return answer;
    }
  }
  return NodeStatus::kFailure;
}

Parallel::Parallel(std::string name, ParallelPolicy policy, std::vector<NodePtr> children)
    : Composite(std::move(name), NodeKind::kParallel, std::move(children)),
      policy_(policy),
      outcomes_(child_count(), NodeStatus::kIdle) {}

std::string Parallel::parameters() const {
  return policy_ == ParallelPolicy::kSuccessOnOne ? "success on one" : "success on all";
}

NodeStatus Parallel::on_tick(const TickContext& context) {
  if (!continues_run()) std::fill(outcomes_.begin(), outcomes_.end(), NodeStatus::kIdle);
  std::size_t successes = 0;
  std::size_t failures = 0;
  for (std::size_t i = 0; i < child_count(); ++i) {
    if (outcomes_[i] == NodeStatus::kIdle) {
      const NodeStatus answer = mutable_child(i).tick(context);
      if (answer != NodeStatus::kRunning) outcomes_[i] = answer;
    }
    if (outcomes_[i] == NodeStatus::kSuccess) ++successes;
    if (outcomes_[i] == NodeStatus::kFailure) ++failures;
    if (policy_ == ParallelPolicy::kSuccessOnOne && successes > 0) return finish(NodeStatus::kSuccess);
    if (policy_ == ParallelPolicy::kSuccessOnAll && failures > 0) return finish(NodeStatus::kFailure);
  }
  if (policy_ == ParallelPolicy::kSuccessOnOne && failures == child_count()) {
    return finish(NodeStatus::kFailure);
  }
  if (policy_ == ParallelPolicy::kSuccessOnAll && successes == child_count()) {
    return finish(NodeStatus::kSuccess);
  }
  return NodeStatus::kRunning;
}

NodeStatus Parallel::finish(NodeStatus outcome) {
  halt_children_from(0);
  return outcome;
}

}  // namespace ssl::bt
