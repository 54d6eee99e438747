// Node: the base of every behaviour-tree node, its status and what a tick receives.
//
// Contract of a tick. A parent calls `tick(context)`; the node does one step of work and answers
// kSuccess, kFailure or kRunning (never kIdle). kRunning means "not finished: tick me again". A node that
// answered kRunning stays responsible for work in progress until it either finishes on a later tick or is
// halted: a parent that stops ticking a running child (because it finished, or a reactive composite chose
// an earlier child) calls `halt()` on it. Halting a running node halts its running descendants, lets it
// clean up (`on_halt`) and sets its status to kIdle; halting a node that is not running does nothing.
//
// Time is an input: `TickContext::now` comes from the caller's clock (real or simulated); no node reads a
// clock. The library allocates nothing while ticking (nodes keep their per-run state in members sized at
// construction); leaves written for it should not either.
//
// Debugging. Every node remembers its last status and the number of the tick it was last ticked in
// (`status()`, `last_tick()`); a node that was not reached by the latest tick keeps its old values, so
// comparing `last_tick()` with the root's tells what the latest tick visited. Idle means "never ticked
// since construction or the last halt".
//
// Nodes are built with the helpers in builders.h and owned by a `Tree` (tree.h), which gives each node its
// path and connects its ports to the blackboard.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <typeindex>
#include <utility>
#include <vector>

#include "libs/behavior_tree/blackboard.h"
#include "libs/common/result.h"
#include "libs/time/time.h"

namespace ssl::bt {

enum class NodeStatus { kIdle, kRunning, kSuccess, kFailure };

/// "IDLE", "RUNNING", "SUCCESS", "FAILURE".
std::string_view to_string(NodeStatus status) noexcept;
std::ostream& operator<<(std::ostream& out, NodeStatus status);

/// The node families, as renderers draw them.
enum class NodeKind {
  kSequence,
  kReactiveSequence,
  kSelector,
  kReactiveSelector,
  kParallel,
  kAction,
  kCondition,
  kDecorator,
};

/// What every node of one tick sees.
struct TickContext {
  time::Timestamp now;            ///< the caller's clock at this tick; decorators measure time with it
  std::uint64_t tick_number = 0;  ///< 1 for the first tick of a tree; 0 is reserved for "never ticked"
};

class Node;
using NodePtr = std::unique_ptr<Node>;

class Node {
 public:
  Node(const Node&) = delete;
  Node& operator=(const Node&) = delete;
  virtual ~Node() = default;

  /// Runs one step and records the answer and the tick number.
  /// @throws std::logic_error if the node answers kIdle (a bug in the node, not a runtime condition).
  NodeStatus tick(const TickContext& context);

  /// If running: halts the running descendants, runs `on_halt()` and becomes kIdle. Otherwise nothing.
  void halt();

  const std::string& name() const noexcept { return name_; }
  /// "Root/Attack/Shoot" once the node is part of a Tree (see tree.h for how duplicates are told apart);
  /// the bare name before that.
  const std::string& path() const noexcept { return path_; }
  NodeKind kind() const noexcept { return kind_; }
  /// The concrete type, e.g. "ReactiveSequence", "Timeout" (stable: used in debug data).
  virtual std::string_view type_name() const = 0;
  /// The node's settings in words, e.g. "2s" for a Timeout, "" if it has none.
  virtual std::string parameters() const { return {}; }

  /// The answer of the last tick, or kIdle if never ticked or halted since.
  NodeStatus status() const noexcept { return status_; }
  /// The tick number the node was last ticked in; 0 if never.
  std::uint64_t last_tick() const noexcept { return last_tick_; }

  std::size_t child_count() const noexcept { return children_.size(); }
  /// Precondition: index < child_count().
  const Node& child(std::size_t index) const noexcept { return *children_[index]; }
  /// The blackboard keys this node declares it reads and writes.
  std::span<const Port> ports() const noexcept { return ports_; }

 protected:
  /// @throws std::invalid_argument if the name is empty or contains '/', or a child is null.
  Node(std::string name, NodeKind kind, std::vector<NodePtr> children = {}, Ports ports = {});

  /// One step of the node's work. While it runs, `status()` still holds the previous tick's answer.
  virtual NodeStatus on_tick(const TickContext& context) = 0;

  /// Cleanup when halted while running. The default halts every child; overrides of composites and
  /// decorators must keep doing that.
  virtual void on_halt();

  /// True while the node is in the middle of a run: its previous answer was kRunning.
  bool continues_run() const noexcept { return status_ == NodeStatus::kRunning; }

  /// The child to tick or halt. Precondition: index < child_count().
  Node& mutable_child(std::size_t index) noexcept { return *children_[index]; }

  /// Halts every child from `first` on (the ones that are not running ignore it).
  void halt_children_from(std::size_t first) noexcept;

  /// Reads `key` through this node's read port. Errors: undeclared port, other type, not in a Tree, unset.
  template <typename T>
  Result<T> get(const Key<T>& key) const {
    Result<detail::Entry*> entry = port_entry(key.name, typeid(T), PortDirection::kRead);
    if (!entry) return entry.error();
    return detail::read_value<T>(**entry, key.name, path_);
  }

  /// Writes `key` through this node's write port. Errors: undeclared port, other type, not in a Tree.
  template <typename T>
  Status set(const Key<T>& key, const std::type_identity_t<T>& value) {
    return store<T>(key, value);
  }
  template <typename T>
  Status set(const Key<T>& key, std::type_identity_t<T>&& value) {
    return store<T>(key, std::move(value));
  }

 private:
  friend class Tree;
  friend class LeafContext;

  template <typename T, typename V>
  Status store(const Key<T>& key, V&& value) {
    Result<detail::Entry*> entry = port_entry(key.name, typeid(T), PortDirection::kWrite);
    if (!entry) return entry.error();
    detail::write_value<T>(**entry, std::forward<V>(value));
    return Status::success();
  }

  /// The bound entry of the port (key, direction), checked against the requested type.
  Result<detail::Entry*> port_entry(std::string_view key, std::type_index type,
                                    PortDirection direction) const;

  std::string name_;
  std::string path_;
  NodeKind kind_;
  std::vector<NodePtr> children_;
  Ports ports_;
  std::vector<detail::Entry*> port_entries_;  ///< parallel to ports_; set by the owning Tree
  NodeStatus status_ = NodeStatus::kIdle;
  std::uint64_t last_tick_ = 0;
};

}  // namespace ssl::bt
