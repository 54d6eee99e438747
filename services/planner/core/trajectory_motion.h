// Planner II's skill layer: each robot follows a time-optimal trajectory path (trajectory.h) that the path
// search (path_search.h) finds around every obstacle, re-planned every tick from the robot's measured
// position and the velocity last sent to it (the measured one lags by the vision delay).
//
// Obstacles of one robot, in the TEAM frame:
//   * our robots planned earlier this tick: their paths (robots are planned in priority order);
//     our robots not planned yet: where their velocity takes them;
//   * opponents: where their velocity takes them, with a margin that grows with our speed, so that a
//     contact is never faster than the league's crash limit on our side;
//   * the intent's rule zones: both defense areas, the placement corridor, the ball's keep-out circle,
//     and the field (or, for the placer, the walls) as bounds.
// The command is the path's velocity one tick ahead, in the robot's LOCAL frame; the heading follows its
// own trajectory the short way round.
//
//   TrajectoryMotionPlanner motion(limits);
//   motion.begin_tick();
//   RobotCommand command = motion.plan(robot, intent, zones, dt);
#pragma once

#include <array>
#include <optional>

#include "services/planner/core/motion.h"
#include "services/planner/core/path_search.h"

namespace ssl::planner {

struct TrajectoryMotionParams {
  double robot_radius = 0.09;          // m, ours and theirs
  double actuation_latency = 0;        // s until a command acts: plans start where the last one takes us
  double our_margin = 0.03;            // m between two of our robots
  double their_margin = 0.05;          // m between us and an opponent at rest
  double their_margin_per_speed = 0.1;  // s: more margin per m/s of our speed (an opponent may move)
  // Sub-destinations per ring and tick; successive ticks turn the rings by half the spacing, so that two
  // ticks try twice as many directions (last tick's best is always tried again).
  PathSearchParams search = {.directions = 8};
};

class TrajectoryMotionPlanner final : public MotionPlanner {
 public:
  explicit TrajectoryMotionPlanner(const MotionLimits& limits, const TrajectoryMotionParams& params = {});

  RobotCommand plan(const wm::RobotState& robot, const MotionIntent& intent, const Zones& zones,
                    double dt) override;
  void sent(std::uint32_t id, const Vec2& velocity, double angular) override;
  void begin_tick() override;
  void describe(std::uint32_t id, double step, std::vector<Vec2>& path,
                std::optional<double>& tracking_error) const override;

  /// The path chosen for robot `id` this tick (TEAM frame), if it was planned.
  const std::optional<PathResult>& path(std::uint32_t id) const { return memory_.at(id).planned; }

 private:
  struct Memory {
    Vec2 velocity = Vec2::Zero();  // last sent, team frame
    double angular = 0;
    std::optional<PathResult> planned;  // this tick's (reset by begin_tick)
    std::optional<TrajectoryPath> previous;  // last tick's, for the search
    bool planned_this_tick = false;
    std::optional<double> tracking_error;  // m, this tick
  };

  /// One robot's obstacles; the other robots come first in `obstacles.circles` (`robots` of them).
  struct Obstacles {
    PathObstacles obstacles;
    std::size_t robots = 0;
  };
  Obstacles obstacles_for(const wm::RobotState& robot, const MotionIntent& intent, const Zones& zones) const;
  /// `target` moved out of any robot standing on it (our robots: where their planned paths end).
  static Vec2 free_target(const wm::RobotState& robot, Vec2 target, const Obstacles& obstacles);

  MotionLimits limits_;
  TrajectoryMotionParams params_;
  std::array<Memory, wm::kMaxRobotsPerTeam> memory_{};
  std::uint64_t ticks_ = 0;
};

}  // namespace ssl::planner
