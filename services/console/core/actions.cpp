#include "services/console/core/actions.h"

#include <cmath>
#include <nlohmann/json.hpp>

namespace ssl::console {
namespace {

using nlohmann::json;

Result<json> parse_object(std::string_view body) {
  json parsed = json::parse(body, nullptr, /*allow_exceptions=*/false);
  if (parsed.is_discarded()) return Error{"the body is not JSON"};
  if (!parsed.is_object()) return Error{"the body must be a JSON object"};
  return parsed;
}

Result<std::string> text_field(const json& object, const char* name, bool required = true) {
  const auto it = object.find(name);
  if (it == object.end()) {
    if (required) return Error{std::string("'") + name + "' is missing"};
    return std::string();
  }
  if (!it->is_string()) return Error{std::string("'") + name + "' must be a string"};
  std::string text = it->get<std::string>();
  if (text.size() > kMaxTextLength) {
    return Error{std::string("'") + name + "' is longer than " + std::to_string(kMaxTextLength) + " characters"};
  }
  return text;
}

Result<double> number_field(const json& object, const char* name) {
  const auto it = object.find(name);
  if (it == object.end()) return Error{std::string("'") + name + "' is missing"};
  if (!it->is_number()) return Error{std::string("'") + name + "' must be a number"};
  const double value = it->get<double>();
  if (!std::isfinite(value)) return Error{std::string("'") + name + "' must be finite"};
  return value;
}

/// The point must lie on the carpet, inside the walls.
Result<geom::Vec2> on_carpet(double x, double y, const FieldGeometry& field) {
  const double half_length = field.wall_half_length();
  const double half_width = field.wall_half_width();
  if (std::abs(x) > half_length || std::abs(y) > half_width) {
    char text[160];
    std::snprintf(text, sizeof text, "(%.2f, %.2f) is off the field (|x| <= %.2f, |y| <= %.2f m)", x, y, half_length,
                  half_width);
    return Error{text};
  }
  return geom::Vec2(x, y);
}

}  // namespace

std::optional<referee::Command> parse_command(std::string_view name) {
  for (int i = 0; i <= static_cast<int>(referee::Command::kBallPlacementBlue); ++i) {
    const auto command = static_cast<referee::Command>(i);
    if (referee::to_string(command) == name) return command;
  }
  return std::nullopt;
}

Result<RefereeAction> parse_referee_action(std::string_view body, const FieldGeometry& field) {
  auto object = parse_object(body);
  if (!object) return object.error();
  auto name = text_field(*object, "command");
  if (!name) return name.error();
  const std::optional<referee::Command> command = parse_command(*name);
  if (!command) return Error{"unknown referee command '" + *name + "' (HALT, STOP, NORMAL_START, ...)"};
  RefereeAction action{.command = *command};
  const auto designated = object->find("designated");
  if (designated != object->end() && !designated->is_null()) {
    if (!designated->is_array() || designated->size() != 2 || !(*designated)[0].is_number() ||
        !(*designated)[1].is_number()) {
      return Error{"'designated' must be [x, y] in metres"};
    }
    const double x = (*designated)[0].get<double>();
    const double y = (*designated)[1].get<double>();
    if (!std::isfinite(x) || !std::isfinite(y)) return Error{"'designated' must be finite"};
    auto point = on_carpet(x, y, field);
    if (!point) return point.error();
    action.designated = *point;
  }
  return action;
}

Result<EstopAction> parse_estop_action(std::string_view body) {
  auto object = parse_object(body);
  if (!object) return object.error();
  const auto engaged = object->find("engaged");
  if (engaged == object->end() || !engaged->is_boolean()) return Error{"'engaged' must be true or false"};
  auto reason = text_field(*object, "reason", false);
  if (!reason) return reason.error();
  return EstopAction{.engaged = engaged->get<bool>(), .reason = *reason};
}

Result<PlaceAction> parse_place_action(std::string_view body, const FieldGeometry& field) {
  auto object = parse_object(body);
  if (!object) return object.error();
  auto kind = text_field(*object, "object");
  if (!kind) return kind.error();
  PlaceAction action;
  if (*kind == "ball") {
    action.object = PlaceObject::kBall;
  } else if (*kind == "robot") {
    action.object = PlaceObject::kRobot;
    auto team_name = text_field(*object, "team");
    if (!team_name) return team_name.error();
    const std::optional<TeamColor> team = parse_team(*team_name);
    if (!team) return Error{"'team' must be blue or yellow"};
    action.team = *team;
    const auto id = object->find("id");
    if (id == object->end() || !id->is_number_integer() || id->get<std::int64_t>() < 0 ||
        id->get<std::int64_t>() > kMaxRobotId) {
      return Error{"'id' must be a robot id 0.." + std::to_string(kMaxRobotId)};
    }
    action.id = id->get<std::uint32_t>();
    if (object->contains("a") && !(*object)["a"].is_null()) {
      auto heading = number_field(*object, "a");
      if (!heading) return heading.error();
      action.heading = *heading;
    }
  } else {
    return Error{"'object' must be ball or robot"};
  }
  auto x = number_field(*object, "x");
  if (!x) return x.error();
  auto y = number_field(*object, "y");
  if (!y) return y.error();
  auto position = on_carpet(*x, *y, field);
  if (!position) return position.error();
  action.position = *position;
  return action;
}

Result<ParamAction> parse_param_action(std::string_view body) {
  auto object = parse_object(body);
  if (!object) return object.error();
  auto target = text_field(*object, "target");
  if (!target) return target.error();
  auto key = text_field(*object, "key");
  if (!key) return key.error();
  auto value = text_field(*object, "value");
  if (!value) return value.error();
  if (target->empty() || key->empty()) return Error{"'target' and 'key' must not be empty"};
  return ParamAction{*target, *key, *value};
}

Result<ParamSaveAction> parse_param_save_action(std::string_view body) {
  auto object = parse_object(body);
  if (!object) return object.error();
  auto target = text_field(*object, "target");
  if (!target) return target.error();
  if (target->empty()) return Error{"'target' must not be empty"};
  return ParamSaveAction{*target};
}

bool is_loopback(std::string_view address) {
  return address == "localhost" || address == "::1" || address.starts_with("127.");
}

AccessPolicy::AccessPolicy(std::string bind_address, std::string token)
    : token_(std::move(token)), loopback_(is_loopback(bind_address)) {}

bool AccessPolicy::allows(std::string_view given_token) const {
  if (token_.empty()) return loopback_;
  if (given_token.size() != token_.size()) return false;
  unsigned char difference = 0;  // constant time in the token's length
  for (std::size_t i = 0; i < token_.size(); ++i) {
    difference |= static_cast<unsigned char>(given_token[i] ^ token_[i]);
  }
  return difference == 0;
}

}  // namespace ssl::console
