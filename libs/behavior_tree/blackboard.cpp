#include "libs/behavior_tree/blackboard.h"

#include <cxxabi.h>

#include <cstdlib>
#include <stdexcept>

namespace ssl::bt {
namespace detail {

std::string type_name(std::type_index type) {
  int status = 0;
  std::unique_ptr<char, decltype(&std::free)> demangled(
      abi::__cxa_demangle(type.name(), nullptr, nullptr, &status), &std::free);
  if (status != 0 || !demangled) return type.name();
  return demangled.get();
}

Error unset_error(std::string_view key, std::string_view reader_path) {
  const std::string reader =
      reader_path.empty() ? "the tree's owner" : "node '" + std::string(reader_path) + "'";
  return Error{"blackboard key '" + std::string(key) + "' has no value yet (read by " + reader + ")"};
}

}  // namespace detail

std::string_view to_string(PortDirection direction) noexcept {
  return direction == PortDirection::kRead ? "read" : "write";
}

bool Blackboard::contains(std::string_view key) const { return slots_.find(key) != slots_.end(); }

std::vector<KeyInfo> Blackboard::keys() const {
  std::vector<KeyInfo> infos;
  infos.reserve(slots_.size());
  for (const auto& [name, slot] : slots_) {
    infos.push_back(KeyInfo{name, slot.entry->type_name(), slot.entry->has_value()});
  }
  return infos;
}

detail::Entry& Blackboard::declare(const Port& port, std::string_view node_path) {
  if (port.make_entry == nullptr) {
    throw std::invalid_argument("node '" + std::string(node_path) + "' declares key '" + port.key +
                                "' without a type; build ports with bt::reads(key) / bt::writes(key)");
  }
  auto found = slots_.find(port.key);
  if (found == slots_.end()) {
    found = slots_.emplace(port.key, Slot{port.make_entry(), std::string(node_path)}).first;
  } else if (found->second.entry->type() != port.type) {
    throw std::invalid_argument("blackboard key '" + port.key + "' is declared as " +
                                found->second.entry->type_name() + " by node '" +
                                found->second.first_declared_by + "' and as " + port.type_name +
                                " by node '" + std::string(node_path) + "'");
  }
  return *found->second.entry;
}

Result<detail::Entry*> Blackboard::checked_entry(std::string_view key, std::type_index type) const {
  const auto found = slots_.find(key);
  if (found == slots_.end()) {
    return Error{"blackboard key '" + std::string(key) + "' is not declared by any node of the tree"};
  }
  detail::Entry* entry = found->second.entry.get();
  if (entry->type() != type) {
    return Error{"blackboard key '" + std::string(key) + "' holds " + entry->type_name() + ", not " +
                 detail::type_name(type)};
  }
  return entry;
}

}  // namespace ssl::bt
