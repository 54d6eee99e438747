// The non-template half of ssl::config: YAML <-> Node (the only place that sees yaml-cpp), scalar parsing,
// overrides, error formatting.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <variant>

#include "libs/config/config.h"
#include "libs/config/node.h"

namespace ssl::config::detail {
namespace {

constexpr int kMaxDepth = 64;

// -------------------------------------------------------------------------------------------------------
// YAML -> Node

struct Converter {
  std::string_view source;
  std::string origin;  // non-empty when converting an override's value

  std::string where(int line) const {
    if (!origin.empty()) return std::string(source) + " (" + origin + ")";
    return std::string(source) + (line > 0 ? ":" + std::to_string(line) : "");
  }

  Result<Node> convert(const YAML::Node& yaml, int depth, int line) const {
    if (depth > kMaxDepth) {
      return Error{where(line) + ": nesting deeper than " + std::to_string(kMaxDepth) + " levels"};
    }
    Node node;
    node.line = line;
    node.origin = origin;
    switch (yaml.Type()) {
      case YAML::NodeType::Null:
      case YAML::NodeType::Undefined:
        node.kind = Node::Kind::kNull;
        return node;
      case YAML::NodeType::Scalar:
        node.kind = Node::Kind::kScalar;
        node.scalar = yaml.Scalar();
        // yaml-cpp tags plain scalars "?" and quoted/literal ones "!"; "!!str 5" is a string too.
        node.quoted = yaml.Tag() == "!" || yaml.Tag() == "tag:yaml.org,2002:str";
        return node;
      case YAML::NodeType::Sequence:
        node.kind = Node::Kind::kSequence;
        for (const YAML::Node& item : yaml) {
          Result<Node> converted = convert(item, depth + 1, line_of(item, line));
          if (!converted) return converted.error();
          node.items.push_back(std::move(*converted));
        }
        return node;
      case YAML::NodeType::Map:
        node.kind = Node::Kind::kMap;
        for (const auto& entry : yaml) {
          const int key_line = line_of(entry.first, line);
          if (!entry.first.IsScalar()) return Error{where(key_line) + ": map keys must be plain names"};
          const std::string key = entry.first.Scalar();
          for (const auto& [existing, value] : node.entries) {
            if (existing == key) {
              return Error{where(key_line) + ": duplicate key '" + key + "' (first on line " +
                           std::to_string(value.line) + ")"};
            }
          }
          // Errors about a value point at its key's line (yaml-cpp marks an empty value on the next line).
          Result<Node> converted = convert(entry.second, depth + 1, key_line);
          if (!converted) return converted.error();
          converted->line = key_line;
          node.entries.push_back(MapEntry{key, std::move(*converted)});
        }
        return node;
    }
    return node;
  }

  static int line_of(const YAML::Node& yaml, int fallback) {
    const YAML::Mark mark = yaml.Mark();
    return mark.line >= 0 ? mark.line + 1 : fallback;
  }
};

// Loads YAML text; syntax errors name the line and column.
Result<Node> load_yaml(std::string_view text, const Converter& converter) {
  try {
    const YAML::Node yaml = YAML::Load(std::string(text));
    return converter.convert(yaml, 0, Converter::line_of(yaml, 0));
  } catch (const YAML::Exception& e) {
    const std::string where = converter.origin.empty()
                                  ? std::string(converter.source) + ":" + std::to_string(e.mark.line + 1) +
                                        ":" + std::to_string(e.mark.column + 1)
                                  : converter.where(0);
    return Error{where + ": YAML syntax error: " + e.msg};
  } catch (const std::exception& e) {
    return Error{converter.where(0) + ": cannot parse YAML: " + e.what()};
  }
}

// -------------------------------------------------------------------------------------------------------
// Node -> YAML

void emit(YAML::Emitter& out, const Node& node) {
  switch (node.kind) {
    case Node::Kind::kNull:
      out << YAML::Null;
      return;
    case Node::Kind::kScalar:
      if (node.quoted) out << YAML::DoubleQuoted;
      out << node.scalar;
      return;
    case Node::Kind::kSequence: {
      const bool flat = std::all_of(node.items.begin(), node.items.end(), [](const Node& item) {
        return item.kind == Node::Kind::kScalar || item.kind == Node::Kind::kNull;
      });
      if (flat) out << YAML::Flow;
      out << YAML::BeginSeq;
      for (const Node& item : node.items) emit(out, item);
      out << YAML::EndSeq;
      return;
    }
    case Node::Kind::kMap:
      out << YAML::BeginMap;
      for (const auto& [key, value] : node.entries) {
        out << YAML::Key << key << YAML::Value;
        emit(out, value);
        if (!value.comment.empty()) out << YAML::Comment(value.comment);
      }
      out << YAML::EndMap;
      return;
  }
}

// -------------------------------------------------------------------------------------------------------
// Scalars

bool is_plain_scalar(const Node& node) { return node.kind == Node::Kind::kScalar && !node.quoted; }

std::string expected(std::string_view what, const Node& node) {
  return "expected " + std::string(what) + ", got " + describe_found(node);
}

// from_chars does not accept a leading '+'.
std::string_view without_plus(std::string_view text) {
  return text.size() > 1 && text.front() == '+' && text[1] != '-' ? text.substr(1) : text;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  // Optimal string alignment: insertions, deletions, substitutions and adjacent transpositions cost 1.
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[a.size()][b.size()];
}

// -------------------------------------------------------------------------------------------------------
// Override key paths: "a.b[2].c" -> {"a", "b", 2, "c"}.

using PathStep = std::variant<std::string, std::size_t>;

std::optional<std::vector<PathStep>> parse_key_path(std::string_view path) {
  std::vector<PathStep> steps;
  std::size_t i = 0;
  while (i < path.size()) {
    const std::size_t name_end = path.find_first_of(".[", i);
    const std::string_view name =
        path.substr(i, name_end == std::string_view::npos ? path.npos : name_end - i);
    if (name.empty()) return std::nullopt;
    steps.emplace_back(std::string(name));
    i += name.size();
    while (i < path.size() && path[i] == '[') {
      const std::size_t close = path.find(']', i);
      if (close == std::string_view::npos) return std::nullopt;
      std::size_t index = 0;
      const std::string_view digits = path.substr(i + 1, close - i - 1);
      const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
      if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size()) return std::nullopt;
      steps.emplace_back(index);
      i = close + 1;
    }
    if (i < path.size()) {
      if (path[i] != '.' || i + 1 == path.size()) return std::nullopt;
      ++i;
    }
  }
  if (steps.empty()) return std::nullopt;
  return steps;
}

void set_origin(Node& node, const std::string& origin) {
  node.origin = origin;
  node.line = 0;
  for (Node& item : node.items) set_origin(item, origin);
  for (auto& [key, value] : node.entries) set_origin(value, origin);
}

// Thread-safe strerror (GNU strerror_r returns the text to use).
std::string errno_text(int error) {
  char buffer[256];
  return ::strerror_r(error, buffer, sizeof buffer);
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------
// Node

const Node* Node::find(std::string_view key) const {
  for (const auto& [name, value] : entries) {
    if (name == key) return &value;
  }
  return nullptr;
}

Node Node::make_scalar(std::string text, bool is_quoted) {
  Node node;
  node.kind = Kind::kScalar;
  node.scalar = std::move(text);
  node.quoted = is_quoted;
  return node;
}

Node Node::make_map() {
  Node node;
  node.kind = Kind::kMap;
  return node;
}

Node Node::make_sequence() {
  Node node;
  node.kind = Kind::kSequence;
  return node;
}

std::string describe_found(const Node& node) {
  switch (node.kind) {
    case Node::Kind::kNull:
      return "no value";
    case Node::Kind::kScalar:
      return node.quoted ? "the string \"" + node.scalar + "\"" : "'" + node.scalar + "'";
    case Node::Kind::kSequence:
      return "a list";
    case Node::Kind::kMap:
      return "a map";
  }
  return "?";
}

std::string join_key(std::string_view path, std::string_view key) {
  if (path.empty()) return std::string(key);
  return std::string(path) + "." + std::string(key);
}

std::string index_key(std::string_view path, std::size_t index) {
  return std::string(path) + "[" + std::to_string(index) + "]";
}

std::string closest_match(std::string_view key, std::span<const std::string> candidates) {
  std::string best;
  std::size_t best_distance = std::string::npos;
  for (const std::string& candidate : candidates) {
    const bool same_ignoring_case =
        key.size() == candidate.size() &&
        std::equal(key.begin(), key.end(), candidate.begin(), [](char a, char b) {
          return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
        });
    const std::size_t distance = same_ignoring_case ? 0 : edit_distance(key, candidate);
    // A likely typo: at most a third of the name differs (at least one edit is allowed), and something of
    // the name survives (so "c" does not suggest "a").
    const std::size_t allowed = std::max<std::size_t>(1, std::max(key.size(), candidate.size()) / 3);
    const bool plausible =
        same_ignoring_case || (distance <= allowed && distance < std::min(key.size(), candidate.size()));
    if (plausible && distance < best_distance) {
      best = candidate;
      best_distance = distance;
    }
  }
  return best;
}

std::string join_list(std::span<const std::string> items) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
  return text;
}

// ---------------------------------------------------------------------------------------------------------
// Context

void Context::key_error(const Node* at, std::string_view path, std::string_view message) {
  error(at, "key '" + std::string(path) + "': " + std::string(message));
}

void Context::error(const Node* at, std::string_view message) {
  if (errors_.size() >= kMaxErrors) {
    ++dropped_;
    return;
  }
  errors_.push_back(where(at) + ": " + std::string(message));
}

Error Context::to_error() const {
  std::string text;
  for (const std::string& line : errors_) text += (text.empty() ? "" : "\n") + line;
  if (dropped_ > 0) text += "\n... and " + std::to_string(dropped_) + " more errors";
  return Error{text};
}

std::string Context::where(const Node* at) const {
  if (at != nullptr && !at->origin.empty()) return source_ + " (" + at->origin + ")";
  const std::string& file = at != nullptr && !at->file.empty() ? at->file : source_;
  if (at != nullptr && at->line > 0) return file + ":" + std::to_string(at->line);
  return file;
}

// ---------------------------------------------------------------------------------------------------------
// Scalars

std::optional<std::string> parse_bool(const Node& node, bool& out) {
  if (is_plain_scalar(node)) {
    const std::string& text = node.scalar;
    if (text == "true" || text == "True" || text == "TRUE") {
      out = true;
      return std::nullopt;
    }
    if (text == "false" || text == "False" || text == "FALSE") {
      out = false;
      return std::nullopt;
    }
  }
  return expected("true or false", node);
}

std::optional<std::string> parse_int(const Node& node, std::int64_t& out) {
  if (!is_plain_scalar(node)) return expected("an integer", node);
  const std::string_view text = without_plus(node.scalar);
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  if (end != text.data() + text.size() || ec == std::errc::invalid_argument)
    return expected("an integer", node);
  if (ec == std::errc::result_out_of_range) return node.scalar + " is too large for a 64-bit integer";
  return std::nullopt;
}

std::optional<std::string> parse_uint(const Node& node, std::uint64_t& out) {
  if (!is_plain_scalar(node)) return expected("a non-negative integer", node);
  const std::string_view text = without_plus(node.scalar);
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  if (end != text.data() + text.size() || ec == std::errc::invalid_argument) {
    return expected("a non-negative integer", node);
  }
  if (ec == std::errc::result_out_of_range) return node.scalar + " is too large for a 64-bit integer";
  return std::nullopt;
}

std::optional<std::string> parse_double(const Node& node, double& out) {
  if (!is_plain_scalar(node)) return expected("a number", node);
  std::string lower = node.scalar;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  if (lower == ".nan" || lower == ".inf" || lower == "+.inf" || lower == "-.inf") {
    return node.scalar + " is not a finite number";
  }
  const std::string_view text = without_plus(node.scalar);
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  if (end != text.data() + text.size() || ec == std::errc::invalid_argument)
    return expected("a number", node);
  if (ec == std::errc::result_out_of_range) return node.scalar + " is out of the range of a double";
  if (!std::isfinite(out)) return node.scalar + " is not a finite number";
  return std::nullopt;
}

std::optional<std::string> parse_string(const Node& node, std::string& out) {
  if (node.kind != Node::Kind::kScalar) return expected("a string", node);
  out = node.scalar;
  return std::nullopt;
}

std::string format_double(double value) {
  char text[64];
  const auto [end, ec] = std::to_chars(text, text + sizeof text, value);
  return ec == std::errc() ? std::string(text, end) : std::to_string(value);
}

// ---------------------------------------------------------------------------------------------------------
// Documents

Result<Node> parse_yaml(std::string_view text, std::string_view source) {
  Result<Node> root = load_yaml(text, Converter{source, {}});
  if (root && root->kind == Node::Kind::kNull) {  // empty file or only comments
    const int line = root->line;
    *root = Node::make_map();
    root->line = line;
  }
  return root;
}

Result<std::string> read_file(const std::string& path) {
  errno = 0;
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) return Error{"cannot read config file '" + path + "': " + errno_text(errno)};
  std::string text;
  char buffer[16384];
  std::size_t read = 0;
  while ((read = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) text.append(buffer, read);
  if (std::ferror(file.get())) return Error{"cannot read config file '" + path + "': " + errno_text(errno)};
  return text;
}

namespace {

void set_file(Node& node, const std::string& file) {
  node.file = file;
  for (Node& item : node.items) set_file(item, file);
  for (auto& [key, value] : node.entries) set_file(value, file);
}

void merge_nodes(Node& base, Node overlay) {
  if (base.kind != Node::Kind::kMap || overlay.kind != Node::Kind::kMap) {
    base = std::move(overlay);
    return;
  }
  for (MapEntry& entry : overlay.entries) {
    auto below = std::find_if(base.entries.begin(), base.entries.end(),
                              [&](const MapEntry& candidate) { return candidate.key == entry.key; });
    if (below == base.entries.end()) {
      base.entries.push_back(std::move(entry));
    } else {
      merge_nodes(below->value, std::move(entry.value));
    }
  }
}

}  // namespace

void merge_layer(Node& base, Node overlay, const std::string& file) {
  set_file(overlay, file);
  merge_nodes(base, std::move(overlay));
}

Status apply_override(Node& root, std::string_view assignment, std::string_view source) {
  const std::string origin = "override '" + std::string(assignment) + "'";
  const auto fail = [&](const std::string& why) {
    return Error{std::string(source) + " (" + origin + "): " + why};
  };

  const std::size_t equals = assignment.find('=');
  if (equals == std::string_view::npos) return fail("expected key.path=value");
  const std::string_view path = assignment.substr(0, equals);
  std::optional<std::vector<PathStep>> steps = parse_key_path(path);
  if (!steps)
    return fail("bad key path '" + std::string(path) +
                "' (expected e.g. physics.ball_radius or robots[1].id)");

  Result<Node> value = load_yaml(assignment.substr(equals + 1), Converter{source, origin});
  if (!value) return value.error();
  set_origin(*value, origin);

  Node* current = &root;
  std::string walked;
  for (const PathStep& step : *steps) {
    if (const std::string* key = std::get_if<std::string>(&step)) {
      if (current->kind == Node::Kind::kNull) current->kind = Node::Kind::kMap;
      if (current->kind != Node::Kind::kMap) {
        return fail("'" + walked + "' is " + describe_found(*current) + ", not a map");
      }
      walked = join_key(walked, *key);
      auto found = std::find_if(current->entries.begin(), current->entries.end(),
                                [&](const MapEntry& entry) { return entry.key == *key; });
      if (found == current->entries.end()) {
        Node created;  // kNull: becomes a map if the path goes deeper, else it is replaced by the value
        created.origin = origin;
        current->entries.push_back(MapEntry{*key, std::move(created)});
        current = &current->entries.back().value;
      } else {
        current = &found->value;
      }
    } else {
      const std::size_t index = std::get<std::size_t>(step);
      if (current->kind != Node::Kind::kSequence) {
        return fail("'" + walked + "' is " + describe_found(*current) + ", not a list");
      }
      if (index >= current->items.size()) {
        return fail("index " + std::to_string(index) + " is out of range: '" + walked + "' has " +
                    std::to_string(current->items.size()) + " elements");
      }
      walked = index_key(walked, index);
      current = &current->items[index];
    }
  }
  *current = std::move(*value);
  return Status::success();
}

std::string emit_yaml(const Node& root) {
  YAML::Emitter out;
  emit(out, root);
  return std::string(out.c_str()) + "\n";
}

}  // namespace ssl::config::detail
