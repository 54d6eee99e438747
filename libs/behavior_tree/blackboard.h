// The typed blackboard of a behaviour tree: named values that nodes share, each with a fixed C++ type.
//
// A `Key<T>` names a value and fixes its type; it is usually a constant next to the nodes that use it.
// Nodes declare the keys they touch as ports (`reads(key)`, `writes(key)`); a `Tree` creates one blackboard
// entry per declared key when it is built, so a key exists exactly when some node declares it, and two
// declarations of one key with different types are rejected then (std::invalid_argument).
//
// Error policy. Nothing on the blackboard throws while a tree ticks: a read returns `Result<T>`, a write
// returns `Status`, and each error message names the key, the types and the node involved. Errors are:
//   * the key is not declared (by the accessing node, for node access; by any node, for access from outside),
//   * the key is accessed with another type than it was declared with, or written through a read port,
//   * the key has no value yet (nothing wrote it). To make "no value" normal data, store std::optional<U>.
//
// Values live in storage created once at tree construction; reading copies the value out, writing assigns
// into that storage. Neither allocates for types that do not allocate on copy. For large values, store a
// std::shared_ptr<const U> so that a read copies a pointer.
//
//   inline constexpr bt::Key<geom::Vec2> kBallPosition{"ball_position"};
//   inline constexpr bt::Key<int> kPassReceiver{"pass_receiver"};
//
//   tree.blackboard().set(kBallPosition, ball);          // the planner feeds inputs before a tick
//   ssl::Result<int> receiver = tree.blackboard().get(kPassReceiver);
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <typeindex>
#include <typeinfo>
#include <utility>
#include <vector>

#include "libs/common/result.h"

namespace ssl::bt {

/// The name and type of one blackboard value. A cheap handle: the name must outlive every use of the key
/// (a string literal, as in `inline constexpr Key<double> kSpeed{"speed"};`).
template <typename T>
struct Key {
  static_assert(std::is_same_v<T, std::remove_cvref_t<T>>, "a blackboard key's type is a plain value type");
  static_assert(std::is_copy_constructible_v<T>, "blackboard values are copied out on read");

  std::string_view name;
};

namespace detail {

/// Readable name of a C++ type for error messages and port listings ("double", "ssl::geom::Vec2").
std::string type_name(std::type_index type);

/// Storage for one key; created once per key when a tree is built.
class Entry {
 public:
  Entry(const Entry&) = delete;
  Entry& operator=(const Entry&) = delete;
  virtual ~Entry() = default;

  std::type_index type() const noexcept { return type_; }
  const std::string& type_name() const noexcept { return type_name_; }
  virtual bool has_value() const noexcept = 0;

 protected:
  Entry(std::type_index type, std::string type_name) : type_(type), type_name_(std::move(type_name)) {}

 private:
  std::type_index type_;
  std::string type_name_;
};

template <typename T>
class TypedEntry final : public Entry {
 public:
  TypedEntry() : Entry(typeid(T), detail::type_name(typeid(T))) {}
  bool has_value() const noexcept override { return value.has_value(); }

  std::optional<T> value;
};

using EntryFactory = std::unique_ptr<Entry> (*)();

template <typename T>
std::unique_ptr<Entry> make_entry() {
  return std::make_unique<TypedEntry<T>>();
}

/// "blackboard key 'k' has no value yet (read by node 'p')"; an empty `reader_path` means the owner.
Error unset_error(std::string_view key, std::string_view reader_path);

/// The value of an entry already checked to hold a T, or the unset error.
template <typename T>
Result<T> read_value(const Entry& entry, std::string_view key, std::string_view reader_path) {
  const auto& typed = static_cast<const TypedEntry<T>&>(entry);
  if (!typed.value) return unset_error(key, reader_path);
  return *typed.value;
}

template <typename T, typename V>
void write_value(Entry& entry, V&& value) {
  auto& typed = static_cast<TypedEntry<T>&>(entry);
  if (typed.value) {
    *typed.value = std::forward<V>(value);  // assign in place: keeps e.g. a vector's capacity
  } else {
    typed.value.emplace(std::forward<V>(value));
  }
}

}  // namespace detail

enum class PortDirection { kRead, kWrite };

/// "read" / "write".
std::string_view to_string(PortDirection direction) noexcept;

/// One key a node declares it reads or writes. Build it with `reads(key)` / `writes(key)`.
struct Port {
  std::string key;
  PortDirection direction = PortDirection::kRead;
  std::type_index type = typeid(void);
  std::string type_name;
  detail::EntryFactory make_entry = nullptr;
};

using Ports = std::vector<Port>;

template <typename T>
Port reads(const Key<T>& key) {
  return Port{std::string(key.name), PortDirection::kRead, typeid(T), detail::type_name(typeid(T)),
              &detail::make_entry<T>};
}

template <typename T>
Port writes(const Key<T>& key) {
  return Port{std::string(key.name), PortDirection::kWrite, typeid(T), detail::type_name(typeid(T)),
              &detail::make_entry<T>};
}

/// What the blackboard holds under one key, for debugging.
struct KeyInfo {
  std::string_view name;
  std::string_view type_name;
  bool has_value = false;
};

/// The values of one tree. Owned by its `Tree`; the entries are the keys the tree's nodes declare.
/// Access from here is unchecked against ports (it is the owner's view: the planner feeding inputs and
/// reading outputs); nodes go through their ports instead.
class Blackboard {
 public:
  Blackboard() = default;
  Blackboard(const Blackboard&) = delete;
  Blackboard& operator=(const Blackboard&) = delete;
  Blackboard(Blackboard&&) noexcept = default;
  Blackboard& operator=(Blackboard&&) noexcept = default;
  ~Blackboard() = default;

  /// The value under `key`; an error if no node declares the key, it has another type, or it is unset.
  template <typename T>
  Result<T> get(const Key<T>& key) const {
    Result<detail::Entry*> entry = checked_entry(key.name, typeid(T));
    if (!entry) return entry.error();
    return detail::read_value<T>(**entry, key.name, {});
  }

  /// Stores `value` under `key`; an error if no node declares the key or it has another type.
  template <typename T>
  Status set(const Key<T>& key, const std::type_identity_t<T>& value) {
    return store<T>(key, value);
  }
  template <typename T>
  Status set(const Key<T>& key, std::type_identity_t<T>&& value) {
    return store<T>(key, std::move(value));
  }

  /// True if some node declares a key of this name (whatever its type).
  bool contains(std::string_view key) const;

  /// Every key, sorted by name.
  std::vector<KeyInfo> keys() const;

 private:
  friend class Tree;

  /// The entry for a port of `node_path`, created on first declaration.
  /// @throws std::invalid_argument if the key was declared before with another type.
  detail::Entry& declare(const Port& port, std::string_view node_path);

  struct Slot {
    std::unique_ptr<detail::Entry> entry;
    std::string first_declared_by;  ///< node path, for the type-conflict message
  };

  template <typename T, typename V>
  Status store(const Key<T>& key, V&& value) {
    Result<detail::Entry*> entry = checked_entry(key.name, typeid(T));
    if (!entry) return entry.error();
    detail::write_value<T>(**entry, std::forward<V>(value));
    return Status::success();
  }

  Result<detail::Entry*> checked_entry(std::string_view key, std::type_index type) const;

  std::map<std::string, Slot, std::less<>> slots_;
};

}  // namespace ssl::bt
