#include "libs/behavior_tree/tree.h"

#include <stdexcept>
#include <string>

namespace ssl::bt {

Tree::Tree(NodePtr root) : root_(std::move(root)) {
  if (!root_) throw std::invalid_argument("a behaviour tree needs a root node");
  attach(*root_, root_->name(), 0);
}

void Tree::attach(Node& node, const std::string& path, std::size_t depth) {
  node.path_ = path;
  nodes_.push_back(Visit{&node, depth});
  for (std::size_t i = 0; i < node.ports_.size(); ++i) {
    node.port_entries_[i] = &blackboard_.declare(node.ports_[i], node.path_);
  }
  for (std::size_t i = 0; i < node.child_count(); ++i) {
    Node& child = node.mutable_child(i);
    std::size_t same_name = 0;
    for (std::size_t j = 0; j < node.child_count(); ++j) {
      if (node.child(j).name() == child.name()) ++same_name;
    }
    std::string child_path = node.path_ + "/" + child.name();
    if (same_name > 1) child_path += "[" + std::to_string(i) + "]";
    attach(child, child_path, depth + 1);
  }
}

NodeStatus Tree::tick(time::Timestamp now) {
  ++tick_count_;
  return root_->tick(TickContext{now, tick_count_});
}

void Tree::halt() { root_->halt(); }

void Tree::snapshot(std::vector<NodeSnapshot>& rows) const {
  rows.clear();
  for (const Visit& visit : nodes_) {
    const Node& node = *visit.node;
    rows.push_back(NodeSnapshot{node.path(), node.name(), node.type_name(), node.status(), node.last_tick(),
                                visit.depth});
  }
}

std::vector<NodeSnapshot> Tree::snapshot() const {
  std::vector<NodeSnapshot> rows;
  rows.reserve(nodes_.size());
  snapshot(rows);
  return rows;
}

std::vector<PortDeclaration> Tree::port_declarations() const {
  std::vector<PortDeclaration> declarations;
  for (const Visit& visit : nodes_) {
    for (const Port& port : visit.node->ports()) {
      declarations.push_back(PortDeclaration{visit.node->path(), port.key, port.direction, port.type_name});
    }
  }
  return declarations;
}

}  // namespace ssl::bt
