// Internals of ssl::config, included by config.h; services use config.h only.
//
// The loader first turns the YAML text into a small tree of `Node`s that remembers, for each value, its
// line in the file, whether it was quoted, and whether it came from a command-line override. The typed
// binding code in config.h (templates) walks this tree; yaml-cpp itself stays inside config.cpp, so
// neither yaml-cpp types nor its headers reach the services.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "libs/common/result.h"

namespace ssl::config::detail {

struct MapEntry;

struct Node {
  enum class Kind { kNull, kScalar, kSequence, kMap };

  Kind kind = Kind::kNull;
  std::string scalar;       ///< kScalar: the text as written, without quotes
  bool quoted = false;      ///< kScalar: quoted or tagged as a string ("5" is then a string, not a number)
  std::vector<Node> items;  ///< kSequence
  std::vector<MapEntry> entries;  ///< kMap, in document order
  int line = 0;                   ///< 1-based line in the source; 0 when unknown
  std::string file;               ///< non-empty for values from a layer over the source (load_files)
  std::string origin;             ///< non-empty for values from an override: "override 'a.b=1'"
  std::string comment;            ///< only for to_yaml: emitted as "# comment" after the value

  /// The value of `key` in a kMap node, or nullptr.
  const Node* find(std::string_view key) const;

  static Node make_scalar(std::string text, bool is_quoted = false);
  static Node make_map();
  static Node make_sequence();
};

/// One key of a map node. (A named struct, not std::pair, so that Node may contain it while incomplete.)
struct MapEntry {
  std::string key;
  Node value;
};

/// "no value", "'abc'", "the string \"5\"", "a list", "a map": what was found, for error messages.
std::string describe_found(const Node& node);

/// "physics" + "ball_radius" -> "physics.ball_radius"; "" + "x" -> "x".
std::string join_key(std::string_view path, std::string_view key);
/// "robots" + 2 -> "robots[2]".
std::string index_key(std::string_view path, std::size_t index);

/// The candidate closest to `key` by edit distance if it is close enough to be a likely typo, else "".
std::string closest_match(std::string_view key, std::span<const std::string> candidates);

/// "a, b, c".
std::string join_list(std::span<const std::string> items);

/// Collects the errors of one load, each prefixed with where it happened.
class Context {
 public:
  explicit Context(std::string source) : source_(std::move(source)) {}

  /// "<where>: key '<path>': <message>".
  void key_error(const Node* at, std::string_view path, std::string_view message);
  /// "<where>: <message>" (message already names the key).
  void error(const Node* at, std::string_view message);

  std::size_t error_count() const noexcept { return errors_.size(); }
  const std::string& source() const noexcept { return source_; }
  /// All errors, one per line (at most kMaxErrors, then "... and N more errors").
  Error to_error() const;

  static constexpr std::size_t kMaxErrors = 20;

 private:
  /// "file.yaml:12", "file.yaml", or "file.yaml (override 'a=1')".
  std::string where(const Node* at) const;

  std::string source_;
  std::vector<std::string> errors_;
  std::size_t dropped_ = 0;
};

// Scalar parsing. Each returns nullopt on success, else what is wrong ("expected an integer, got '3.5'").
std::optional<std::string> parse_bool(const Node& node, bool& out);
std::optional<std::string> parse_int(const Node& node, std::int64_t& out);
std::optional<std::string> parse_uint(const Node& node, std::uint64_t& out);
/// Rejects NaN and infinities.
std::optional<std::string> parse_double(const Node& node, double& out);
std::optional<std::string> parse_string(const Node& node, std::string& out);

/// Shortest text that parses back to exactly `value` ("0.0215", "1e-09").
std::string format_double(double value);

/// The YAML document as a Node tree. An empty document is an empty map. Errors:
/// "<source>:<line>:<column>: YAML syntax error: <what>", "<source>:<line>: duplicate key 'x' ...".
Result<Node> parse_yaml(std::string_view text, std::string_view source);

/// The whole file. Error: "cannot read config file '<path>': <errno text>".
Result<std::string> read_file(const std::string& path);

/// Applies "key.path=value" (value in YAML syntax, e.g. "0.03", "[1, 2]", "\"text\""); list elements are
/// addressed as "robots[1].id". Missing intermediate maps are created; type and unknown-key errors are
/// found later by the normal validation, which names the override.
Status apply_override(Node& root, std::string_view assignment, std::string_view source);

/// Lays `overlay` (parsed from `file`) over `base`: a map's keys merge key by key, recursively; any other
/// value (scalar, list, null) replaces the one below whole. The overlay's nodes remember `file`.
void merge_layer(Node& base, Node overlay, const std::string& file);

/// YAML text for a Node tree (block style; lists of scalars in flow style; comments after values).
std::string emit_yaml(const Node& root);

}  // namespace ssl::config::detail
