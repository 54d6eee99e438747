// What the console shows, as plain values: the adapter converts every DDS sample into these once; the core
// (ConsoleState) keeps the latest of each and turns them into the page's JSON (PROTOCOL.md). Metres,
// radians, seconds. Team-scoped inputs (world state, planner debug) are in THAT team's frame, as
// published; everything the core emits is in the vision frame.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "libs/common/team.h"
#include "libs/config/config.h"
#include "libs/geometry/vec2.h"
#include "libs/time/time.h"

namespace ssl::console {

struct RobotView {
  TeamColor team = TeamColor::kBlue;
  std::uint32_t id = 0;
  geom::Vec2 position = geom::Vec2::Zero();
  double heading = 0;                       // rad
  geom::Vec2 velocity = geom::Vec2::Zero();
  bool visible = true;
};

struct BallView {
  geom::Vec2 position = geom::Vec2::Zero();
  double height = 0;
  geom::Vec2 velocity = geom::Vec2::Zero();
  bool visible = true;
};

/// One camera's latest raw detections (vision frame).
struct CameraView {
  std::uint32_t camera_id = 0;
  std::vector<geom::Vec2> balls;
  std::vector<RobotView> robots;
};

enum class Possession { kNone, kOurs, kTheirs, kContested };

/// One team's world.state, in that team's frame (`flipped` as world_model published it).
struct TeamWorld {
  bool flipped = false;
  std::optional<BallView> ball;
  std::vector<RobotView> robots;  // both colours
  Possession possession = Possession::kNone;
};

enum class NodeStatus { kIdle, kRunning, kSuccess, kFailure };

struct TreeNodeView {
  std::string name;
  int depth = 0;
  NodeStatus status = NodeStatus::kIdle;
};

struct RoleView {
  std::uint32_t id = 0;
  std::string role;
  std::string tactic;
  std::string skill;
};

struct PathView {
  std::uint32_t id = 0;
  std::vector<geom::Vec2> points;
  geom::Vec2 destination = geom::Vec2::Zero();
};

/// One team's planner.debug, in that team's frame.
struct TeamDebug {
  std::string play;
  std::string tactic;
  double tick_duration = 0;  // s
  std::vector<RoleView> roles;
  std::vector<TreeNodeView> tree;
  std::vector<PathView> paths;
};

enum class HealthLevel { kOk, kWarn, kError };

/// One service instance's system.health.
struct ServiceHealth {
  std::string service;
  std::string host;
  HealthLevel level = HealthLevel::kOk;
  std::string status;
  double rate_hz = 0;
  double latency_p99 = 0;  // s
  std::uint64_t errors = 0;
  std::uint64_t dropped = 0;
  double uptime = 0;       // s
};

/// One robot's robot.feedback.
struct RobotFeedbackView {
  TeamColor team = TeamColor::kBlue;
  std::uint32_t id = 0;
  std::optional<double> battery_voltage;  // V
  std::optional<double> link_quality;     // 0..1
};

/// One service instance's run-time parameters (system.param_state) and its answer to the last request.
struct ParameterStateView {
  std::string target;                  // "planner/blue"
  std::vector<config::KeyInfo> params;
  std::uint64_t revision = 0;          // of the last request answered
  bool accepted = true;
  std::string reason;
  std::string saved_file;
};

struct EstopView {
  bool engaged = false;
  std::string source;
  std::string reason;
};

}  // namespace ssl::console
