#include "libs/behavior_tree/leaves.h"

#include <stdexcept>

namespace ssl::bt {

Action::Action(std::string name, Ports ports)
    : Node(std::move(name), NodeKind::kAction, {}, std::move(ports)) {}

FunctionAction::FunctionAction(std::string name, ActionFunction on_tick, Ports ports, HaltFunction on_halt)
    : Action(std::move(name), std::move(ports)),
      tick_function_(std::move(on_tick)),
      halt_function_(std::move(on_halt)) {
  if (!tick_function_) throw std::invalid_argument("action '" + this->name() + "' has no tick function");
}

NodeStatus FunctionAction::on_tick(const TickContext& context) {
  LeafContext leaf(*this, context);
  return tick_function_(leaf);
}

void FunctionAction::on_halt() {
  if (halt_function_) halt_function_();
}

Condition::Condition(std::string name, ConditionFunction check, Ports ports)
    : Node(std::move(name), NodeKind::kCondition, {}, std::move(ports)), check_(std::move(check)) {
  if (!check_) throw std::invalid_argument("condition '" + this->name() + "' has no check function");
  for (const Port& port : this->ports()) {
    if (port.direction == PortDirection::kWrite) {
      throw std::invalid_argument("condition '" + this->name() + "' declares a write port for key '" +
                                  port.key + "'; conditions only read (make it an action)");
    }
  }
}

NodeStatus Condition::on_tick(const TickContext& context) {
  const LeafContext leaf(*this, context);
  return check_(leaf) ? NodeStatus::kSuccess : NodeStatus::kFailure;
}

}  // namespace ssl::bt
