#include "libs/behavior_tree/node.h"

#include <ostream>
#include <stdexcept>

namespace ssl::bt {

std::string_view to_string(NodeStatus status) noexcept {
  switch (status) {
    case NodeStatus::kIdle:
      return "IDLE";
    case NodeStatus::kRunning:
      return "RUNNING";
    case NodeStatus::kSuccess:
      return "SUCCESS";
    case NodeStatus::kFailure:
      return "FAILURE";
  }
  return "UNKNOWN";
}

std::ostream& operator<<(std::ostream& out, NodeStatus status) { return out << to_string(status); }

Node::Node(std::string name, NodeKind kind, std::vector<NodePtr> children, Ports ports)
    : name_(std::move(name)),
      path_(name_),
      kind_(kind),
      children_(std::move(children)),
      ports_(std::move(ports)),
      port_entries_(ports_.size(), nullptr) {
  if (name_.empty()) throw std::invalid_argument("a behaviour-tree node needs a name");
  if (name_.find('/') != std::string::npos) {
    throw std::invalid_argument("node name '" + name_ +
                                "' contains '/', which separates names in node paths");
  }
  for (const NodePtr& child : children_) {
    if (!child) throw std::invalid_argument("node '" + name_ + "' was given a null child");
  }
}

NodeStatus Node::tick(const TickContext& context) {
  const NodeStatus answer = on_tick(context);
  if (answer == NodeStatus::kIdle) {
    throw std::logic_error("node '" + path_ +
                           "' answered IDLE to a tick; a tick must answer RUNNING, SUCCESS or FAILURE");
  }
  status_ = answer;
  last_tick_ = context.tick_number;
  return answer;
}

void Node::halt() {
  if (status_ != NodeStatus::kRunning) return;
  on_halt();
  status_ = NodeStatus::kIdle;
}

void Node::on_halt() { halt_children_from(0); }

void Node::halt_children_from(std::size_t first) noexcept {
  for (std::size_t i = first; i < children_.size(); ++i) children_[i]->halt();
}

Result<detail::Entry*> Node::port_entry(std::string_view key, std::type_index type,
                                        PortDirection direction) const {
  const Port* same_key = nullptr;
  for (std::size_t i = 0; i < ports_.size(); ++i) {
    const Port& port = ports_[i];
    if (port.key != key) continue;
    same_key = &port;
    if (port.direction != direction) continue;
    if (port.type != type) {
      return Error{"node '" + path_ + "' accesses blackboard key '" + std::string(key) + "' as " +
                   detail::type_name(type) + " but declares it as " + port.type_name};
    }
    if (port_entries_[i] == nullptr) {
      return Error{"node '" + path_ + "' is not part of a Tree, so its ports have no blackboard"};
    }
    return port_entries_[i];
  }
  const std::string verb = direction == PortDirection::kRead ? "reads" : "writes";
  const std::string declare = direction == PortDirection::kRead ? "bt::reads" : "bt::writes";
  if (same_key != nullptr) {
    return Error{"node '" + path_ + "' " + verb + " blackboard key '" + std::string(key) +
                 "' but declares it only for " + std::string(to_string(same_key->direction)) + "; add " +
                 declare + "(key) to its ports"};
  }
  return Error{"node '" + path_ + "' " + verb + " blackboard key '" + std::string(key) +
               "' without declaring it; add " + declare + "(key) to its ports"};
}

}  // namespace ssl::bt
