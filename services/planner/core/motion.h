// Motion intents and the skill layer that turns them into velocity commands.
//
// A tree action decides WHAT a robot should do (go there, facing that way, at most this fast, keeping
// clear of these zones, dribbling or kicking) and writes it as a MotionIntent; a MotionPlanner decides HOW
// (the velocity to send now). Planner I uses SimpleMotionPlanner: a proportional approach with speed and
// acceleration limits, heading control, targets pushed out of forbidden zones and a local detour around
// them. Planner II replaces it with a trajectory planner behind the same interface.
//
//   SimpleMotionPlanner motion(limits);
//   RobotCommand command = motion.plan(robot, intent, zones_context, dt);
//
// All positions here are in the TEAM frame; commands come out in the robot's LOCAL frame.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>
#include <vector>

#include "services/planner/core/planner.h"
#include "libs/domain/team_field.h"
#include "libs/geometry/rectangle.h"
#include "libs/geometry/stadium.h"
#include "libs/domain/world.h"

namespace ssl::planner {

/// What one robot should do this tick (TEAM frame). Names are string literals (no allocation).
struct MotionIntent {
  bool active = false;                    // false: no intent (the robot is stopped)
  bool halt = false;                      // zero velocity now, whatever else is set
  Vec2 target = Vec2::Zero();             // m
  Vec2 target_velocity = Vec2::Zero();    // m/s the target moves at (a marked opponent): kept up with
  double orientation = 0;                 // rad, heading at the target
  double max_speed = 3.0;                 // m/s
  double max_angular_speed = std::numeric_limits<double>::infinity();  // rad/s (below the robot's limit)
  double avoid_ball_radius = 0;           // m, robot centre keeps this far from the ball; 0: may touch it
  bool keep_off_ball = false;             // no business at the ball: clear of it as it rolls (trajectory motion)
  bool contests_ball = false;             // goes for the ball (not yet dribbling or armed) or stands in
                                          // its way (keeper, blocker): the contact guard lets it contest
                                          // the ball with robots there
  bool guard_ball_circle = false;         // that circle is a hard limit on the command too (the zone guard)
  bool avoid_placement_corridor = false;  // keep out of the ball -> designated position stadium
  bool avoid_their_defense_area = true;   // keep the rule distance (+ margin) from their defense area
  bool avoid_our_defense_area = true;     // false only for the goalkeeper
  bool may_enter_boundary = false;        // the placer fetching a ball: up to the walls, not only the lines
  bool dribble = false;
  KickType kick = KickType::kNone;  // armed: the kicker fires when the ball touches it
  double kick_speed = 0;            // m/s
  std::string_view role = "idle";
  std::string_view tactic = "none";
  std::string_view skill = "move_to";
};

/// A visible robot as the skill layer sees it (TEAM frame).
struct ZoneRobot {
  std::uint32_t id = 0;
  bool ours = false;
  Vec2 position = Vec2::Zero();  // m
  Vec2 velocity = Vec2::Zero();  // m/s
};

/// Where robots must not go this tick (TEAM frame), as the rules and the current command say.
struct Zones {
  wm::Field field = wm::Field();
  std::optional<Vec2> ball;
  Vec2 ball_velocity = Vec2::Zero();                // m/s; zero while the ball is not seen
  std::optional<geom::Stadium> placement_corridor;  // ball -> designated position, for robot centres
  double their_defense_margin = 0.3;     // m, robot centre distance from their defense area
  double our_defense_margin = 0.1;       // m, robot centre distance from our defense area (non-keepers)
  double field_margin = 0.05;            // m, how far beyond the field lines a centre may go
  double wall_margin = 0.11;             // m, robot centre from the walls when it may enter the boundary
  std::vector<ZoneRobot> robots;         // every visible robot, ours and theirs (the planned one included)
};

/// `p` moved (minimally, a few passes) out of every zone the intent asks to avoid and into the field.
Vec2 project_out(const Vec2& p, const MotionIntent& intent, const Zones& zones);

// ---- shared by the skill layers ----

/// Where robot centres keep out of our (-x) / their (+x) defense area: grown by the zones' margin towards
/// the field and sideways, and reaching behind the goal line into the goal and up to the wall.
geom::Rectangle our_defense_zone(const Zones& zones);
/// The way out of a defense zone (`zone` centred on y = 0, open towards +x or -x) for a centre `p` in it or
/// on its edge: the unit normal of the nearer of its front and the side on p's side (never behind the goal).
Vec2 zone_exit_normal(const geom::Rectangle& zone, const Vec2& p, bool opens_towards_positive_x);
geom::Rectangle their_defense_zone(const Zones& zones);
/// Where the intent lets a robot centre go: the field and field_margin beyond its lines, or, for a robot
/// that may enter the boundary, up to wall_margin from the walls.
geom::Rectangle allowed_area(const MotionIntent& intent, const Zones& zones);
/// The intent's dribbler and kick (flat or chip) on `command`; its motion is left alone.
void set_ball_actions(const MotionIntent& intent, RobotCommand& command);

/// The skill layer: one robot, one tick.
class MotionPlanner {
 public:
  virtual ~MotionPlanner() = default;

  /// The command that moves `robot` towards `intent` during the next `dt` seconds.
  virtual RobotCommand plan(const wm::RobotState& robot, const MotionIntent& intent, const Zones& zones,
                            double dt) = 0;

  /// `velocity` (team frame) for `robot` kept off the other robots as plan() keeps its own: for a velocity
  /// the rule layer changed after plan() (the escape from the ball's circle). As given without a guard.
  virtual Vec2 keep_off_robots(const wm::RobotState& /*robot*/, const MotionIntent& /*intent*/,
                               const Zones& /*zones*/, const Vec2& velocity) const {
    return velocity;
  }

  /// What was finally sent after the rule layer (team frame), so that acceleration limits start from it.
  virtual void sent(std::uint32_t /*id*/, const Vec2& /*velocity*/, double /*angular*/) {}

  /// Called once per tick before the first plan(): robots are then planned in priority order.
  virtual void begin_tick() {}

  /// s from this tick until its commands act on the robots: as configured, or `measured` by world_model.
  virtual void set_actuation_latency(double /*latency*/, bool /*measured*/) {}

  /// For planner.debug: robot `id`'s planned path this tick (team frame, every `step` s; empty without
  /// one) and how far the robot was from where last tick's plan put it (nullopt without one).
  virtual void describe(std::uint32_t /*id*/, double /*step*/, std::vector<Vec2>& path,
                        std::optional<double>& tracking_error) const {
    path.clear();
    tracking_error.reset();
  }
};

/// Planner I's controller. Keeps the last sent velocity per robot id (0..15) for acceleration limiting.
class SimpleMotionPlanner final : public MotionPlanner {
 public:
  explicit SimpleMotionPlanner(const MotionLimits& limits);

  RobotCommand plan(const wm::RobotState& robot, const MotionIntent& intent, const Zones& zones,
                    double dt) override;
  void sent(std::uint32_t id, const Vec2& velocity, double angular) override;

 private:
  struct Memory {
    Vec2 velocity = Vec2::Zero();
    double angular = 0;
  };

  MotionLimits limits_;
  std::array<Memory, wm::kMaxRobotsPerTeam> memory_{};
};

/// Local-frame command from a team-frame velocity and the robot's heading.
RobotCommand to_local(std::uint32_t id, const Vec2& velocity, double angular, double heading);
/// Team-frame velocity of a local-frame command.
Vec2 to_team(const RobotCommand& command, double heading);

}  // namespace ssl::planner
