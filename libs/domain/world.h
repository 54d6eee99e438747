// The world types of the shared domain vocabulary (namespace ssl::wm): what world_model takes in
// (detections, geometry, referee, robot feedback and the commands we sent) and what it publishes and the
// planner consumes (WorldState, with its team frame). SI units (m, m/s, rad, rad/s, s).
//
// Frames. INPUTS are in the SSL-Vision global frame (origin at the field centre, x along the length,
// angles CCW from +x), except robot commands, which are in each robot's local frame (forward, left, CCW).
// The OUTPUT WorldState is in the TEAM frame (our goal at negative x, angle 0 towards the opponent goal,
// CCW positive); the one conversion is TeamFrame (team_frame.h), applied in WorldModel::state().
//
// Clocks. Capture and sent times are on the VISION clock (SSL-Vision host, Unix ns); `now` arguments and
// receive times are on this host's wall clock (Unix ns). WorldModel estimates the offset between the two.
// Wire types never appear here: the adapter converts IDL samples once.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "libs/common/team.h"
#include "libs/domain/field.h"
#include "libs/geometry/vec2.h"
#include "libs/time/time.h"

namespace ssl::wm {

using geom::Vec2;
using Vec3 = Eigen::Vector3d;

inline constexpr std::uint32_t kMaxRobotsPerTeam = 16;

struct BallDetection {
  Vec2 position = Vec2::Zero();  // m, vision frame (an airborne ball: projected onto z = ball radius)
  double z = 0;                  // m, only when has_z
  bool has_z = false;
  double confidence = 1;         // 0..1
};

struct RobotDetection {
  std::uint32_t id = 0;          // pattern id 0..15
  Vec2 position = Vec2::Zero();  // m, vision frame
  double orientation = 0;        // rad, vision frame; only when has_orientation
  bool has_orientation = true;
  double confidence = 1;         // 0..1
};

/// One camera frame (SSL_DetectionFrame in SI units).
struct DetectionFrame {
  std::uint32_t camera_id = 0;
  std::uint32_t frame_number = 0;
  time::Timestamp capture_time;   // vision clock
  time::Timestamp sent_time;      // vision clock (capture + processing); == capture_time when unknown
  time::Timestamp receive_time;   // gateway host wall clock (0 when unknown)
  std::vector<BallDetection> balls;
  std::vector<RobotDetection> robots_yellow;
  std::vector<RobotDetection> robots_blue;
};

/// Field dimensions, metres (SSL_GeometryFieldSize): the shared vocabulary's (libs/domain/field.h).
using FieldSize = ssl::FieldGeometry;

struct CameraInfo {
  std::uint32_t camera_id = 0;
  Vec3 position = Vec3::Zero();  // m, camera centre in the vision frame (calibration's derived_world)
};

/// Straight-ball model published by ssl-vision (accelerations negative).
struct BallModel {
  double acc_slide = -3.0;  // m/s^2
  double acc_roll = -0.35;  // m/s^2
  double k_switch = 0.7;    // fraction of the kick speed at which rolling starts
};

struct Geometry {
  FieldSize field;
  std::vector<CameraInfo> cameras;
  std::optional<BallModel> ball_model;  // nullopt: keep the configured one
};

/// Referee commands, same order as the league's Referee.Command (and idl/referee.idl).
enum class RefereeCommand {
  kHalt,
  kStop,
  kNormalStart,
  kForceStart,
  kPrepareKickoffYellow,
  kPrepareKickoffBlue,
  kPreparePenaltyYellow,
  kPreparePenaltyBlue,
  kDirectFreeYellow,
  kDirectFreeBlue,
  kIndirectFreeYellow,
  kIndirectFreeBlue,
  kTimeoutYellow,
  kTimeoutBlue,
  kGoalYellow,
  kGoalBlue,
  kBallPlacementYellow,
  kBallPlacementBlue,
};

/// The part of referee.state that world_model and the planner use (both teams; GameState takes one team's
/// view of it). Converted from the IDL in ONE place: libs/domain/idl_convert.h.
struct RefereeInfo {
  RefereeCommand command = RefereeCommand::kHalt;
  std::uint32_t command_counter = 0;
  std::optional<bool> blue_team_on_positive_half;
  std::optional<Vec2> designated_position;  // m, VISION frame (ball placement target)
  std::optional<RefereeCommand> next_command;
  std::uint32_t yellow_goalkeeper = 0;
  std::uint32_t blue_goalkeeper = 0;
  bool yellow_can_place_ball = true;  // TeamInfo.can_place_ball (false after too many failed placements)
  bool blue_can_place_ball = true;
  std::uint32_t yellow_max_allowed_bots = 11;  // TeamInfo.max_allowed_bots (lowered by cards)
  std::uint32_t blue_max_allowed_bots = 11;
};

/// robot.feedback of one of OUR robots.
struct RobotFeedback {
  std::uint32_t id = 0;
  bool ball_in_dribbler = false;
};

/// One command we sent to one of OUR robots, local frame.
struct RobotCommand {
  std::uint32_t id = 0;
  double forward = 0;  // m/s
  double left = 0;     // m/s
  double angular = 0;  // rad/s
};

// ---- output (TEAM frame) -------------------------------------------------------------------------------

enum class Possession { kNone, kFriendly, kEnemy, kContested };

struct BallState {
  Vec3 position = Vec3::Zero();  // m, team frame, z = height of the centre
  Vec3 velocity = Vec3::Zero();  // m/s, team frame
  bool visible = false;          // a detection was used within the visibility timeout
  double confidence = 0;         // 0..1
  time::Timestamp last_seen;     // vision clock: capture time of the last detection used
  bool in_dribbler = false;      // placed at a robot's dribbler (feedback or geometry)
  bool airborne = false;         // a chip flight is being reconstructed
};

struct RobotState {
  std::uint32_t id = 0;
  Vec2 position = Vec2::Zero();  // m, team frame
  double orientation = 0;        // rad, team frame, (-pi, pi]
  Vec2 velocity = Vec2::Zero();  // m/s, team frame
  double angular_velocity = 0;   // rad/s
  bool visible = false;
  double confidence = 0;         // 0..1
};

struct VisionStamp {
  time::Timestamp capture_time;  // vision clock, newest frame used
  time::Timestamp receive_time;  // gateway wall clock of that frame
  std::uint32_t camera_id = 0;
  std::uint32_t frame_number = 0;
};

struct WorldState {
  TeamColor team = TeamColor::kBlue;  // whose frame
  VisionStamp stamp;
  time::Timestamp predicted_to;       // vision clock: the instant the state was predicted to
  bool has_ball = false;
  BallState ball;
  std::vector<RobotState> friendly;   // by id
  std::vector<RobotState> enemy;      // by id
  Possession possession = Possession::kNone;
  std::optional<std::uint32_t> possessing_robot;  // robot of the possessing (or last touching) team
  bool flipped = false;               // the team frame is the vision frame turned by pi
  std::optional<double> command_delay;  // s, our robots' measured delay from command to motion
};

}  // namespace ssl::wm
