// The operator actions the page (or any HTTP client) may ask for, parsed and validated from their JSON
// bodies (PROTOCOL.md), and who may ask. Pure: a bad body gets an Error that names what is wrong, and
// nothing reaches the bus unless it parsed.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "libs/common/result.h"
#include "libs/common/team.h"
#include "libs/domain/field.h"
#include "libs/geometry/vec2.h"
#include "services/referee_gateway/core/types.h"

namespace ssl::console {

struct RefereeAction {
  referee::Command command = referee::Command::kHalt;
  std::optional<geom::Vec2> designated;  // m, vision frame; only for BALL_PLACEMENT_*
};

struct EstopAction {
  bool engaged = true;
  std::string reason;
};

enum class PlaceObject { kBall, kRobot };

struct PlaceAction {
  PlaceObject object = PlaceObject::kBall;
  TeamColor team = TeamColor::kBlue;     // robots only
  std::uint32_t id = 0;                  // robots only
  geom::Vec2 position = geom::Vec2::Zero();  // m, vision frame
  std::optional<double> heading;         // rad; robots only (default: keep the robot's heading)
};

struct ParamAction {
  std::string target;  // service instance, e.g. "planner/blue"
  std::string key;     // dotted config key
  std::string value;   // YAML scalar text
};

struct ParamSaveAction {
  std::string target;
};

inline constexpr std::size_t kMaxTextLength = 200;  // reasons, keys, values, targets
inline constexpr std::uint32_t kMaxRobotId = 15;    // SSL-Vision's pattern ids

/// `field` bounds the positions: anywhere on the carpet (inside the walls).
Result<RefereeAction> parse_referee_action(std::string_view body, const FieldGeometry& field);
Result<EstopAction> parse_estop_action(std::string_view body);
Result<PlaceAction> parse_place_action(std::string_view body, const FieldGeometry& field);
Result<ParamAction> parse_param_action(std::string_view body);
Result<ParamSaveAction> parse_param_save_action(std::string_view body);

/// The league name ("STOP") of a referee command, or nullopt.
std::optional<referee::Command> parse_command(std::string_view name);

/// Who may act: with a token configured, exactly the requests that carry it; without one, everyone when
/// the console listens on a loopback address only, and nobody otherwise (a read-only console).
class AccessPolicy {
 public:
  AccessPolicy(std::string bind_address, std::string token);

  bool allows(std::string_view given_token) const;
  /// Operator actions are possible at all (a page can be told so before it tries).
  bool operator_possible() const { return !token_.empty() || loopback_; }
  bool needs_token() const { return !token_.empty(); }

 private:
  std::string token_;
  bool loopback_ = false;
};

/// 127.0.0.0/8, ::1 and "localhost".
bool is_loopback(std::string_view address);

}  // namespace ssl::console
