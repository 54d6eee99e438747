#include "libs/behavior_tree/render.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

namespace ssl::bt {
namespace {

/// The latest tick of the drawn tree: the root is ticked by every tick.
std::uint64_t latest_tick(const Node& root) { return root.last_tick(); }

bool reached_by_latest_tick(const Node& node, std::uint64_t latest) {
  return node.last_tick() == 0 || node.last_tick() == latest;
}

std::string status_text(const Node& node, std::uint64_t latest) {
  std::string text(to_string(node.status()));
  if (!reached_by_latest_tick(node, latest)) text += " (tick " + std::to_string(node.last_tick()) + ")";
  return text;
}

/// "<-- a, b --> c" (reads first); "" if the node has no ports.
std::string ports_text(const Node& node) {
  std::string reads;
  std::string writes;
  for (const Port& port : node.ports()) {
    std::string& list = port.direction == PortDirection::kRead ? reads : writes;
    list += list.empty() ? "" : ", ";
    list += port.key;
  }
  std::string text;
  if (!reads.empty()) text += "<-- " + reads;
  if (!writes.empty()) text += (text.empty() ? "--> " : " --> ") + writes;
  return text;
}

std::string ascii_label(const Node& node) {
  switch (node.kind()) {
    case NodeKind::kSequence:
      return "(S) " + node.name();
    case NodeKind::kReactiveSequence:
      return "(S*) " + node.name();
    case NodeKind::kSelector:
      return "(?) " + node.name();
    case NodeKind::kReactiveSelector:
      return "(?*) " + node.name();
    case NodeKind::kParallel:
      return "(P) " + node.name() + " (" + node.parameters() + ")";
    case NodeKind::kAction:
      return "[ " + node.name() + " ]";
    case NodeKind::kCondition:
      return "{ " + node.name() + " }";
    case NodeKind::kDecorator:
      break;
  }
  const std::string parameters = node.parameters();
  std::string label =
      "<" + std::string(node.type_name()) + (parameters.empty() ? "" : " " + parameters) + ">";
  if (node.name() != node.type_name()) label += " " + node.name();
  return label;
}

struct AsciiLine {
  std::string tree_part;  ///< connectors, label and ports
  const Node* node;
};

void collect_ascii(const Node& node, const std::string& line_prefix, const std::string& child_prefix,
                   const RenderOptions& options, std::vector<AsciiLine>& lines) {
  std::string text = line_prefix + ascii_label(node);
  if (options.show_ports) {
    const std::string ports = ports_text(node);
    if (!ports.empty()) text += " " + ports;
  }
  lines.push_back(AsciiLine{std::move(text), &node});
  for (std::size_t i = 0; i < node.child_count(); ++i) {
    const bool last = i + 1 == node.child_count();
    collect_ascii(node.child(i), child_prefix + (last ? "`--" : "|--"), child_prefix + (last ? "   " : "|  "),
                  options, lines);
  }
}

std::string dot_escape(std::string_view text) {
  std::string escaped;
  escaped.reserve(text.size());
  for (const char c : text) {
    if (c == '"' || c == '\\') escaped += '\\';
    escaped += c;
  }
  return escaped;
}

std::string_view dot_shape(NodeKind kind) {
  switch (kind) {
    case NodeKind::kSequence:
    case NodeKind::kReactiveSequence:
      return "box";
    case NodeKind::kSelector:
    case NodeKind::kReactiveSelector:
      return "octagon";
    case NodeKind::kParallel:
      return "parallelogram";
    case NodeKind::kAction:
      return "box";
    case NodeKind::kCondition:
      return "ellipse";
    case NodeKind::kDecorator:
      return "hexagon";
  }
  return "box";
}

std::string_view dot_fill(NodeStatus status) {
  switch (status) {
    case NodeStatus::kRunning:
      return "#ffd966";
    case NodeStatus::kSuccess:
      return "#93c47d";
    case NodeStatus::kFailure:
      return "#e06666";
    case NodeStatus::kIdle:
      break;
  }
  return "#ffffff";
}

void collect_dot(const Node& node, std::uint64_t latest, const RenderOptions& options, std::size_t& next_id,
                 std::string& out) {
  const std::size_t id = next_id++;
  // The name, then the type with its parameters; one line for both when the name is the type's name.
  std::string label = dot_escape(node.name());
  if (node.name() != node.type_name()) label += "\\n" + std::string(node.type_name());
  const std::string parameters = node.parameters();
  if (!parameters.empty()) label += ": " + parameters;
  if (options.show_ports) {
    for (const Port& port : node.ports()) {
      label += (port.direction == PortDirection::kRead ? "\\n<-- " : "\\n--> ") + dot_escape(port.key);
    }
  }
  std::string style = "filled";
  if (node.kind() == NodeKind::kAction) style += ",rounded";
  if (options.show_status) {
    label += "\\n" + status_text(node, latest);
    if (!reached_by_latest_tick(node, latest)) style += ",dashed";
  }
  const std::string_view fill = options.show_status ? dot_fill(node.status()) : dot_fill(NodeStatus::kIdle);
  const bool reactive =
      node.kind() == NodeKind::kReactiveSequence || node.kind() == NodeKind::kReactiveSelector;

  out += "  n" + std::to_string(id) + " [label=\"" + label +
         "\", shape=" + std::string(dot_shape(node.kind())) + ", style=\"" + style + "\", fillcolor=\"" +
         std::string(fill) + "\"" + (reactive ? ", peripheries=2" : "") + "];\n";
  for (std::size_t i = 0; i < node.child_count(); ++i) {
    out += "  n" + std::to_string(id) + " -> n" + std::to_string(next_id) + ";\n";
    collect_dot(node.child(i), latest, options, next_id, out);
  }
}

}  // namespace

std::string to_ascii(const Node& root, const RenderOptions& options) {
  std::vector<AsciiLine> lines;
  collect_ascii(root, "", "", options, lines);
  std::size_t width = 0;
  for (const AsciiLine& line : lines) width = std::max(width, line.tree_part.size());

  const std::uint64_t latest = latest_tick(root);
  std::string out;
  for (const AsciiLine& line : lines) {
    out += line.tree_part;
    if (options.show_status) {
      out.append(width + 2 - line.tree_part.size(), ' ');
      out += status_text(*line.node, latest);
    }
    out += '\n';
  }
  return out;
}

std::string to_dot(const Node& root, const RenderOptions& options) {
  std::string out = "digraph behavior_tree {\n  node [fontname=\"Helvetica\"];\n";
  std::size_t next_id = 0;
  collect_dot(root, latest_tick(root), options, next_id, out);
  out += "}\n";
  return out;
}

}  // namespace ssl::bt
