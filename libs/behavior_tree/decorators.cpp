#include "libs/behavior_tree/decorators.h"

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace ssl::bt {
namespace {

std::vector<NodePtr> only_child(NodePtr child) {
  std::vector<NodePtr> children;
  children.push_back(std::move(child));
  return children;
}

}  // namespace

Decorator::Decorator(std::string name, NodePtr child)
    : Node(std::move(name), NodeKind::kDecorator, only_child(std::move(child))) {}

Inverter::Inverter(NodePtr child, std::string name) : Decorator(std::move(name), std::move(child)) {}

NodeStatus Inverter::on_tick(const TickContext& context) {
  switch (decorated().tick(context)) {
    case NodeStatus::kSuccess:
      return NodeStatus::kFailure;
    case NodeStatus::kFailure:
      return NodeStatus::kSuccess;
    default:
      return NodeStatus::kRunning;
  }
}

Succeeder::Succeeder(NodePtr child, std::string name) : Decorator(std::move(name), std::move(child)) {}

NodeStatus Succeeder::on_tick(const TickContext& context) {
  const NodeStatus answer = decorated().tick(context);
  return answer == NodeStatus::kRunning ? NodeStatus::kRunning : NodeStatus::kSuccess;
}

Failer::Failer(NodePtr child, std::string name) : Decorator(std::move(name), std::move(child)) {}

NodeStatus Failer::on_tick(const TickContext& context) {
  const NodeStatus answer = decorated().tick(context);
  return answer == NodeStatus::kRunning ? NodeStatus::kRunning : NodeStatus::kFailure;
}

Repeater::Repeater(NodePtr child, std::uint32_t times, std::string name)
    : Repeater(std::move(child), std::optional<std::uint32_t>(times), std::move(name)) {
  if (times == 0) throw std::invalid_argument("repeater '" + this->name() + "' must repeat at least once");
}

Repeater::Repeater(NodePtr child, std::optional<std::uint32_t> times, std::string name)
    : Decorator(std::move(name), std::move(child)), times_(times) {}

std::unique_ptr<Repeater> Repeater::forever(NodePtr child, std::string name) {
  return std::unique_ptr<Repeater>(new Repeater(std::move(child), std::nullopt, std::move(name)));
}

std::string Repeater::parameters() const {
  if (!times_) return "forever";
  return std::to_string(*times_) + (*times_ == 1 ? " time" : " times");
}

NodeStatus Repeater::on_tick(const TickContext& context) {
  if (!continues_run()) completed_runs_ = 0;
  const NodeStatus answer = decorated().tick(context);
  if (answer != NodeStatus::kSuccess) return answer;
  ++completed_runs_;
  if (times_ && completed_runs_ >= *times_) return NodeStatus::kSuccess;
  return NodeStatus::kRunning;
}

RetryUntilSuccessful::RetryUntilSuccessful(NodePtr child, std::uint32_t attempts, std::string name)
    : Decorator(std::move(name), std::move(child)), attempts_(attempts) {
  if (attempts == 0) {
    throw std::invalid_argument("retry node '" + this->name() + "' must allow at least one attempt");
  }
}

std::string RetryUntilSuccessful::parameters() const {
  return std::to_string(attempts_) + (attempts_ == 1 ? " attempt" : " attempts");
}

NodeStatus RetryUntilSuccessful::on_tick(const TickContext& context) {
  if (!continues_run()) failed_attempts_ = 0;
  const NodeStatus answer = decorated().tick(context);
  if (answer != NodeStatus::kFailure) return answer;
  ++failed_attempts_;
  return failed_attempts_ >= attempts_ ? NodeStatus::kFailure : NodeStatus::kRunning;
}

Timeout::Timeout(NodePtr child, time::Duration limit, std::string name)
    : Decorator(std::move(name), std::move(child)), limit_(limit) {
  if (limit <= time::Duration::zero()) {
    throw std::invalid_argument("timeout '" + this->name() + "' needs a positive limit, got " +
                                time::to_string(limit));
  }
}

std::string Timeout::parameters() const { return compact_duration(limit_); }

NodeStatus Timeout::on_tick(const TickContext& context) {
  if (!continues_run()) {
    deadline_ = context.now + limit_;
  } else if (context.now >= deadline_) {
    decorated().halt();
    return NodeStatus::kFailure;
  }
  return decorated().tick(context);
}

std::string compact_duration(time::Duration duration) {
  const auto count = duration.count();
  if (count % 1'000'000'000 == 0) return std::to_string(count / 1'000'000'000) + "s";
  if (count % 1'000'000 == 0) return std::to_string(count / 1'000'000) + "ms";
  if (count % 1'000 == 0) return std::to_string(count / 1'000) + "us";
  return std::to_string(count) + "ns";
}

}  // namespace ssl::bt
