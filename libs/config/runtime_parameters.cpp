#include "libs/config/runtime_parameters.h"

#include <map>
#include <memory>

namespace ssl::config {
namespace {

/// A map of nested keys, in the order they came.
struct Tree {
  std::vector<std::pair<std::string, std::unique_ptr<Tree>>> children;
  std::string value;  // a leaf's YAML text

  Tree& child(const std::string& name) {
    for (auto& [key, node] : children) {
      if (key == name) return *node;
    }
    children.emplace_back(name, std::make_unique<Tree>());
    return *children.back().second;
  }
};

std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

void emit(const Tree& tree, int indent, std::string& out) {
  for (const auto& [key, node] : tree.children) {
    out += std::string(static_cast<std::size_t>(indent), ' ') + key + ":";
    if (node->children.empty()) {
      out += " " + node->value + "\n";
    } else {
      out += "\n";
      emit(*node, indent + 2, out);
    }
  }
}

}  // namespace

std::string layer_yaml(std::span<const KeyInfo> keys) {
  Tree root;
  for (const KeyInfo& info : keys) {
    Tree* node = &root;
    std::size_t start = 0;
    for (std::size_t dot = info.key.find('.'); ; dot = info.key.find('.', start)) {
      node = &node->child(info.key.substr(start, dot - start));
      if (dot == std::string::npos) break;
      start = dot + 1;
    }
    node->value = info.type == "string" ? quoted(info.value) : info.value;
  }
  std::string out;
  emit(root, 0, out);
  return out;
}

}  // namespace ssl::config
