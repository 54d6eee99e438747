// Tree: owns a root node and the blackboard its nodes share; ticks it, halts it and describes it.
//
// Construction walks the nodes once: it gives each node its path, creates one blackboard entry per
// declared key and connects every port to its entry. After that, ticking does no lookups by name and
// allocates nothing.
//
// Paths name nodes uniquely: the names from the root down, joined by '/' ("Root/Attack/Shoot"). When
// siblings share a name, each of them gets its child index appended ("Root/Kick[0]", "Root/Kick[2]").
//
//   bt::Tree tree(bt::selector("Root", {...}));
//   tree.blackboard().set(kBallPosition, ball);     // inputs, before the tick
//   bt::NodeStatus status = tree.tick(now);         // `now` from the planner's clock
//   tree.snapshot(debug_rows);                      // reuses the vector: no allocation once it is big enough
//
// Not thread-safe; tick one tree from one thread. Nothing is global: two trees share nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "libs/behavior_tree/blackboard.h"
#include "libs/behavior_tree/node.h"
#include "libs/time/time.h"

namespace ssl::bt {

/// One node's debug state. The views point into the tree and stay valid as long as it exists.
struct NodeSnapshot {
  std::string_view path;
  std::string_view name;
  std::string_view type;  ///< Node::type_name(), e.g. "ReactiveSelector"
  NodeStatus status = NodeStatus::kIdle;
  std::uint64_t last_tick = 0;  ///< 0: never ticked
  std::size_t depth = 0;        ///< 0 for the root; rows are in depth-first order, so depth rebuilds the tree
};

/// One port of one node. The views point into the tree.
struct PortDeclaration {
  std::string_view node_path;
  std::string_view key;
  PortDirection direction = PortDirection::kRead;
  std::string_view type_name;
};

class Tree {
 public:
  /// @throws std::invalid_argument if `root` is null or two ports declare one key with different types.
  explicit Tree(NodePtr root);

  /// Ticks the root once with `now` (the caller's clock). The tick number grows by one per call.
  NodeStatus tick(time::Timestamp now);

  /// Halts everything still running (e.g. when the planner switches to another tree).
  void halt();

  const Node& root() const noexcept { return *root_; }
  Blackboard& blackboard() noexcept { return blackboard_; }
  const Blackboard& blackboard() const noexcept { return blackboard_; }

  /// Number of ticks so far (= the tick number of the latest tick).
  std::uint64_t tick_count() const noexcept { return tick_count_; }
  /// Number of nodes, root included.
  std::size_t size() const noexcept { return nodes_.size(); }

  /// Every node's debug state in depth-first order, into `rows` (cleared first; its capacity is reused).
  void snapshot(std::vector<NodeSnapshot>& rows) const;
  std::vector<NodeSnapshot> snapshot() const;

  /// Every declared port of every node, in depth-first node order, then declaration order.
  std::vector<PortDeclaration> port_declarations() const;

 private:
  struct Visit {
    const Node* node;
    std::size_t depth;
  };

  void attach(Node& node, const std::string& path, std::size_t depth);

  NodePtr root_;
  Blackboard blackboard_;
  std::vector<Visit> nodes_;  ///< depth-first order
  std::uint64_t tick_count_ = 0;
};

}  // namespace ssl::bt
