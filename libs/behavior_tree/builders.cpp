#include "libs/behavior_tree/builders.h"

#include <memory>

namespace ssl::bt {

Children::Children(std::initializer_list<Slot> slots) {
  nodes_.reserve(slots.size());
  for (const Slot& slot : slots) nodes_.push_back(std::move(slot.node));
}

NodePtr sequence(std::string name, Children children) {
  return std::make_unique<Sequence>(std::move(name), std::move(children).take());
}

NodePtr reactive_sequence(std::string name, Children children) {
  return std::make_unique<ReactiveSequence>(std::move(name), std::move(children).take());
}

NodePtr selector(std::string name, Children children) {
  return std::make_unique<Selector>(std::move(name), std::move(children).take());
}

NodePtr reactive_selector(std::string name, Children children) {
  return std::make_unique<ReactiveSelector>(std::move(name), std::move(children).take());
}

NodePtr parallel(std::string name, ParallelPolicy policy, Children children) {
  return std::make_unique<Parallel>(std::move(name), policy, std::move(children).take());
}

NodePtr action(std::string name, ActionFunction on_tick, Ports ports, HaltFunction on_halt) {
  return std::make_unique<FunctionAction>(std::move(name), std::move(on_tick), std::move(ports),
                                          std::move(on_halt));
}

NodePtr condition(std::string name, ConditionFunction check, Ports ports) {
  return std::make_unique<Condition>(std::move(name), std::move(check), std::move(ports));
}

NodePtr inverter(NodePtr child, std::string name) {
  return std::make_unique<Inverter>(std::move(child), std::move(name));
}

NodePtr succeeder(NodePtr child, std::string name) {
  return std::make_unique<Succeeder>(std::move(child), std::move(name));
}

NodePtr failer(NodePtr child, std::string name) {
  return std::make_unique<Failer>(std::move(child), std::move(name));
}

NodePtr repeater(NodePtr child, std::uint32_t times, std::string name) {
  return std::make_unique<Repeater>(std::move(child), times, std::move(name));
}

NodePtr repeat_forever(NodePtr child, std::string name) {
  return Repeater::forever(std::move(child), std::move(name));
}

NodePtr retry_until_successful(NodePtr child, std::uint32_t attempts, std::string name) {
  return std::make_unique<RetryUntilSuccessful>(std::move(child), attempts, std::move(name));
}

NodePtr timeout(NodePtr child, time::Duration limit, std::string name) {
  return std::make_unique<Timeout>(std::move(child), limit, std::move(name));
}

}  // namespace ssl::bt
