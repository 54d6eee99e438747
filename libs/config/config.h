// Typed, validated configuration from YAML, loaded once at startup (deploy/config/<service>.yaml).
//
// A service declares a plain config struct and, next to it, a `Fields<T>` list that names every YAML key,
// its member, unit, limits and documentation. The loader fills a T and fails fast, naming the file, line
// and key path, on: an unknown key (with a "did you mean" suggestion), a missing required key, a wrong
// type, a fractional or oversized integer, a NaN/inf number, an out-of-range value, a bad enum/one_of
// value (listing the allowed ones), a duplicate key, an unreadable file or a YAML syntax error. All errors
// of a file are reported at once, one per line. There are no hidden defaults: a key is required unless it
// is declared with `optional_field` and an explicit default, which is part of the schema (and printed by
// `to_yaml` and `describe`).
//
// Supported member types: bool, integers (range-checked against the member's type), float/double,
// std::string, enums (named with .values), std::vector of those, nested structs (nested) and
// std::vector of nested structs (nested_list).
//
//   struct Physics { double ball_radius_m; };
//   enum class Division { kA, kB };
//   struct SimConfig { Physics physics; int robots_per_team; Division division; std::vector<double> gains; };
//
//   ssl::config::Fields<Physics> physics_fields() {
//     using namespace ssl::config;
//     return {field("ball_radius", &Physics::ball_radius_m).unit("m").range(0.01, 0.05).doc("ball radius")};
//   }
//   ssl::config::Fields<SimConfig> sim_fields() {
//     using namespace ssl::config;
//     return {
//         nested("physics", &SimConfig::physics, physics_fields()),
//         field("robots_per_team", &SimConfig::robots_per_team).range(0, 16),
//         field("division", &SimConfig::division).values({{"a", Division::kA}, {"b", Division::kB}}),
//         optional_field("gains", &SimConfig::gains, {1.0, 2.0}).length(2, 2),
//     };
//   }
//
//   ssl::Result<SimConfig> config = ssl::config::load_file("deploy/config/simulator.yaml", sim_fields(),
//                                                          overrides /* {"physics.ball_radius=0.03"} */);
//   if (!config) { spdlog::critical("{}", config.error().message); return EXIT_FAILURE; }
//   // e.g. "deploy/config/simulator.yaml:3: key 'physics.ball_radius': 0.5 is out of range [0.01, 0.05] (m)"
//   std::cout << ssl::config::to_yaml(*config, sim_fields());   // --print-config
//
// Schema mistakes (duplicate keys in a Fields list, an enum without .values, a default that breaks its
// own limits) are reported by the loader as "config schema error: ..." so a unit test that loads the
// deployed file catches them.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "libs/common/result.h"
#include "libs/config/node.h"

namespace ssl::config {

template <typename T>
class Fields;
template <typename T, typename M>
class FieldSpec;

/// One scalar key of a config with its schema and current value (for run-time parameters: a page or a
/// terminal lists, edits and checks them). Lists and nested maps are not scalar keys.
struct KeyInfo {
  std::string key;                   // dotted path, e.g. "planner.limits.max_speed"
  std::string type;                  // "boolean", "integer", "number", "string", "one of a, b"
  std::string value;                 // current value as YAML scalar text (strings unquoted)
  std::optional<double> min;         // numbers: inclusive limits
  std::optional<double> max;
  std::vector<std::string> allowed;  // strings with one_of, enums: the accepted values
  std::string unit;
  std::string doc;
};

namespace detail {

template <typename M>
struct VectorTraits {
  static constexpr bool kIsVector = false;
  using Element = M;
};
template <typename E, typename A>
struct VectorTraits<std::vector<E, A>> {
  static constexpr bool kIsVector = true;
  using Element = E;
};

template <typename E>
inline constexpr bool kIsScalar =
    std::is_arithmetic_v<E> || std::is_enum_v<E> || std::is_same_v<E, std::string>;
template <typename E>
inline constexpr bool kIsRecord = std::is_class_v<E> && !kIsScalar<E> && !VectorTraits<E>::kIsVector;

/// The type-erased interface of one field of T; implemented by FieldSpec<T, M>.
template <typename T>
class FieldBase {
 public:
  virtual ~FieldBase() = default;
  virtual const std::string& key() const = 0;
  /// `value` is nullptr when the key is absent.
  virtual void load(const Node* value, T& out, Context& context, const std::string& path) const = 0;
  virtual Node dump(const T& in) const = 0;
  virtual void check_schema(Context& context, const std::string& path) const = 0;
  virtual void describe(std::vector<std::string>& lines, const std::string& path) const = 0;
  /// Appends a KeyInfo for each scalar key under this field, with its value in `in`.
  virtual void collect(std::vector<KeyInfo>& out, const T& in, const std::string& path) const = 0;
};

/// Limits and names that apply to one value (or to each element of a list).
template <typename E>
struct Constraints {
  std::optional<E> min;                          // arithmetic
  std::optional<E> max;                          // arithmetic
  std::vector<std::string> allowed;              // std::string: one_of
  std::vector<std::pair<std::string, E>> names;  // enums: YAML name -> value
  std::shared_ptr<const Fields<E>> fields;       // nested structs
  std::string unit;
};

template <typename T>
void load_record(const Node* node, T& out, const Fields<T>& fields, Context& context,
                 const std::string& path);
template <typename T>
Node dump_record(const T& value, const Fields<T>& fields);
template <typename T>
void check_record_schema(const Fields<T>& fields, Context& context, const std::string& path);
template <typename T>
void describe_record(const Fields<T>& fields, std::vector<std::string>& lines, const std::string& path);

}  // namespace detail

/// One key of a config struct T, type-erased. Built implicitly from field(), optional_field(), nested()...
template <typename T>
class Field {
 public:
  template <typename M>
  Field(FieldSpec<T, M> spec)  // NOLINT: implicit so that Fields<T>{field(...), ...} reads naturally
      : impl_(std::make_shared<FieldSpec<T, M>>(std::move(spec))) {}

  const detail::FieldBase<T>& impl() const { return *impl_; }

 private:
  std::shared_ptr<const detail::FieldBase<T>> impl_;
};

/// The schema of a config struct T: its fields, in the order to_yaml prints them, plus optional checks
/// across fields. Cheap to copy (fields are shared).
template <typename T>
class Fields {
 public:
  Fields(std::initializer_list<Field<T>> fields) : fields_(fields) {}

  /// Adds a check of the whole struct, run after all its fields loaded without error; return an
  /// ssl::Error saying what is wrong, e.g. Error{"min_speed must not exceed max_speed"}.
  Fields& check(std::function<Status(const T&)> whole_struct_check) & {
    checks_.push_back(std::move(whole_struct_check));
    return *this;
  }
  Fields&& check(std::function<Status(const T&)> whole_struct_check) && {
    checks_.push_back(std::move(whole_struct_check));
    return std::move(*this);
  }

  const std::vector<Field<T>>& fields() const noexcept { return fields_; }
  const std::vector<std::function<Status(const T&)>>& checks() const noexcept { return checks_; }

 private:
  std::vector<Field<T>> fields_;
  std::vector<std::function<Status(const T&)>> checks_;
};

/// Describes member `M T::*`: a scalar, a list of scalars, a nested struct or a list of nested structs.
/// Built by field(), optional_field(), nested(), nested_list(); the modifiers return the spec by value so
/// they chain: field("radius", &Cfg::radius).unit("m").range(0.01, 0.05).doc("ball radius").
template <typename T, typename M>
class FieldSpec final : public detail::FieldBase<T> {
 public:
  using Element = typename detail::VectorTraits<M>::Element;
  static constexpr bool kIsList = detail::VectorTraits<M>::kIsVector;
  static constexpr bool kIsNumber = std::is_arithmetic_v<Element> && !std::is_same_v<Element, bool>;

  static_assert(detail::kIsScalar<Element> || detail::kIsRecord<Element>,
                "config fields must be bool, integers, floating point, std::string, enums, nested structs, "
                "or std::vector of those");
  static_assert(!std::is_same_v<Element, char>,
                "use an integer type such as int, not char, for config numbers");
  static_assert(std::is_default_constructible_v<Element>, "config values must be default-constructible");

  /// @param default_value the value for an absent key; nullopt makes the key required.
  FieldSpec(std::string key, M T::*member, std::optional<M> default_value = std::nullopt)
      : key_(std::move(key)), member_(member), default_(std::move(default_value)) {}

  /// Documentation, shown by to_yaml (as a comment) and describe().
  FieldSpec doc(std::string text) && {
    doc_ = std::move(text);
    return std::move(*this);
  }
  /// Unit of the value ("m", "m/s", "rad", "ms"), shown in errors, to_yaml and describe().
  FieldSpec unit(std::string symbol) && {
    constraints_.unit = std::move(symbol);
    return std::move(*this);
  }
  /// Inclusive limits for a number (for a list: for each element).
  FieldSpec range(Element lowest, Element highest) && requires kIsNumber {
    constraints_.min = lowest;
    constraints_.max = highest;
    return std::move(*this);
  }
  FieldSpec min(Element lowest) && requires kIsNumber {
    constraints_.min = lowest;
    return std::move(*this);
  }
  FieldSpec max(Element highest) && requires kIsNumber {
    constraints_.max = highest;
    return std::move(*this);
  }
  /// The allowed values of a string (for a list: of each element).
  FieldSpec one_of(std::vector<std::string> allowed) && requires std::is_same_v<Element, std::string> {
    constraints_.allowed = std::move(allowed);
    return std::move(*this);
  }
  /// The YAML names of an enum's values; required for enum fields.
  FieldSpec values(std::vector<std::pair<std::string, Element>> names) && requires std::is_enum_v<Element> {
    constraints_.names = std::move(names);
    return std::move(*this);
  }
  /// Inclusive limits on the number of elements of a list.
  FieldSpec length(std::size_t fewest, std::size_t most) && requires kIsList {
    length_ = {fewest, most};
    return std::move(*this);
  }

  // Used by the builder functions below.
  FieldSpec with_fields(Fields<Element> fields) && requires detail::kIsRecord<Element> {
    constraints_.fields = std::make_shared<const Fields<Element>>(std::move(fields));
    return std::move(*this);
  }

  // detail::FieldBase<T>
  const std::string& key() const override { return key_; }
  void load(const detail::Node* value, T& out, detail::Context& context,
            const std::string& path) const override;
  detail::Node dump(const T& in) const override;
  void check_schema(detail::Context& context, const std::string& path) const override;
  void describe(std::vector<std::string>& lines, const std::string& path) const override;
  void collect(std::vector<KeyInfo>& out, const T& in, const std::string& path) const override;

 private:
  std::string comment() const;
  std::string type_name() const;
  std::string default_text() const;

  std::string key_;
  M T::*member_;
  std::string doc_;
  detail::Constraints<Element> constraints_;
  std::optional<M> default_;
  std::optional<std::pair<std::size_t, std::size_t>> length_;
};

// ---------------------------------------------------------------------------------------------------------
// Builders

/// A required key holding a scalar or a list of scalars.
template <typename T, typename M>
FieldSpec<T, M> field(std::string key, M T::*member) {
  static_assert(!detail::kIsRecord<typename detail::VectorTraits<M>::Element>,
                "use nested() / nested_list() for struct members");
  return FieldSpec<T, M>(std::move(key), member);
}

/// An optional key: when absent, the member gets `default_value` (which must satisfy the field's limits).
template <typename T, typename M>
FieldSpec<T, M> optional_field(std::string key, M T::*member, std::type_identity_t<M> default_value) {
  static_assert(!detail::kIsRecord<typename detail::VectorTraits<M>::Element>,
                "use nested() / optional_nested_list() for struct members");
  return FieldSpec<T, M>(std::move(key), member, std::move(default_value));
}

/// A nested struct under `key`. An absent key is treated as an empty map, so each missing required
/// sub-key is reported by its full path and sub-keys with defaults need not be written.
template <typename T, typename N>
FieldSpec<T, N> nested(std::string key, N T::*member, Fields<N> fields) {
  static_assert(detail::kIsRecord<N>, "nested() is for struct members");
  return FieldSpec<T, N>(std::move(key), member).with_fields(std::move(fields));
}

/// A required list of nested structs (may be written as [] when empty).
template <typename T, typename N>
FieldSpec<T, std::vector<N>> nested_list(std::string key, std::vector<N> T::*member, Fields<N> fields) {
  static_assert(detail::kIsRecord<N>, "nested_list() is for std::vector<struct> members");
  return FieldSpec<T, std::vector<N>>(std::move(key), member).with_fields(std::move(fields));
}

/// An optional list of nested structs, `default_value` when absent.
template <typename T, typename N>
FieldSpec<T, std::vector<N>> optional_nested_list(std::string key, std::vector<N> T::*member,
                                                  Fields<N> fields, std::vector<N> default_value = {}) {
  static_assert(detail::kIsRecord<N>, "optional_nested_list() is for std::vector<struct> members");
  return FieldSpec<T, std::vector<N>>(std::move(key), member, std::move(default_value))
      .with_fields(std::move(fields));
}

// ---------------------------------------------------------------------------------------------------------
// Loading and printing

/// Parses `yaml`, applies `overrides` ("key.path=value", e.g. from --set flags) and binds the result to a
/// T. `source` names the text in error messages (a file name, "<inline>").
template <typename T>
Result<T> load_string(std::string_view yaml, const Fields<T>& fields, std::string_view source = "<string>",
                      std::span<const std::string> overrides = {});

/// Reads and loads a file; errors name the file. See load_string.
template <typename T>
Result<T> load_file(const std::string& path, const Fields<T>& fields,
                    std::span<const std::string> overrides = {});

/// Loads layered files, lowest first: `paths[0]` is complete (the defaults); each later file holds only
/// the keys it changes (a site, a user's file) and is laid over the ones below (maps merge key by key, any
/// other value replaces the one below whole). Then `overrides`, then the same validation as load_string:
/// an unknown key or a bad value is reported at its own file and line.
template <typename T>
Result<T> load_files(std::span<const std::string> paths, const Fields<T>& fields,
                     std::span<const std::string> overrides = {});

/// The effective config as YAML, in schema order, with units and docs as comments. Loading the output
/// with the same fields gives back an equal struct (doubles are printed with round-trip precision).
template <typename T>
std::string to_yaml(const T& value, const Fields<T>& fields);

/// One line per key: path, type, limits, default or "required", unit and doc (for --help-config).
template <typename T>
std::string describe(const Fields<T>& fields);

/// Every scalar key of `value` with its schema and current value, in schema order.
template <typename T>
std::vector<KeyInfo> key_infos(const T& value, const Fields<T>& fields);

// =========================================================================================================
// Implementation

namespace detail {

template <typename E>
std::string type_name_of(const Constraints<E>& constraints) {
  if constexpr (std::is_same_v<E, bool>) {
    return "boolean";
  } else if constexpr (std::is_integral_v<E>) {
    return std::is_signed_v<E> ? "integer" : "non-negative integer";
  } else if constexpr (std::is_floating_point_v<E>) {
    return "number";
  } else if constexpr (std::is_same_v<E, std::string>) {
    return "string";
  } else if constexpr (std::is_enum_v<E>) {
    std::vector<std::string> names;
    for (const auto& [name, value] : constraints.names) names.push_back(name);
    return "one of " + join_list(names);
  } else {
    return "map";
  }
}

template <typename E>
std::string format_value(const E& value, const Constraints<E>& constraints) {
  if constexpr (std::is_same_v<E, bool>) {
    return value ? "true" : "false";
  } else if constexpr (std::is_integral_v<E>) {
    return std::to_string(value);
  } else if constexpr (std::is_floating_point_v<E>) {
    return format_double(static_cast<double>(value));
  } else if constexpr (std::is_same_v<E, std::string>) {
    return "'" + value + "'";
  } else if constexpr (std::is_enum_v<E>) {
    for (const auto& [name, named] : constraints.names) {
      if (named == value) return name;
    }
    return "<unnamed enum value " + std::to_string(static_cast<std::underlying_type_t<E>>(value)) + ">";
  } else {
    return "{...}";
  }
}

/// Whether a value satisfies its limits: nullopt if it does, else the problem.
template <typename E>
std::optional<std::string> check_value(const E& value, const Constraints<E>& c) {
  const std::string unit = c.unit.empty() ? "" : " (" + c.unit + ")";
  if constexpr (std::is_arithmetic_v<E> && !std::is_same_v<E, bool>) {
    const bool below = c.min && value < *c.min;
    const bool above = c.max && value > *c.max;
    if (!below && !above) return std::nullopt;
    const std::string text = format_value(value, c);
    if (c.min && c.max) {
      return text + " is out of range [" + format_value(*c.min, c) + ", " + format_value(*c.max, c) + "]" +
             unit;
    }
    if (below) return text + " is below the minimum " + format_value(*c.min, c) + unit;
    return text + " is above the maximum " + format_value(*c.max, c) + unit;
  } else if constexpr (std::is_same_v<E, std::string>) {
    if (c.allowed.empty()) return std::nullopt;
    for (const std::string& allowed : c.allowed) {
      if (allowed == value) return std::nullopt;
    }
    std::string problem = "'" + value + "' is not one of: " + join_list(c.allowed);
    if (std::string guess = closest_match(value, c.allowed); !guess.empty()) {
      problem += " (did you mean '" + guess + "'?)";
    }
    return problem;
  } else if constexpr (std::is_enum_v<E>) {
    for (const auto& [name, named] : c.names) {
      if (named == value) return std::nullopt;
    }
    return format_value(value, c) + " has no name in .values()";
  } else {
    return std::nullopt;
  }
}

/// Stores a parsed integer in a narrower member type, or says why it does not fit.
template <typename E, typename Wide>
std::optional<std::string> narrow_integer(Wide wide, E& out) {
  if (std::cmp_less(wide, std::numeric_limits<E>::min()) ||
      std::cmp_greater(wide, std::numeric_limits<E>::max())) {
    return std::to_string(wide) + " does not fit this field's type [" +
           std::to_string(std::numeric_limits<E>::min()) + ", " +
           std::to_string(std::numeric_limits<E>::max()) + "]";
  }
  out = static_cast<E>(wide);
  return std::nullopt;
}

/// Parses one value into `out`; reports and returns false on failure.
template <typename E>
bool load_value(const Node& node, E& out, const Constraints<E>& c, Context& context,
                const std::string& path) {
  std::optional<std::string> problem;
  if constexpr (std::is_same_v<E, bool>) {
    problem = parse_bool(node, out);
  } else if constexpr (std::is_integral_v<E>) {
    if constexpr (std::is_signed_v<E>) {
      std::int64_t wide = 0;
      problem = parse_int(node, wide);
      if (!problem) problem = narrow_integer(wide, out);
    } else {
      std::uint64_t wide = 0;
      problem = parse_uint(node, wide);
      if (!problem) problem = narrow_integer(wide, out);
    }
  } else if constexpr (std::is_floating_point_v<E>) {
    double wide = 0;
    problem = parse_double(node, wide);
    if (!problem) {
      if (std::abs(wide) > static_cast<double>(std::numeric_limits<E>::max())) {
        problem = node.scalar + " does not fit this field's type";
      } else {
        out = static_cast<E>(wide);
      }
    }
  } else if constexpr (std::is_same_v<E, std::string>) {
    problem = parse_string(node, out);
  } else if constexpr (std::is_enum_v<E>) {
    std::string name;
    problem = parse_string(node, name);
    if (!problem) {
      std::vector<std::string> names;
      for (const auto& [candidate, value] : c.names) {
        if (candidate == name) {
          out = value;
          return true;
        }
        names.push_back(candidate);
      }
      problem = "'" + name + "' is not one of: " + join_list(names);
      if (std::string guess = closest_match(name, names); !guess.empty())
        *problem += " (did you mean '" + guess + "'?)";
    }
  } else {
    const std::size_t before = context.error_count();
    load_record(&node, out, *c.fields, context, path);
    return context.error_count() == before;
  }
  if (!problem) problem = check_value(out, c);
  if (problem) {
    context.key_error(&node, path, *problem);
    return false;
  }
  return true;
}

template <typename E>
Node dump_value(const E& value, const Constraints<E>& c) {
  if constexpr (std::is_same_v<E, std::string>) {
    return Node::make_scalar(value, /*is_quoted=*/true);
  } else if constexpr (kIsScalar<E>) {
    return Node::make_scalar(format_value(value, c));
  } else {
    return dump_record(value, *c.fields);
  }
}

template <typename T>
void load_record(const Node* node, T& out, const Fields<T>& fields, Context& context,
                 const std::string& path) {
  if (node != nullptr && node->kind != Node::Kind::kMap && node->kind != Node::Kind::kNull) {
    const std::string problem = "expected a map of keys, got " + describe_found(*node);
    if (path.empty()) {
      context.error(node, "the top level must be a map of keys, got " + describe_found(*node));
    } else {
      context.key_error(node, path, problem);
    }
    return;
  }
  const std::size_t errors_before = context.error_count();
  std::vector<std::string> keys;
  for (const Field<T>& field : fields.fields()) {
    const std::string& key = field.impl().key();
    keys.push_back(key);
    const Node* value = node != nullptr ? node->find(key) : nullptr;
    field.impl().load(value, out, context, join_key(path, key));
  }
  if (node != nullptr) {
    for (const auto& [key, value] : node->entries) {
      bool known = false;
      for (const std::string& candidate : keys) known = known || candidate == key;
      if (known) continue;
      std::string message = "unknown key '" + join_key(path, key) + "'";
      if (std::string guess = closest_match(key, keys); !guess.empty()) {
        message += " (did you mean '" + guess + "'?)";
      } else if (!keys.empty()) {
        message += " (allowed here: " + join_list(keys) + ")";
      }
      context.error(&value, message);
    }
  }
  if (context.error_count() != errors_before) return;  // checks see only fully loaded structs
  for (const auto& check : fields.checks()) {
    if (Status status = check(out); !status) {
      if (path.empty()) {
        context.error(nullptr, status.error().message);  // about the whole file, no single line
      } else {
        context.key_error(node, path, status.error().message);
      }
    }
  }
}

template <typename T>
Node dump_record(const T& value, const Fields<T>& fields) {
  Node map = Node::make_map();
  for (const Field<T>& field : fields.fields())
    map.entries.push_back(MapEntry{field.impl().key(), field.impl().dump(value)});
  return map;
}

template <typename T>
void check_record_schema(const Fields<T>& fields, Context& context, const std::string& path) {
  std::vector<std::string> seen;
  for (const Field<T>& field : fields.fields()) {
    const std::string& key = field.impl().key();
    const std::string full = join_key(path, key);
    if (key.empty() || key.find_first_of(".[]= ") != std::string::npos) {
      context.error(nullptr,
                    "config schema error: key '" + full + "' must be non-empty without . [ ] = or spaces");
    }
    for (const std::string& other : seen) {
      if (other == key) context.error(nullptr, "config schema error: key '" + full + "' is declared twice");
    }
    seen.push_back(key);
    field.impl().check_schema(context, full);
  }
}

template <typename T>
void describe_record(const Fields<T>& fields, std::vector<std::string>& lines, const std::string& path) {
  for (const Field<T>& field : fields.fields())
    field.impl().describe(lines, join_key(path, field.impl().key()));
}

}  // namespace detail

template <typename T, typename M>
void FieldSpec<T, M>::load(const detail::Node* value, T& out, detail::Context& context,
                           const std::string& path) const {
  using detail::Node;
  M& target = out.*member_;
  if constexpr (!kIsList && detail::kIsRecord<Element>) {
    // An absent or empty nested map: load its defaults and report its missing required keys.
    detail::load_record(value, target, *constraints_.fields, context, path);
    return;
  } else {
    if (value == nullptr) {
      if (default_) {
        target = *default_;
      } else {
        std::string message = "missing required key '" + path + "' (" + type_name();
        if (!constraints_.unit.empty()) message += ", " + constraints_.unit;
        message += doc_.empty() ? ")" : "): " + doc_;
        context.error(nullptr, message);
      }
      return;
    }
    if (value->kind == Node::Kind::kNull) {
      context.key_error(
          value, path,
          default_ ? "has no value (write one, or remove the key to use the default)" : "has no value");
      return;
    }
    if constexpr (kIsList) {
      if (value->kind != Node::Kind::kSequence) {
        context.key_error(value, path, "expected a list, got " + detail::describe_found(*value));
        return;
      }
      M loaded;
      loaded.reserve(value->items.size());
      bool ok = true;
      for (std::size_t i = 0; i < value->items.size(); ++i) {
        Element element{};
        if (detail::load_value(value->items[i], element, constraints_, context, detail::index_key(path, i))) {
          loaded.push_back(std::move(element));
        } else {
          ok = false;
        }
      }
      if (length_ && (loaded.size() < length_->first || loaded.size() > length_->second) && ok) {
        const std::string expected =
            length_->first == length_->second
                ? "exactly " + std::to_string(length_->first)
                : "between " + std::to_string(length_->first) + " and " + std::to_string(length_->second);
        context.key_error(value, path,
                          "has " + std::to_string(loaded.size()) + " elements, expected " + expected);
        return;
      }
      if (ok) target = std::move(loaded);
    } else {
      Element loaded{};
      if (detail::load_value(*value, loaded, constraints_, context, path)) target = std::move(loaded);
    }
  }
}

template <typename T, typename M>
detail::Node FieldSpec<T, M>::dump(const T& in) const {
  const M& value = in.*member_;
  detail::Node node;
  if constexpr (kIsList) {
    node = detail::Node::make_sequence();
    for (const Element& element : value) node.items.push_back(detail::dump_value(element, constraints_));
  } else {
    node = detail::dump_value(value, constraints_);
  }
  if constexpr (detail::kIsScalar<Element>) node.comment = comment();  // block maps/lists get no comment
  return node;
}

template <typename T, typename M>
std::string FieldSpec<T, M>::default_text() const {
  if constexpr (kIsList) {
    std::string text = "[";
    for (std::size_t i = 0; i < default_->size(); ++i) {
      if (i > 0) text += ", ";
      if constexpr (detail::kIsScalar<Element>) {
        text += detail::format_value((*default_)[i], constraints_);
      } else {
        text += "{...}";
      }
    }
    return text + "]";
  } else {
    return detail::format_value(*default_, constraints_);
  }
}

template <typename T, typename M>
void FieldSpec<T, M>::check_schema(detail::Context& context, const std::string& path) const {
  const std::string prefix = "config schema error: key '" + path + "': ";
  if constexpr (kIsNumber) {
    if (constraints_.min && constraints_.max && *constraints_.min > *constraints_.max) {
      context.error(nullptr, prefix + "range minimum is above its maximum");
    }
  }
  if constexpr (std::is_enum_v<Element>) {
    if (constraints_.names.empty())
      context.error(nullptr, prefix + "enum field needs .values({{\"name\", value}, ...})");
  }
  if constexpr (detail::kIsRecord<Element>) {
    detail::check_record_schema(*constraints_.fields, context, path);
  }
  if (length_ && length_->first > length_->second) {
    context.error(nullptr, prefix + "length minimum is above its maximum");
  }
  if (default_) {
    if constexpr (kIsList) {
      if (length_ && (default_->size() < length_->first || default_->size() > length_->second)) {
        context.error(nullptr, prefix + "the default list has " + std::to_string(default_->size()) +
                                   " elements, outside its length limits");
      }
      for (const Element& element : *default_) {
        if constexpr (detail::kIsScalar<Element>) {
          if (auto problem = detail::check_value(element, constraints_)) {
            context.error(nullptr, prefix + "default: " + *problem);
          }
        }
      }
    } else if constexpr (detail::kIsScalar<Element>) {
      if (auto problem = detail::check_value(*default_, constraints_)) {
        context.error(nullptr, prefix + "default: " + *problem);
      }
    }
  }
}

template <typename T, typename M>
std::string FieldSpec<T, M>::type_name() const {
  const std::string element = detail::type_name_of(constraints_);
  return kIsList ? "list of " + element : element;
}

template <typename T, typename M>
std::string FieldSpec<T, M>::comment() const {
  std::string text;
  if (!constraints_.unit.empty()) text = "[" + constraints_.unit + "]";
  if (!doc_.empty()) text += (text.empty() ? "" : " ") + doc_;
  return text;
}

template <typename T, typename M>
void FieldSpec<T, M>::describe(std::vector<std::string>& lines, const std::string& path) const {
  if constexpr (!kIsList && detail::kIsRecord<Element>) {
    if (!doc_.empty()) lines.push_back(path + ": map: " + doc_);
    detail::describe_record(*constraints_.fields, lines, path);
  } else {
    std::string line = path + ": " + type_name();
    if constexpr (kIsNumber) {
      if (constraints_.min && constraints_.max) {
        line += " in [" + detail::format_value(*constraints_.min, constraints_) + ", " +
                detail::format_value(*constraints_.max, constraints_) + "]";
      } else if (constraints_.min) {
        line += " >= " + detail::format_value(*constraints_.min, constraints_);
      } else if (constraints_.max) {
        line += " <= " + detail::format_value(*constraints_.max, constraints_);
      }
    }
    if constexpr (std::is_same_v<Element, std::string>) {
      if (!constraints_.allowed.empty()) line += " (one of " + detail::join_list(constraints_.allowed) + ")";
    }
    if (length_)
      line += ", " + std::to_string(length_->first) + " to " + std::to_string(length_->second) + " elements";
    if (!constraints_.unit.empty()) line += ", unit " + constraints_.unit;
    if (default_) {
      line += ", default " + default_text();
    } else {
      line += ", required";
    }
    if (!doc_.empty()) line += ": " + doc_;
    lines.push_back(std::move(line));
    if constexpr (kIsList && detail::kIsRecord<Element>) {
      detail::describe_record(*constraints_.fields, lines, path + "[]");
    }
  }
}

template <typename T, typename M>
void FieldSpec<T, M>::collect(std::vector<KeyInfo>& out, const T& in, const std::string& path) const {
  if constexpr (!kIsList && detail::kIsRecord<Element>) {
    for (const Field<Element>& field : constraints_.fields->fields()) {
      field.impl().collect(out, in.*member_, detail::join_key(path, field.impl().key()));
    }
  } else if constexpr (!kIsList) {
    KeyInfo info{.key = path, .type = type_name(), .unit = constraints_.unit, .doc = doc_};
    if constexpr (std::is_same_v<Element, std::string>) {
      info.value = in.*member_;
      info.allowed = constraints_.allowed;
    } else {
      info.value = detail::format_value(in.*member_, constraints_);
    }
    if constexpr (kIsNumber) {
      if (constraints_.min) info.min = static_cast<double>(*constraints_.min);
      if (constraints_.max) info.max = static_cast<double>(*constraints_.max);
    }
    if constexpr (std::is_enum_v<Element>) {
      for (const auto& [name, value] : constraints_.names) info.allowed.push_back(name);
    }
    out.push_back(std::move(info));
  }
}

template <typename T>
std::vector<KeyInfo> key_infos(const T& value, const Fields<T>& fields) {
  std::vector<KeyInfo> out;
  for (const Field<T>& field : fields.fields()) field.impl().collect(out, value, field.impl().key());
  return out;
}

template <typename T>
Result<T> load_string(std::string_view yaml, const Fields<T>& fields, std::string_view source,
                      std::span<const std::string> overrides) {
  detail::Context context{std::string(source)};
  detail::check_record_schema(fields, context, "");
  if (context.error_count() != 0) return context.to_error();

  Result<detail::Node> root = detail::parse_yaml(yaml, source);
  if (!root) return root.error();
  for (const std::string& assignment : overrides) {
    if (Status applied = detail::apply_override(*root, assignment, source); !applied) return applied.error();
  }
  T value{};
  detail::load_record(&*root, value, fields, context, "");
  if (context.error_count() != 0) return context.to_error();
  return value;
}

template <typename T>
Result<T> load_file(const std::string& path, const Fields<T>& fields,
                    std::span<const std::string> overrides) {
  Result<std::string> text = detail::read_file(path);
  if (!text) return text.error();
  return load_string(*text, fields, path, overrides);
}

template <typename T>
Result<T> load_files(std::span<const std::string> paths, const Fields<T>& fields,
                     std::span<const std::string> overrides) {
  if (paths.empty()) return Error{"no config file given"};
  detail::Context context{paths.front()};
  detail::check_record_schema(fields, context, "");
  if (context.error_count() != 0) return context.to_error();

  Result<std::string> text = detail::read_file(paths.front());
  if (!text) return text.error();
  Result<detail::Node> root = detail::parse_yaml(*text, paths.front());
  if (!root) return root.error();
  for (const std::string& path : paths.subspan(1)) {
    Result<std::string> layer_text = detail::read_file(path);
    if (!layer_text) return layer_text.error();
    Result<detail::Node> layer = detail::parse_yaml(*layer_text, path);
    if (!layer) return layer.error();
    detail::merge_layer(*root, std::move(*layer), path);
  }
  for (const std::string& assignment : overrides) {
    if (Status applied = detail::apply_override(*root, assignment, paths.front()); !applied) {
      return applied.error();
    }
  }
  T value{};
  detail::load_record(&*root, value, fields, context, "");
  if (context.error_count() != 0) return context.to_error();
  return value;
}

template <typename T>
std::string to_yaml(const T& value, const Fields<T>& fields) {
  return detail::emit_yaml(detail::dump_record(value, fields));
}

template <typename T>
std::string describe(const Fields<T>& fields) {
  std::vector<std::string> lines;
  detail::describe_record(fields, lines, "");
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

}  // namespace ssl::config
