// Planner II's skill layer: each robot follows a time-optimal trajectory path (trajectory.h) that the path
// search (path_search.h) finds around every obstacle, re-planned every tick from the robot's measured
// position and the velocity last sent to it (the measured one lags by the vision delay).
//
// Obstacles of one robot, in the TEAM frame:
//   * our robots planned earlier this tick: their paths (robots are planned in priority order);
//     our robots not planned yet: last tick's paths, or without one where their velocity takes them;
//   * opponents: where their velocity takes them (for robot_prediction s, then standing), with a margin;
//   * the intent's rule zones: both defense areas, the placement corridor, the ball's keep-out circle,
//     and the field (or, for the placer, the walls) as bounds.
// A robot inside a defense area or the placement corridor it must avoid first leaves it the shortest way.
// The command is the path's velocity one tick ahead, capped by the contact guard (the speed-dependent
// margin: towards any robot no faster than still stops us short of it, so that a contact is never ours to
// blame under the league's crash rule), in the robot's LOCAL frame; the heading follows its own trajectory
// the short way round.
//
//   TrajectoryMotionPlanner motion(limits);
//   motion.begin_tick();
//   RobotCommand command = motion.plan(robot, intent, zones, dt);
#pragma once

#include <algorithm>
#include <array>
#include <optional>
#include <span>

#include "services/planner/core/motion.h"
#include "services/planner/core/path_search.h"

namespace ssl::planner {

struct TrajectoryMotionParams {
  double robot_radius = 0.09;          // m, ours and theirs
  double actuation_latency = 0;        // s until a command acts: plans start where the last one takes us
  double our_margin = 0.03;            // m between two of our robots
  double their_margin = 0.05;          // m between us and an opponent
  double robot_prediction = 0.5;       // s a robot's measured velocity is extrapolated; then it stands
  double follow_gain = 3.0;            // 1/s: near a moving target, m/s of correction per m of distance
  // The contact guard, last before the command goes out: towards any robot, our speed may not exceed what
  // still stops us (after guard_latency at guard_deceleration) within half the gap that is left
  // guard_margin short of touching it, plus the way it goes on if, an opponent running away (within 45
  // degrees of straight away: one crossing our way may turn towards us instead; a teammate ahead is not
  // followed closely), it brakes at guard_other_braking.
  // Two robots that both keep it never touch, whatever each predicts of the other; only a robot driving
  // into another can still touch it.
  double guard_margin = 0.03;          // m beyond two radii
  double guard_latency = 0.06;         // s until a command acts (vision delay, pipeline, one tick); at least
                                       // actuation_latency (the measured delay where robots answer later)
  // s the guard adds to a MEASURED delay: the estimate folds a lagging velocity into one delay (realistic
  // robots: 25 ms late and 50 ms of lag, measured as 56 ms). PlannedMatch kRealistic, 11 v 11, four halves of
  // 120 s: 2000 camera frames with two robots closer than 2 radii + 1 cm with the estimate alone, 1200 with it.
  double measured_latency_allowance = 0.06;
  double guard_deceleration = 3.0;     // m/s^2 the guard counts on (below the robots' limit)
  // m/s^2 a robot ahead of us is counted on to brake at most: as hard as ours brake. One braking harder
  // can touch a robot of ours following it, at a closing speed far below the crash rule's 1.5 m/s; counting
  // on more keeps a follower too far back to mark a robot running away (at 2 m/s a follower needs 0.45 m
  // centre to centre with 3 m/s^2, 0.78 m with 4).
  double guard_other_braking = 3.0;
  // Sub-destinations per ring and tick; successive ticks turn the rings by half the spacing, so that two
  // ticks try twice as many directions (last tick's best is always tried again).
  PathSearchParams search = {.directions = 8};
};

class TrajectoryMotionPlanner final : public MotionPlanner {
 public:
  explicit TrajectoryMotionPlanner(const MotionLimits& limits, const TrajectoryMotionParams& params = {});

  RobotCommand plan(const wm::RobotState& robot, const MotionIntent& intent, const Zones& zones,
                    double dt) override;
  Vec2 keep_off_robots(const wm::RobotState& robot, const MotionIntent& intent, const Zones& zones,
                       const Vec2& velocity) const override;
  void sent(std::uint32_t id, const Vec2& velocity, double angular) override;
  void begin_tick() override;
  void set_actuation_latency(double latency, bool measured) override {
    params_.actuation_latency = latency;
    latency_measured_ = measured;
  }
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
    // The paths above as the other robots' searches sweep them (sampled once per tick).
    std::shared_ptr<const PathSamples> planned_samples;
    std::shared_ptr<const PathSamples> previous_samples;  // one tick along
    bool planned_this_tick = false;
    std::optional<double> tracking_error;  // m, this tick
  };

  /// One robot's obstacles; the other robots come first in `obstacles.circles` (`robots` of them).
  struct Obstacles {
    PathObstacles obstacles;
    std::size_t robots = 0;
  };
  /// `dt`: the tick period (how far along last tick's paths our robots not planned yet are now).
  Obstacles obstacles_for(const wm::RobotState& robot, const MotionIntent& intent, const Zones& zones,
                          double dt) const;
  double guard_latency() const {
    return std::max(params_.guard_latency,
                    params_.actuation_latency + (latency_measured_ ? params_.measured_latency_allowance : 0.0));
  }
  /// A limit on the command: velocity . direction <= max (direction unit, team frame; max >= 0 m/s).
  struct SpeedBound {
    Vec2 direction;
    double max = 0;
  };
  /// The contact guard's bounds on `robot`'s velocity, one per other robot where it is now and, unless
  /// `at_ball` (the robot dribbling or armed to kick) or `for_ball` (contesting the ball) with the other by
  /// the ball too, where it will be when the command acts.
  /// keep_off_robots with `bounds` as scratch (cleared first): plan() reuses its own.
  Vec2 keep_off_robots(const wm::RobotState& robot, const MotionIntent& intent, const Zones& zones,
                       const Vec2& velocity, std::vector<SpeedBound>& bounds) const;
  void contact_bounds(const wm::RobotState& robot, const Zones& zones, bool at_ball, bool for_ball,
                      std::vector<SpeedBound>& bounds) const;
  /// Bounds so that `robot` can still stop before each defense zone the intent keeps it out of (and the
  /// ball's circle, with guard_ball_circle) after guard_latency at guard_deceleration, and never goes deeper
  /// into one it is inside: the zones are a hard limit whatever the plan (a robot following a moving target,
  /// or a path that overshoots).
  void zone_bounds(const wm::RobotState& robot, const MotionIntent& intent, const Zones& zones,
                   std::vector<SpeedBound>& bounds) const;
  /// `velocity` brought within every bound: projected onto each violated one in turn, a few rounds, then
  /// scaled towards rest (which meets them all) if one is still violated.
  static Vec2 within(Vec2 velocity, std::span<const SpeedBound> bounds);
  /// No other robot (where it is now, with its clearance) touches the straight way from `from` to `to`.
  static bool direct_way_clear(const Vec2& from, const Vec2& to, const Obstacles& obstacles);
  /// `target` moved out of any robot standing on it (our robots: where their planned paths end).
  static Vec2 free_target(const wm::RobotState& robot, Vec2 target, const Obstacles& obstacles);

  MotionLimits limits_;
  TrajectoryMotionParams params_;
  std::array<Memory, wm::kMaxRobotsPerTeam> memory_{};
  std::uint64_t ticks_ = 0;
  double last_dt_ = 0;  // s, the tick period plan() was last called with
  bool latency_measured_ = false;  // actuation_latency is world_model's measured delay
};

}  // namespace ssl::planner
