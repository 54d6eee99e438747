// Referee scenarios in LOCKSTEP with the real cores, on the one lockstep match harness
// (services/planner/testing/planned_match.h): the Bullet simulator (6 v 6, `realistic` vision noise, division
// B and A fields), one WorldModel per team fed with the simulator's camera frames, its dribbler feedback and
// the commands its team sent, one Planner per team (blue and yellow, each with its own colour, planning with
// the delay its world model measures) and a scripted referee both planners see, under the harness's
// `realistic` conditions (robots answering about 75 ms after the camera with a lagging velocity and +-10 %
// limits; the scenarios that do not hold there yet run under `ideal` and say why: kNotYetRealistic). Every
// 10 ms tick: referee -> world models -> planners -> simulator commands (local velocities, flat kick / chip,
// dribbler) -> 10 ms of simulated time -> camera frames into the world models -> validation functions.
// Simulated time only: no threads, no sleeps, no DDS; the same seed gives the same match (PLANNER_SIM_SEED=n
// runs another seed).
//
// The VALIDATION FUNCTIONS (seeds/003, tests/support/validation.h) read the simulator's GROUND TRUTH (its
// snapshot after each tick), never the world model: a planner that believes it obeys the rules but does not
// is caught. Always: a predicate that must hold at every tick of a phase; Eventually: one that must become
// true (for a hold time) before a deadline. A failing check reports how many ticks failed and the first
// failure (time, robot, value). Each scenario
// prints one "[figures]" line (closest approach, top speed, placement error and time, ...).
//
// Distances are measured as the league's automatic referees do: robot CENTRE to ball centre against the rule
// distance PLUS the robot radius (0.09 m), i.e. the robot's whole body is outside the 0.5 m circle; the same
// for the opponent defense area (0.2 m), the placement stadium (0.5 m) and "1 m behind the ball". No further
// tolerance is subtracted: ground truth is exact, and the planner aims 0.1 m beyond each limit
// (keep_away_margin), which is its budget for world-model error and controller overshoot.
//
// Both teams run our planner, so each scenario tests the restart's "ours" rules on one team and its
// "theirs" rules on the other; with both colours as "us" every branch runs for both colours, both sides.
//   Halt*            normal play with both teams sprinting (up to 3 m/s), then HALT: every robot < 0.05 m/s
//                    after a brake allowance, and the ball is never sped up.
//   Stop*            STOP from crowded balls (in front of their defense area; next to it with our free kick
//                    announced; inside our defense area) and a rolling ball: after 2 s grace every robot
//                    <= 1.5 m/s, >= 0.5 m from the ball, >= 0.2 m from the opponent defense area.
//   TheirFreeKick*/TheirThrowIn*   STOP (next: their free kick) with ours crowding the ball, then DIRECT_FREE
//                    theirs: STOP rules, then ours >= 0.5 m from the ball and everybody >= 0.2 m from the
//                    opponent defense area until the ball is in play; their kicker plays it within 6 s and
//                    does not touch it twice.
//   Kickoff*         STOP -> PREPARE_KICKOFF ours -> NORMAL_START, starting with one robot of each team on
//   the
//                    wrong side: nobody touches the ball before NORMAL_START; ours (but the kicker) and all
//                    of theirs in their own half outside the centre circle until the ball is in play; our
//                    kicker kicks within 3 s and does not touch the ball twice.
//   OurBallPlacement*  BALL_PLACEMENT ours (next: our free kick), several placements: the ball at rest within
//                    0.15 m of the target with no robot within 0.05 m by 15 s (30 s, the rules' time, for the
//                    field-long one); after 2 s grace our other robots >= 0.5 m from the ball, theirs >= 0.5
//                    m from the ball and from the ball -> target segment, everybody <= 1.5 m/s.
//   Penalty*         STOP -> PREPARE_PENALTY ours -> NORMAL_START: our kicker within 0.4 m of the mark but
//   not
//                    touching, every other robot (both teams, but their keeper) >= 1 m behind the ball, their
//                    keeper touching its goal line between the posts; our kicker shoots within 3 s.
//   PlannerSimDeterminism  the same seed twice: bit-identical final ground truth; another seed differs.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "libs/common/team.h"
#include "services/planner/core/planner.h"
#include "services/planner/core/planner_test_util.h"
#include "services/planner/core/skills.h"
#include "services/planner/core/team_play.h"
#include "services/planner/testing/planned_match.h"
#include "services/simulator/core/simulator.h"
#include "services/world_model/core/sim_harness.h"
#include "libs/domain/team_frame.h"
#include "services/world_model/core/world_model.h"
#include "tests/support/validation.h"

namespace ssl::planner {
namespace {

using ssl::testing::Always;
using ssl::testing::Eventually;
using testing::Restart;
using testing::Side;
using wm::RefereeCommand;

constexpr std::uint32_t kRobots = 6;  // per team (division B)
constexpr std::uint64_t kDefaultSeed = 20260301;
/// The seed of every scenario: fixed, so a run is reproducible; PLANNER_SIM_SEED=n explores another one.
std::uint64_t seed() {
  const char* env = std::getenv("PLANNER_SIM_SEED");
  return env && *env ? std::strtoull(env, nullptr, 10) : kDefaultSeed;
}
constexpr double kTick = 0.01;  // s, planner period and lockstep step
constexpr double kR = 0.09;     // robot radius (simulator RobotSpec and rules' envelope)
constexpr double kBallRadius = 0.0215;
constexpr double kStopSpeed = 1.5;            // m/s, rules: STOP
constexpr double kBallKeepOut = 0.5 + kR;     // robot centre to ball centre (body outside 0.5 m)
constexpr double kDefenseKeepOut = 0.2 + kR;  // robot centre to opponent defense area
constexpr double kGrace = 2.0;                // s, rules: grace after STOP / a restart before distances count
constexpr double kInPlayMove = 0.05;          // m, rules: the ball is in play after moving this far
constexpr double kHaltSpeed = 0.05;           // m/s, "stopped"
constexpr double kWarmUp = 0.3;               // s of HALT at the start: the world models lock on

/// One parameter of the suites: our colour and side, and the division's field.
struct Case {
  Side side;
  bool division_a = false;
  sim::FieldGeometry field() const {
    return division_a ? sim::FieldGeometry::division_a() : sim::FieldGeometry::division_b();
  }
  std::string name() const { return side.name() + (division_a ? "_DivA" : "_DivB"); }
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name(); }

std::vector<Case> all_cases() {
  std::vector<Case> cases;
  for (bool a : {false, true}) {
    for (const Side& side : testing::all_sides()) cases.push_back({side, a});
  }
  return cases;
}

// ---- the lockstep match -----------------------------------------------------------------------------------

/// One robot of the ground truth, in OUR team frame.
struct TrueRobot {
  bool ours = false;
  std::uint32_t id = 0;
  Vec2 position = Vec2::Zero();
  Vec2 velocity = Vec2::Zero();
  bool dribbler_contact = false;
  bool touching = false;  // touched the ball during the last tick (see refresh_truth)
  double speed() const { return velocity.norm(); }
  std::string name() const { return std::string(ours ? "our " : "their ") + std::to_string(id); }
};

/// The simulator's ground truth after a tick, in OUR team frame.
struct Truth {
  Vec2 ball = Vec2::Zero();
  Vec2 ball_velocity = Vec2::Zero();
  std::vector<TrueRobot> robots;
};

struct RefereeEvent {
  double at = 0;  // s since the start
  RefereeCommand command = RefereeCommand::kHalt;
  std::optional<RefereeCommand> next;
  std::optional<Vec2> designated;  // OUR team frame
};

/// The scenarios that do not hold yet under the realistic conditions (PlannedMatch's default: robots
/// answering about 75 ms after the camera with a lagging velocity and +-10 % limits) run under ideal; each
/// says what fails. They are the open part of making the play hold up outside the lab.
constexpr testing::Conditions kNotYetRealistic = testing::Conditions::kIdeal;

/// A scenario's view of the lockstep match (services/planner/testing, the one harness): positions given and
/// returned in OUR team frame, and the ground truth after each tick with who touched the ball.
class LockstepMatch {
 public:
  /// Both teams play `ours` / `theirs` in normal play (the base strategy unless a scenario says otherwise);
  /// we take our penalties with `our_penalty`. Under the harness's default conditions (realistic) unless a
  /// scenario says otherwise (kNotYetRealistic).
  LockstepMatch(const Case& c, std::uint64_t seed, Strategy ours = Strategy::kBase, Strategy theirs = Strategy::kBase,
                PenaltyPlay our_penalty = PlannerConfig().penalty,
                testing::Conditions conditions = testing::PlannedMatchOptions{}.conditions)
      : case_(c),
        side_(c.side),
        field_(c.field()),
        us_frame_(c.side.frame()),
        match_({.conditions = conditions,
                .field = field_,
                .robots = kRobots,
                .seed = seed,
                .blue_on_positive_half = c.side.blue_on_positive_half,
                .actuation_latency = PlannerConfig().actuation_latency,
                .blue_strategy = c.side.us == TeamColor::kBlue ? ours : theirs,
                .yellow_strategy = c.side.us == TeamColor::kBlue ? theirs : ours,
                .blue_penalty = c.side.us == TeamColor::kBlue ? our_penalty : PlannerConfig().penalty,
                .yellow_penalty = c.side.us == TeamColor::kBlue ? PlannerConfig().penalty : our_penalty}) {
    refresh_truth();
  }
  LockstepMatch(const Case& c, std::uint64_t seed, testing::Conditions conditions)
      : LockstepMatch(c, seed, Strategy::kBase, Strategy::kBase, PlannerConfig().penalty, conditions) {}

  TeamColor us() const { return side_.us; }
  const sim::FieldGeometry& field() const { return field_; }
  const Case& test_case() const { return case_; }
  double half_length() const { return field_.field_length / 2; }
  TeamColor them() const { return opponent(side_.us); }
  double time() const { return match_.elapsed(); }
  const Truth& truth() const { return truth_; }
  const sim::Simulator& sim() const { return match_.sim(); }

  /// Teleports: robot `id` of us / them, ball. Our team frame; heading in our team frame.
  void place(bool ours, std::uint32_t id, const Vec2& p, double heading) {
    const Vec2 v = us_frame_.to_vision_point(p);
    sim::ControlRequest request;
    request.robots.push_back({.key = {ours ? us() : them(), id},
                              .x = v.x(),
                              .y = v.y(),
                              .orientation = us_frame_.to_vision_angle(heading),
                              .vx = 0,
                              .vy = 0,
                              .angular = 0,
                              .present = true});
    EXPECT_TRUE(sim_apply(request));
  }
  void place_ball(const Vec2& p) {
    const Vec2 v = us_frame_.to_vision_point(p);
    sim::ControlRequest request;
    request.ball = sim::BallTeleport{.x = v.x(), .y = v.y(), .z = kBallRadius};
    EXPECT_TRUE(sim_apply(request));
  }

  /// Sets the ball rolling where it is with velocity `v` (our frame).
  void roll_ball(const Vec2& v) {
    const Vec2 w = us_frame_.vector(v);
    const sim::WorldSnapshot snap = match_.sim().snapshot();
    sim::ControlRequest request;
    request.ball = sim::BallTeleport{.x = snap.ball.position.x(),
                                     .y = snap.ball.position.y(),
                                     .z = kBallRadius,
                                     .vx = w.x(),
                                     .vy = w.y(),
                                     .vz = 0,
                                     .roll = true};
    EXPECT_TRUE(sim_apply(request));
  }
  /// The referee's script; designated positions in OUR team frame.
  void script(const std::vector<RefereeEvent>& events) {
    std::vector<testing::ScriptedCommand> commands;
    for (const RefereeEvent& e : events) {
      commands.push_back({.at = e.at, .command = e.command, .next = e.next, .designated = std::nullopt});
      if (e.designated) commands.back().designated = us_frame_.to_vision_point(*e.designated);
    }
    match_.script(std::move(commands));
  }
  /// Applies a simulator control request; true when it was accepted whole.
  bool sim_apply(const sim::ControlRequest& request) {
    const bool ok = match_.apply(request);
    refresh_truth();
    return ok;
  }

  /// One lockstep tick: referee, both stacks, 10 ms of simulation, camera frames, ground truth.
  void tick() {
    match_.step();
    refresh_truth();
  }

  /// The last planner output of a team (debug: roles, play).
  const PlannerOutput& output(bool ours) const { return match_.output(ours ? us() : them()); }
  /// A team's planner (to run single skills: Planner::override_skill).
  Planner& planner(bool ours) { return match_.planner(ours ? us() : them()); }

 private:
  void refresh_truth() {
    const sim::WorldSnapshot snap = match_.sim().snapshot();
    const Vec2 previous_velocity = truth_.ball_velocity;
    truth_.ball = us_frame_.point(snap.ball.position.head<2>());
    truth_.ball_velocity = us_frame_.vector(snap.ball.velocity.head<2>());
    truth_.robots.clear();
    for (const sim::RobotState& r : snap.robots) {
      truth_.robots.push_back({.ours = r.key.team == us(),
                               .id = r.key.id,
                               .position = us_frame_.point(r.position),
                               .velocity = us_frame_.vector(r.velocity),
                               .dribbler_contact = r.ball_contact});
    }
    // Touches. Sampling every 10 ms misses a fast ball bouncing off a robot (4 cm per tick), so besides
    // contact now (dribbler contact, or the ball centre within radius + ball radius + 3 mm of the robot
    // centre: the round body, conservative at the flat front) a sudden change of the ball's velocity
    // (> 0.3 m/s in a tick: 10x the carpet's sliding friction) is a touch by the nearest robot when the
    // ball could have reached it during the tick.
    const bool deflected = (truth_.ball_velocity - previous_velocity).norm() > 0.3;
    const double reach =
        kR + kBallRadius + (previous_velocity.norm() + truth_.ball_velocity.norm()) * kTick + 0.01;
    TrueRobot* nearest = nullptr;
    for (TrueRobot& r : truth_.robots) {
      const double d = (r.position - truth_.ball).norm();
      r.touching = r.dribbler_contact || d <= kR + kBallRadius + 0.003;
      if (!nearest || d < (nearest->position - truth_.ball).norm()) nearest = &r;
    }
    if (deflected && nearest && (nearest->position - truth_.ball).norm() <= reach) nearest->touching = true;
  }

  Case case_;
  Side side_;
  sim::FieldGeometry field_;
  wm::TeamFrame us_frame_;
  testing::PlannedMatch match_;
  Truth truth_;
};

// ---- validation functions ---------------------------------------------------------------------------------

/// Robot-centre distance to a team's OPPONENT defense area (our frame: theirs at +x, ours at -x).
double distance_to_opponent_defense_area(const sim::FieldGeometry& f, const TrueRobot& r) {
  const wm::Field field(f);
  return testing::distance_to_their_defense_area(field, r.ours ? r.position : Vec2(-r.position));
}

/// Rules' STOP checks for every robot of both teams (after the grace time), plus figures.
struct StopRules {
  Always speed{"STOP: every robot <= 1.5 m/s"};
  Always ball{"STOP: every robot centre >= 0.5 m + radius from the ball"};
  Always defense{"STOP: every robot >= 0.2 m from the opponent defense area"};
  double min_ball = 1e9;
  double max_speed = 0;
  double min_defense = 1e9;

  void check(const sim::FieldGeometry& field, const Truth& truth, double t) {
    for (const TrueRobot& r : truth.robots) {
      const double d = (r.position - truth.ball).norm();
      const double dd = distance_to_opponent_defense_area(field, r);
      min_ball = std::min(min_ball, d);
      max_speed = std::max(max_speed, r.speed());
      min_defense = std::min(min_defense, dd);
      speed.require(r.speed() <= kStopSpeed, t,
                    [&] { return r.name() + " at " + Always::fmt(r.speed()) + " m/s"; });
      ball.require(d >= kBallKeepOut, t,
                   [&] { return r.name() + " " + Always::fmt(d) + " m from the ball"; });
      defense.require(dd >= kDefenseKeepOut, t,
                      [&] { return r.name() + " " + Always::fmt(dd) + " m from the opponent defense area"; });
    }
  }
  void report() const {
    speed.report();
    ball.report();
    defense.report();
  }
};

void print_figures(const std::string& scenario, const Case& side, const std::string& figures) {
  std::printf("[figures] %-14s %-22s %s\n", scenario.c_str(), side.name().c_str(), figures.c_str());
  std::fflush(stdout);
}

bool touches(const TrueRobot& r) { return r.touching; }

/// The robot of the kicking team nearest the ball: the kicker while the restart is being taken.
std::optional<TrueRobot> nearest(const Truth& truth, bool ours) {
  std::optional<TrueRobot> best;
  for (const TrueRobot& r : truth.robots) {
    if (r.ours != ours) continue;
    if (!best || (r.position - truth.ball).norm() < (best->position - truth.ball).norm()) best = r;
  }
  return best;
}

/// Rules (double touch): after a kickoff / free kick / penalty the kicker may not touch the ball again
/// until another robot touched it. Runs the match on for `seconds` after the kick by `kicker`; returns a
/// figure: the kicker's closest approach to the ball afterwards, and whether another robot touched it.
std::string check_no_double_touch(LockstepMatch& m, const TrueRobot& kicker, double seconds) {
  Always double_touch{"double touch: the kicker does not touch the ball again before another robot"};
  bool left = false;  // the ball has left the kicker (the kick itself is one touch)
  const double end = m.time() + seconds;
  double min_gap = 1e9;
  while (m.time() < end) {
    m.tick();
    const Truth& truth = m.truth();
    bool other = false;
    for (const TrueRobot& r : truth.robots) {
      const bool is_kicker = r.ours == kicker.ours && r.id == kicker.id;
      if (!is_kicker) {
        other |= touches(r);
        continue;
      }
      const double gap = (r.position - truth.ball).norm() - kR - kBallRadius;
      if (!left) {
        left = gap > 0.02;
        continue;
      }
      min_gap = std::min(min_gap, gap);
      double_touch.require(!touches(r), m.time(), [&] { return r.name() + " touched it again"; });
    }
    if (other) break;  // somebody else played the ball: the kicker may touch it again
  }
  double_touch.report();
  return "kicker's closest gap after its kick " + Always::fmt(min_gap) + " m" +
         (m.time() < end ? " (then another robot played the ball)" : "");
}

/// The default layout (our frame): both teams spread over their halves, keepers in goal.
void default_layout(LockstepMatch& m) {
  const double hl = m.half_length();
  const Vec2 ours[kRobots] = {{-hl + 0.3, 0}, {-2.0, 1.0},  {-2.0, -1.0},
                              {-1.0, 2.0},    {-1.0, -2.0}, {-0.6, 0.3}};
  const Vec2 theirs[kRobots] = {{hl - 0.3, 0}, {2.0, 1.2}, {2.0, -0.8}, {1.0, 2.2}, {1.0, -1.8}, {0.7, -0.4}};
  for (std::uint32_t id = 0; id < kRobots; ++id) {
    m.place(true, id, ours[id], 0.0);
    m.place(false, id, theirs[id], M_PI);
  }
}

class PlannerSimReferee : public ::testing::TestWithParam<Case> {
 protected:
  const Case& param() const { return GetParam(); }
  const Side& side() const { return GetParam().side; }
  RefereeCommand ours(Restart r) const { return testing::command_for(r, side().us); }
};

// ---- HALT -------------------------------------------------------------------------------------------------

TEST_P(PlannerSimReferee, HaltStopsEveryRobotWithinTheBrakeAllowance) {
  LockstepMatch m(param(), seed());
  // Both teams start in the wrong half (mirrored layout), so that normal play sends them sprinting back
  // at up to 3 m/s when HALT comes.
  const double hl = m.half_length();
  const Vec2 ours[kRobots] = {{hl - 1.0, 0}, {2.0, 1.0}, {2.0, -1.0}, {1.0, 2.0}, {1.0, -2.0}, {0.6, 0.3}};
  for (std::uint32_t id = 0; id < kRobots; ++id) {
    m.place(true, id, ours[id], M_PI);
    m.place(false, id, -ours[id] + Vec2(0, 0.3), 0.0);
  }
  m.place_ball({0.8, -0.6});
  const double halt_at = kWarmUp + 1.6;
  m.script({{kWarmUp, RefereeCommand::kForceStart}, {halt_at, RefereeCommand::kHalt}});
  // The brake allowance is physical, not a tolerance: the simulated robots brake at acc_brake_absolute_max
  // (4 m/s^2), so a robot at v needs v / 4 s; plus 2 ticks (one planner tick, one command in flight) and
  // 0.1 s for the velocity controller to settle below 0.05 m/s. A fixed 0.3 s would hold only below
  // ~0.7 m/s, so the allowance is computed from the fastest robot at the HALT instant (0.87 s from 3 m/s).
  const double brake = m.sim().options().blue_spec.limits.acc_brake_absolute_max;
  Always stopped{"HALT: every robot < 0.05 m/s after the brake allowance"};
  Always no_kick{"HALT: nobody kicks or pushes the ball (its speed never rises)"};
  std::optional<double> ball_speed_at_halt;
  double speed_at_halt = 0;
  double allowance = 0.3;
  double last_moving = 0;
  while (m.time() < halt_at + 1.5) {
    m.tick();
    const Truth& truth = m.truth();
    const double t = m.time();
    if (t <= halt_at + 1e-9) {
      speed_at_halt = 0;
      for (const TrueRobot& r : truth.robots) speed_at_halt = std::max(speed_at_halt, r.speed());
      allowance = std::max(0.3, speed_at_halt / brake + 2 * kTick + 0.1);
      continue;
    }
    for (const TrueRobot& r : truth.robots) {
      if (r.speed() >= kHaltSpeed) last_moving = std::max(last_moving, t - halt_at);
      if (t - halt_at < allowance) continue;
      stopped.require(r.speed() < kHaltSpeed, t,
                      [&] { return r.name() + " at " + Always::fmt(r.speed()) + " m/s"; });
    }
    // A ball kicked before HALT may still roll; after HALT it must never speed up (nobody kicks or
    // pushes it). 0.05 m/s: simulator noise of a rolling ball bouncing off a stopped robot or the wall.
    // A shot that went in before HALT bounces about in the goal, where no robot can reach it: not checked.
    if (!ball_speed_at_halt) ball_speed_at_halt = truth.ball_velocity.norm();
    if (std::abs(truth.ball.x()) > hl) continue;
    no_kick.require(truth.ball_velocity.norm() <= *ball_speed_at_halt + 0.05, t, [&] {
      return "ball at " + Always::fmt(truth.ball_velocity.norm()) + " m/s, was " +
             Always::fmt(*ball_speed_at_halt);
    });
    ball_speed_at_halt = std::min(*ball_speed_at_halt, truth.ball_velocity.norm());
  }
  stopped.report();
  no_kick.report();
  // Not vacuous: the robots were moving when HALT came.
  EXPECT_GT(speed_at_halt, 1.0);
  print_figures("Halt", param(),
                "max speed at HALT " + Always::fmt(speed_at_halt) + " m/s, allowance " +
                    Always::fmt(allowance) + " s, all < 0.05 m/s after " + Always::fmt(last_moving) + " s");
}

// ---- STOP -------------------------------------------------------------------------------------------------

/// STOP from the current layout: 2 s grace, then 4 s of the STOP rules for every robot of both teams.
void run_stop(LockstepMatch& m, const char* scenario, std::optional<RefereeCommand> next) {
  const double stop_at = kWarmUp;
  m.script({{stop_at, RefereeCommand::kStop, next}});
  StopRules rules;
  double max_speed_grace = 0;
  while (m.time() < stop_at + kGrace + 4.0) {
    m.tick();
    const double t = m.time();
    if (t < stop_at) continue;
    if (t - stop_at < kGrace) {
      for (const TrueRobot& r : m.truth().robots) max_speed_grace = std::max(max_speed_grace, r.speed());
      continue;
    }
    rules.check(m.field(), m.truth(), t);
  }
  rules.report();
  print_figures(scenario, m.test_case(),
                "min ball dist " + Always::fmt(rules.min_ball) + " m, max speed " +
                    Always::fmt(rules.max_speed) + " m/s (grace " + Always::fmt(max_speed_grace) +
                    "), min opp. defense dist " + Always::fmt(rules.min_defense) + " m");
}

TEST_P(PlannerSimReferee, StopCrowdedBallInFrontOfTheirDefenseArea) {
  // kNotYetRealistic: in 1 of the 8 sides and divisions our robot leaving their area meets one of theirs
  // moving into its way, slows, and is 0.18 m from their area (not 0.2) when the grace ends.
  LockstepMatch m(param(), seed(), kNotYetRealistic);
  default_layout(m);
  // A crowded ball 0.6 m in front of THEIR defense area: three of ours and two of theirs within 0.3 m,
  // one of ours inside their defense area (it must leave it by 0.2 m).
  const double hl = m.half_length();
  const Vec2 ball(hl - m.field().penalty_area_depth - 0.6, -0.5);
  m.place_ball(ball);
  m.place(true, 1, ball + Vec2(-0.2, 0.05), 0.0);
  m.place(true, 2, ball + Vec2(0.02, 0.22), -M_PI / 2);
  m.place(true, 3, {hl - 0.5, 0.4}, 0.0);
  m.place(true, 5, ball + Vec2(0.05, -0.22), M_PI / 2);
  m.place(false, 1, ball + Vec2(0.22, 0.0), M_PI);
  m.place(false, 2, ball + Vec2(0.2, -0.25), M_PI);
  run_stop(m, "Stop", std::nullopt);
}

TEST_P(PlannerSimReferee, StopBeforeOurFreeKickNextToTheirDefenseArea) {
  LockstepMatch m(param(), seed());
  default_layout(m);
  // The ball 0.25 m in front of their defense area's corner, our free kick announced: our kicker stages
  // behind the ball and the attack formation moves up, all outside the 0.2 m band around their area.
  const double hl = m.half_length();
  const sim::FieldGeometry& field = m.field();
  const Vec2 ball(hl - field.penalty_area_depth - 0.25, field.penalty_area_width / 2 - 0.2);
  m.place_ball(ball);
  m.place(true, 1, ball + Vec2(-0.3, 0.0), 0.0);
  m.place(true, 2, {hl - 0.4, -0.3}, 0.0);
  m.place(true, 5, ball + Vec2(0.1, 0.25), 0.0);
  m.place(false, 1, ball + Vec2(0.25, -0.1), M_PI);
  run_stop(m, "StopOurFreeKick", testing::command_for(Restart::kFreeKick, m.us()));
}

TEST_P(PlannerSimReferee, StopWithTheBallRollingThroughOurTeam) {
  LockstepMatch m(param(), seed());
  default_layout(m);
  // STOP is usually called while the ball still rolls (after a goal, a foul, out): 2.2 m/s towards our
  // goal, passing about 0.3 m from one of ours, still rolling when the 2 s grace ends.
  m.place_ball({-0.5, 0.0});
  m.roll_ball({-2.0, 0.9});
  run_stop(m, "StopRolling", std::nullopt);
}

TEST_P(PlannerSimReferee, StopBallInsideOurDefenseArea) {
  LockstepMatch m(param(), seed());
  default_layout(m);
  // The ball deep in OUR defense area next to our keeper: our keeper must give it 0.5 m too, their robots
  // must stay 0.2 m outside our defense area.
  const double hl = m.half_length();
  const Vec2 ball(-hl + 0.4, 0.3);
  m.place_ball(ball);
  m.place(true, 0, {-hl + 0.2, 0.1}, 0.0);
  m.place(false, 1, ball + Vec2(1.0, 0.2), M_PI);
  m.place(false, 5, {-hl + m.field().penalty_area_depth + 0.1, -0.3}, M_PI);
  run_stop(m, "StopOurArea", std::nullopt);
}

// ---- their free kick --------------------------------------------------------------------------------------

/// STOP (their free kick announced) with ours crowding the ball at `ball`, then DIRECT_FREE theirs.
void run_their_free_kick(LockstepMatch& m, const char* scenario, const Vec2& ball) {
  const sim::FieldGeometry& field = m.field();
  m.place_ball(ball);
  m.place(true, 1, ball + Vec2(-0.15, -0.1), 0.0);
  m.place(true, 2, ball + Vec2(0.1, -0.25), 0.0);
  m.place(false, 5, ball + Vec2(0.4, 0.1), M_PI);
  const double stop_at = kWarmUp;
  const double free_at = stop_at + 2.5;
  const RefereeCommand free_kick = testing::command_for(Restart::kFreeKick, m.them());
  m.script({{stop_at, RefereeCommand::kStop, free_kick}, {free_at, free_kick}});
  StopRules stop;
  Always keep{"their free kick: ours >= 0.5 m + radius from the ball until it is in play"};
  Always defense{"free kick: every robot >= 0.2 m from the opponent defense area until the ball is in play"};
  Eventually kicked{"their free kick: their kicker puts the ball in play", 6.0};
  double min_ours = 1e9;
  std::optional<TrueRobot> kicker;
  while (m.time() < free_at + 6.0 && !kicked.done()) {
    m.tick();
    const Truth& truth = m.truth();
    const double t = m.time();
    if (t < stop_at + kGrace) continue;
    if (t < free_at) {
      stop.check(m.field(), truth, t);
      continue;
    }
    const bool in_play = (truth.ball - ball).norm() > kInPlayMove;
    if (kicked.update(in_play, t - free_at)) break;
    kicker = nearest(truth, false);
    for (const TrueRobot& r : truth.robots) {
      const double dd = distance_to_opponent_defense_area(field, r);
      defense.require(dd >= kDefenseKeepOut, t, [&] { return r.name() + " " + Always::fmt(dd) + " m"; });
      if (!r.ours) continue;
      const double d = (r.position - truth.ball).norm();
      min_ours = std::min(min_ours, d);
      keep.require(d >= kBallKeepOut, t,
                   [&] { return r.name() + " " + Always::fmt(d) + " m from the ball"; });
    }
  }
  std::string after;
  if (kicked.done() && kicker) after = check_no_double_touch(m, *kicker, 2.0);
  stop.report();
  keep.report();
  defense.report();
  kicked.report();
  print_figures(scenario, m.test_case(),
                "min ours-ball dist " + Always::fmt(min_ours) + " m (STOP min " + Always::fmt(stop.min_ball) +
                    "), their kick after " + Always::fmt(kicked.at()) + " s, " + after);
}

TEST_P(PlannerSimReferee, TheirFreeKickInOurHalf) {
  LockstepMatch m(param(), seed());
  default_layout(m);
  run_their_free_kick(m, "TheirFreeKick", {-1.5, 1.0});
}

TEST_P(PlannerSimReferee, TheirFreeKickOneMetreFromOurDefenseArea) {
  LockstepMatch m(param(), seed());
  default_layout(m);
  // Rules: a free kick is at least 1 m from either defense area.
  const sim::FieldGeometry& field = m.field();
  run_their_free_kick(
      m, "TheirFKNearArea",
      {-m.half_length() + field.penalty_area_depth + 1.0, field.penalty_area_width / 2 - 0.4});
}

TEST_P(PlannerSimReferee, TheirThrowInAtOurTouchLine) {
  LockstepMatch m(param(), seed());
  default_layout(m);
  // Rules: a throw-in is 0.2 m inside the touch line.
  run_their_free_kick(m, "TheirThrowIn", {-1.0, m.field().field_width / 2 - 0.2});
}

// ---- kickoff (ours; theirs for the opponent) --------------------------------------------------------------

TEST_P(PlannerSimReferee, KickoffFormationsHoldThenOurKickerKicks) {
  LockstepMatch m(param(), seed());
  default_layout(m);
  const sim::FieldGeometry& field = m.field();
  m.place_ball({0, 0});
  // One of ours in their half inside the centre circle, one of theirs in ours: both must get out.
  m.place(true, 5, {0.3, 0.15}, M_PI);
  m.place(false, 5, {-0.35, -0.3}, 0.0);
  const double stop_at = kWarmUp;
  const double prepare_at = stop_at + 2.0;
  const double start_at = prepare_at + 2.5;
  const RefereeCommand kickoff = ours(Restart::kKickoff);
  m.script({{stop_at, RefereeCommand::kStop, kickoff},
            {prepare_at, kickoff},
            {start_at, RefereeCommand::kNormalStart}});
  const double circle = field.center_circle_radius;
  Always untouched{"kickoff: no robot touches the ball before NORMAL_START"};
  Always our_half{"our kickoff: ours but the kicker in our half, outside the centre circle"};
  Always their_half{
      "their kickoff: theirs in their half, outside the centre circle, until the ball is in play"};
  Eventually kicked{"our kickoff: the ball moves > 0.05 m after NORMAL_START", 3.0};
  double min_gap = 1e9;
  double min_theirs = 1e9;
  std::optional<TrueRobot> kicker_before;
  while (m.time() < start_at + 3.0 && !kicked.done()) {
    m.tick();
    const Truth& truth = m.truth();
    const double t = m.time();
    const bool in_play = truth.ball.norm() > kInPlayMove;
    if (t < start_at) {
      for (const TrueRobot& r : truth.robots) {
        const double gap = (r.position - truth.ball).norm() - kR - kBallRadius;
        min_gap = std::min(min_gap, gap);
        untouched.require(gap > 0 && !in_play, t,
                          [&] { return r.name() + " gap " + Always::fmt(gap) + " m"; });
      }
    } else if (kicked.update(in_play, t - start_at)) {
      break;
    }
    kicker_before = nearest(truth, true);
    // Formations: settled 2 s after PREPARE_KICKOFF (they were prepared during STOP already).
    if (t < prepare_at + kGrace) continue;
    // The kicker is our robot nearest the ball; all the others must be legal.
    std::optional<std::uint32_t> kicker;
    double best = 1e9;
    for (const TrueRobot& r : truth.robots) {
      if (r.ours && (r.position - truth.ball).norm() < best) {
        best = (r.position - truth.ball).norm();
        kicker = r.id;
      }
    }
    for (const TrueRobot& r : truth.robots) {
      // In own half: the whole body (centre x <= -radius in the owner's frame); outside the circle: the body.
      const Vec2 own = r.ours ? r.position : Vec2(-r.position);
      const bool legal = own.x() <= -kR && own.norm() >= circle + kR;
      if (r.ours) {
        if (r.id == *kicker) continue;
        our_half.require(
            legal, t, [&] { return r.name() + " at " + Always::fmt(own.x()) + ", " + Always::fmt(own.y()); });
      } else {
        min_theirs = std::min(min_theirs, own.norm());
        their_half.require(
            legal, t, [&] { return r.name() + " at " + Always::fmt(own.x()) + ", " + Always::fmt(own.y()); });
      }
    }
  }
  std::string after;
  if (kicked.done() && kicker_before) after = check_no_double_touch(m, *kicker_before, 2.0);
  untouched.report();
  our_half.report();
  their_half.report();
  kicked.report();
  print_figures("Kickoff", param(),
                "min robot-ball gap before start " + Always::fmt(min_gap) + " m, theirs min dist to centre " +
                    Always::fmt(min_theirs) + " m, kicked after " + Always::fmt(kicked.at()) + " s, " +
                    after);
}

// ---- ball placement (ours; theirs for the opponent) -------------------------------------------------------

/// BALL_PLACEMENT ours from the current layout (ball already placed) to `target`, next: our free kick.
void run_our_placement(LockstepMatch& m, const char* scenario, const Vec2& target, double deadline) {
  const double place_at = kWarmUp;
  m.script({{place_at, testing::command_for(Restart::kPlacement, m.us()),
             testing::command_for(Restart::kFreeKick, m.us()), target}});
  constexpr double kPlacementTolerance = 0.15;  // rules: ball within 0.15 m of the designated position
  constexpr double kMinRobotGap = 0.05;         // rules: no robot within 0.05 m (next: our free kick)
  constexpr double kRest = 0.05;                // m/s: the ball is stationary
  Eventually placed{"our placement: ball at rest within 0.15 m, nobody within 0.05 m", deadline, 0.5};
  Always our_others{"our placement: our other robots >= 0.5 m + radius from the ball"};
  Always their_ball{"their placement: theirs >= 0.5 m + radius from the ball"};
  Always their_corridor{"their placement: theirs >= 0.5 m + radius from the ball -> target segment"};
  Always speed{"placement: every robot <= 1.5 m/s"};
  std::optional<std::uint32_t> placer;
  double min_theirs = 1e9;
  double min_others = 1e9;
  double error = 1e9;
  double gap_at_success = 0;
  while (m.time() < place_at + deadline + 0.6 && !placed.done()) {
    m.tick();
    const Truth& truth = m.truth();
    const double t = m.time();
    if (t < place_at) continue;
    for (const RoleInfo& role : m.output(true).roles) {
      if (role.role == "placer") placer = role.robot_id;
    }
    error = (truth.ball - target).norm();
    double gap = 1e9;
    for (const TrueRobot& r : truth.robots)
      gap = std::min(gap, (r.position - truth.ball).norm() - kR - kBallRadius);
    if (placed.update(
            error <= kPlacementTolerance && truth.ball_velocity.norm() < kRest && gap >= kMinRobotGap,
            t - place_at)) {
      gap_at_success = gap;
    }
    if (t - place_at < kGrace) continue;
    for (const TrueRobot& r : truth.robots) {
      speed.require(r.speed() <= kStopSpeed, t,
                    [&] { return r.name() + " at " + Always::fmt(r.speed()) + " m/s"; });
      const double d = (r.position - truth.ball).norm();
      if (r.ours) {
        if (placer && r.id == *placer) continue;
        min_others = std::min(min_others, d);
        our_others.require(d >= kBallKeepOut, t, [&] { return r.name() + " " + Always::fmt(d) + " m"; });
      } else {
        const double c = testing::distance_to_segment(r.position, truth.ball, target);
        min_theirs = std::min(min_theirs, c);
        their_ball.require(d >= kBallKeepOut, t, [&] { return r.name() + " " + Always::fmt(d) + " m"; });
        their_corridor.require(c >= kBallKeepOut, t, [&] { return r.name() + " " + Always::fmt(c) + " m"; });
      }
    }
  }
  placed.report("(ball error " + Always::fmt(error) + " m)");
  our_others.report();
  their_ball.report();
  their_corridor.report();
  speed.report();
  print_figures(scenario, m.test_case(),
                "placed after " + Always::fmt(placed.at()) + " s, error " + Always::fmt(error) + " m, gap " +
                    Always::fmt(gap_at_success) + " m, our others min " + Always::fmt(min_others) +
                    " m, theirs min to corridor " + Always::fmt(min_theirs) + " m");
}

TEST_P(PlannerSimReferee, OurBallPlacementAcrossTheCentre) {
  LockstepMatch m(param(), seed());
  default_layout(m);
  const Vec2 start(1.2, 1.3);
  m.place_ball(start);
  m.place(false, 5, {0.3, 0.45}, M_PI);  // one of theirs right on the ball -> target path
  m.place(false, 3, start + Vec2(0.3, 0.2), M_PI);
  run_our_placement(m, "BallPlacement", {-0.6, -0.4}, 15.0);
}

TEST_P(PlannerSimReferee, OurBallPlacementDiagonallyOverTheField) {
  LockstepMatch m(param(), seed());
  default_layout(m);
  // From near their corner to near ours: 6.7 m (division B) / 11.3 m (A). The placer carries at most
  // 1 m/s, so this one gets the rules' full placement time (30 s, GC default) rather than 15 s.
  const double hl = m.half_length();
  const double hw = m.field().field_width / 2;
  m.place_ball({hl - 1.5, hw - 0.5});
  run_our_placement(m, "PlacementLong", {-hl + 2.5, -hw + 0.5}, 30.0);
}

TEST_P(PlannerSimReferee, OurBallPlacementOutOfTheCornerInsideTheField) {
  LockstepMatch m(param(), seed());
  default_layout(m);
  // The ball in their corner, 0.15 m from both lines, to a point 0.85 m along the touch line: the placer
  // has to get between the ball and the corner (it may leave the field by 0.05 m).
  const double hl = m.half_length();
  const double hw = m.field().field_width / 2;
  m.place_ball({hl - 0.15, -hw + 0.15});
  run_our_placement(m, "PlacementCorner", {hl - 1.0, -hw + 0.2}, 15.0);
}

// ---- penalty (ours; theirs for the opponent) --------------------------------------------------------------

TEST_P(PlannerSimReferee, PenaltyPositionsHoldThenOurKickerShoots) {
  LockstepMatch m(param(), seed());
  default_layout(m);
  const double hl = m.half_length();
  const sim::FieldGeometry& field = m.field();
  // Rules: the penalty mark is goal_center_to_penalty_mark from the DEFENDING goal (6 m in division B).
  const Vec2 mark(hl - field.goal_center_to_penalty_mark, 0);
  m.place_ball(mark);
  const double stop_at = kWarmUp;
  const double prepare_at = stop_at + 2.5;
  const double start_at = prepare_at + 2.5;
  const RefereeCommand penalty = ours(Restart::kPenalty);
  m.script({{stop_at, RefereeCommand::kStop, penalty},
            {prepare_at, penalty},
            {start_at, RefereeCommand::kNormalStart}});
  Always kicker_near{"our penalty: our kicker within 0.4 m of the mark, not touching the ball"};
  Always behind{"penalty: every other robot >= 1 m behind the ball"};
  Always keeper{"their penalty: their keeper touches its goal line between the posts"};
  Eventually shot{"our penalty: the ball moves > 0.05 m towards their goal after NORMAL_START", 3.0};
  double max_behind = -1e9;
  double keeper_offset = 0;
  double kicker_distance = 0;
  while (m.time() < start_at + 3.0 && !shot.done()) {
    m.tick();
    const Truth& truth = m.truth();
    const double t = m.time();
    const bool in_play = (truth.ball - mark).norm() > kInPlayMove;
    if (t >= start_at) {
      if (shot.update(in_play && truth.ball.x() > mark.x(), t - start_at)) break;
    }
    if (t < prepare_at + kGrace || in_play) continue;
    std::optional<std::uint32_t> kicker;
    double best = 1e9;
    for (const TrueRobot& r : truth.robots) {
      if (r.ours && (r.position - truth.ball).norm() < best) {
        best = (r.position - truth.ball).norm();
        kicker = r.id;
      }
    }
    kicker_distance = best;
    kicker_near.require(best <= 0.4 && (t >= start_at || best >= kR + kBallRadius), t,
                        [&] { return "nearest of ours " + Always::fmt(best) + " m from the ball"; });
    for (const TrueRobot& r : truth.robots) {
      if (r.ours && r.id == *kicker) continue;
      if (!r.ours && r.id == 0) {
        // Touching the goal line (thickness 0.01 m) with its body, between the posts.
        const double off = std::abs(r.position.x() - hl);
        keeper_offset = std::max(keeper_offset, off);
        keeper.require(
            off <= kR + field.line_thickness / 2 && std::abs(r.position.y()) <= field.goal_width / 2, t,
            [&] { return "at " + Always::fmt(r.position.x()) + ", " + Always::fmt(r.position.y()); });
        continue;
      }
      // >= 1 m behind the ball: the robot's body (our frame: towards -x, our kicker attacks +x).
      const double margin = truth.ball.x() - r.position.x() - kR;
      max_behind = std::max(max_behind, -margin);
      behind.require(margin >= 1.0, t,
                     [&] { return r.name() + " only " + Always::fmt(margin) + " m behind"; });
    }
  }
  kicker_near.report();
  behind.report();
  keeper.report();
  shot.report();
  print_figures("Penalty", param(),
                "kicker " + Always::fmt(kicker_distance) + " m from the mark, closest other " +
                    Always::fmt(-max_behind) + " m behind, keeper off the line " +
                    Always::fmt(keeper_offset) + " m, shot after " + Always::fmt(shot.at()) + " s");
}


/// One penalty of ours taken with `play` (the rest as PenaltyPositionsHoldThenOurKickerShoots sets it up),
/// run until it is decided or 10 s (the rules' time) after NORMAL_START. Checks the rules on our attacker
/// while it plays the ball on: the ball never faster than the rules allow, no other robot of ours touches
/// it before the shot, our attacker never touches it partly inside their defense area, no robot of ours
/// dribbles it further than 1 m.
struct PenaltyOutcome {
  bool goal = false;
  double decided_after = 0;  // s after NORMAL_START
};
PenaltyOutcome take_penalty(const Case& c, std::uint64_t seed, PenaltyPlay play, Always& speed, Always& others,
                            Always& area, Always& dribble) {
  LockstepMatch m(c, seed, Strategy::kBase, Strategy::kBase, play);
  default_layout(m);
  const double hl = m.half_length();
  const sim::FieldGeometry& field = m.field();
  m.place_ball({hl - field.goal_center_to_penalty_mark, 0});
  const double start_at = kWarmUp + 5.0;
  const RefereeCommand penalty = testing::command_for(Restart::kPenalty, c.side.us);
  m.script({{kWarmUp, RefereeCommand::kStop, penalty},
            {kWarmUp + 2.5, penalty},
            {start_at, RefereeCommand::kNormalStart}});
  while (m.time() < start_at) m.tick();
  const std::uint32_t kicker = nearest(m.truth(), true)->id;
  constexpr double kPenaltyShotSeen = 4.0;  // m/s
  // Where the ball was when a robot of ours last took it on its dribbler (dribbled: while it keeps contact).
  Vec2 dribble_start = Vec2::Zero();
  bool dribbling = false;
  bool shot = false;
  while (m.time() < start_at + rules::kPenaltyTimeout) {
    m.tick();
    const Truth& truth = m.truth();
    const double t = m.time();
    const double after = t - start_at;
    if (truth.ball.x() > hl) return {.goal = std::abs(truth.ball.y()) < field.goal_width / 2, .decided_after = after};
    if (std::abs(truth.ball.y()) > field.field_width / 2 || truth.ball.x() < -hl) return {.decided_after = after};
    speed.require(truth.ball_velocity.norm() <= rules::kMaxBallSpeed, t,
                  [&] { return "the ball at " + Always::fmt(truth.ball_velocity.norm()) + " m/s"; });
    // The shot (faster than a played-on ball ever rolls): what follows is the keeper's save and play on.
    shot = shot || truth.ball_velocity.norm() > kPenaltyShotSeen;
    for (const TrueRobot& r : truth.robots) {
      if (!r.ours || !r.touching || shot) continue;
      others.require(r.id == kicker, t, [&] { return r.name() + " touched the ball"; });
      const double clear = distance_to_opponent_defense_area(field, r);
      area.require(clear >= kR, t, [&] { return "touched " + Always::fmt(clear) + " m from their defense area"; });
    }
    const std::optional<TrueRobot> holder = nearest(truth, true);
    const bool contact = holder && holder->dribbler_contact;
    if (contact && !dribbling) dribble_start = truth.ball;
    dribbling = contact;
    const double dribbled = dribbling ? (truth.ball - dribble_start).norm() : 0.0;
    dribble.require(dribbled <= rules::kMaxDribblingDistance, t,
                    [&] { return "dribbled " + Always::fmt(dribbled) + " m"; });
  }
  return {.decided_after = rules::kPenaltyTimeout};
}

/// The base strategy's penalty (PenaltyPlay::kAdvance: played on, shot from close in) against our keeper
/// scores in at least 3 of 4 penalties, and more often than the shot from the mark (PenaltyPlay::kShot) in the
/// same 4 (seeds 1-4, both keepers our own), within the rules checked by take_penalty.
TEST_P(PlannerSimReferee, OurPenaltyPlayedOnAndShotFromCloseInScoresMoreThanTheShotFromTheMark) {
  constexpr int kPenalties = 4;
  Always speed{"our penalty: the ball never faster than the rules' 6.5 m/s"};
  Always others{"our penalty: no robot of ours but the kicker touches the ball before the shot"};
  Always area{"our penalty: our kicker touches the ball only wholly outside their defense area"};
  Always dribble{"our penalty: no robot of ours dribbles the ball further than 1 m"};
  Always unchecked{"the shot from the mark (not checked)"};
  int advanced = 0;
  int from_mark = 0;
  double slowest = 0;
  for (int k = 1; k <= kPenalties; ++k) {
    const PenaltyOutcome played_on = take_penalty(param(), k, PenaltyPlay::kAdvance, speed, others, area, dribble);
    if (played_on.goal) {
      ++advanced;
      slowest = std::max(slowest, played_on.decided_after);
    }
    if (take_penalty(param(), k, PenaltyPlay::kShot, unchecked, unchecked, unchecked, unchecked).goal) ++from_mark;
  }
  speed.report();
  others.report();
  area.report();
  dribble.report();
  EXPECT_GE(advanced, kPenalties - 1);
  EXPECT_GT(advanced, from_mark);
  print_figures("PenaltyScored", param(),
                "played on and shot from close in " + std::to_string(advanced) + " of " + std::to_string(kPenalties) +
                    " (slowest goal " + Always::fmt(slowest) + " s after NORMAL_START), from the mark " +
                    std::to_string(from_mark) + " of " + std::to_string(kPenalties));
}

// ---- the keeper --------------------------------------------------------------------------------------------

/// Removes robot `id` of us / them from the field.
void take_off(LockstepMatch& m, bool ours, std::uint32_t id) {
  sim::ControlRequest request;
  request.robots.push_back({.key = {ours ? m.us() : m.them(), id}, .present = false});
  EXPECT_TRUE(m.sim_apply(request));
}

TEST_P(PlannerSimReferee, TheKeeperSavesStraightShotsAtFourMetresPerSecond) {
  // Only the two keepers on the field, normal play: 20 shots from 4 m in front of our goal, each at a random
  // point of the goal mouth at 4 m/s. A save: the ball does not cross our goal line inside the goal.
  constexpr int kShots = 20;
  constexpr double kShotSpeed = 4.0;    // m/s
  constexpr double kShotDistance = 4.0;  // m from the goal line
  LockstepMatch m(param(), seed());
  for (std::uint32_t id = 1; id < kRobots; ++id) {
    take_off(m, true, id);
    take_off(m, false, id);
  }
  const double goal_line = -m.half_length();
  const double half_goal = m.field().goal_width / 2;
  m.script({{0.0, RefereeCommand::kForceStart}});
  std::mt19937 random(static_cast<std::uint32_t>(seed()));
  std::uniform_real_distribution<double> from_y(-1.0, 1.0);
  std::uniform_real_distribution<double> aim_y(-(half_goal - kBallRadius), half_goal - kBallRadius);
  int goals = 0;
  for (int shot = 0; shot < kShots; ++shot) {
    m.place(true, 0, {goal_line + 0.15, 0}, 0.0);
    m.place(false, 0, {-goal_line - 0.15, 0}, M_PI);
    const Vec2 from(goal_line + kShotDistance, from_y(random));
    m.place_ball(from);
    for (int i = 0; i < 50; ++i) m.tick();  // 0.5 s: the keeper takes its place for the ball lying there
    m.place_ball(from);
    const Vec2 aim(goal_line, aim_y(random));
    m.roll_ball((aim - from).normalized() * kShotSpeed);
    bool scored = false;
    for (int i = 0; i < 250; ++i) {
      m.tick();
      const Vec2 ball = m.truth().ball;
      if (ball.x() < goal_line) {
        scored = std::abs(ball.y()) < half_goal;
        break;
      }
      if (m.truth().ball_velocity.x() > 0.2) break;  // turned back: saved
    }
    goals += scored ? 1 : 0;
  }
  std::printf("[%s] keeper: %d of %d shots saved\n", param().name().c_str(), kShots - goals, kShots);
  EXPECT_GE(kShots - goals, kShots * 8 / 10);
}

// ---- the action nodes (skills.h), one robot each, everybody else taken off or standing ---------------------

TEST_P(PlannerSimReferee, ShootScoresOnAnEmptyGoalFromTenRandomSpots) {
  // Our robot 1 alone with the ball in their half (no keeper), normal play: the shoot skill gets behind the
  // ball and scores, from each of 10 random spots.
  constexpr int kSpots = 10;
  std::mt19937 random(static_cast<std::uint32_t>(seed()));
  int goals = 0;
  for (int spot = 0; spot < kSpots; ++spot) {
    LockstepMatch m(param(), seed() + static_cast<std::uint64_t>(spot));
    for (std::uint32_t id = 0; id < kRobots; ++id) {
      if (id != 1) take_off(m, true, id);
      take_off(m, false, id);
    }
    const double hl = m.half_length();
    const double half_goal = m.field().goal_width / 2;
    std::uniform_real_distribution<double> x(0.5, hl - m.field().penalty_area_depth - 0.5);
    std::uniform_real_distribution<double> y(-m.field().field_width / 2 + 0.5, m.field().field_width / 2 - 0.5);
    const Vec2 ball(x(random), y(random));
    m.place_ball(ball);
    m.place(true, 1, ball + Vec2(-0.8, 0.4), 0.0);
    m.planner(true).override_skill(1, SkillOverride{ShootParams{}});
    m.script({{kWarmUp, RefereeCommand::kForceStart}});
    bool scored = false;
    while (m.time() < kWarmUp + 8.0 && !scored) {
      m.tick();
      const Vec2 at = m.truth().ball;
      if (at.x() > hl) {
        scored = std::abs(at.y()) < half_goal;
        if (!scored) break;  // wide
      }
    }
    if (!scored) std::printf("[%s] shot from (%.2f, %.2f) missed\n", param().name().c_str(), ball.x(), ball.y());
    goals += scored ? 1 : 0;
  }
  std::printf("[%s] shoot: %d of %d from random spots scored\n", param().name().c_str(), goals, kSpots);
  EXPECT_EQ(goals, kSpots);
}

TEST_P(PlannerSimReferee, ReceiveControlsAtLeastEightyPercentOfPassesFromTwoToFiveMetres) {
  // Our robot 1 passes (pass skill, arriving at 1.5 m/s) to robot 2 (receive skill) 2-5 m away in a random
  // direction; nobody else on the field. Controlled: within 4 s the ball lies (< 0.5 m/s) at robot 2's
  // dribbler.
  constexpr int kPasses = 10;
  std::mt19937 random(static_cast<std::uint32_t>(seed()));
  std::uniform_real_distribution<double> distance(2.0, 5.0);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  int controlled = 0;
  for (int attempt = 0; attempt < kPasses; ++attempt) {
    LockstepMatch m(param(), seed() + static_cast<std::uint64_t>(attempt));
    for (std::uint32_t id = 0; id < kRobots; ++id) {
      if (id != 1 && id != 2) take_off(m, true, id);
      take_off(m, false, id);
    }
    const double hx = m.half_length() - 1.4;  // clear of both defense areas
    const double hy = m.field().field_width / 2 - 0.4;
    Vec2 ball = Vec2::Zero();
    Vec2 receiver = Vec2::Zero();
    do {
      ball = Vec2(std::uniform_real_distribution<double>(-hx, hx)(random),
                  std::uniform_real_distribution<double>(-hy, hy)(random));
      const double a = angle(random);
      receiver = ball + distance(random) * Vec2(std::cos(a), std::sin(a));
    } while (std::abs(receiver.x()) > hx || std::abs(receiver.y()) > hy);
    m.place_ball(ball);
    const Vec2 u = (receiver - ball).normalized();
    m.place(true, 1, ball - u * 0.5, std::atan2(u.y(), u.x()));
    m.place(true, 2, receiver, std::atan2(-u.y(), -u.x()));
    m.planner(true).override_skill(1, SkillOverride{PassParams{.receiver = receiver}});
    m.planner(true).override_skill(2, SkillOverride{ReceiveParams{.point = receiver}});
    m.script({{kWarmUp, RefereeCommand::kForceStart}});
    bool kicked = false;
    bool got_it = false;
    while (m.time() < kWarmUp + 8.0 && !got_it) {
      m.tick();
      const Truth& truth = m.truth();
      if (!kicked && truth.ball_velocity.norm() > 1.0) {
        kicked = true;
        m.planner(true).override_skill(1, SkillOverride{StopParams{}});  // the passer steps out of it
      }
      if (!kicked) continue;
      for (const TrueRobot& r : truth.robots) {
        if (r.ours && r.id == 2 && (r.position - truth.ball).norm() < kR + kBallRadius + 0.03 &&
            truth.ball_velocity.norm() < 0.5 && (truth.ball_velocity - r.velocity).norm() < 0.5) {
          got_it = true;
        }
      }
    }
    if (!got_it) {
      std::printf("[%s] pass %.2f m from (%.2f, %.2f) not controlled (kicked: %d)\n", param().name().c_str(),
                  (receiver - ball).norm(), ball.x(), ball.y(), kicked ? 1 : 0);
    }
    controlled += got_it ? 1 : 0;
  }
  std::printf("[%s] receive: %d of %d passes controlled\n", param().name().c_str(), controlled, kPasses);
  EXPECT_GE(controlled, kPasses * 8 / 10);
}

/// A pass from where the ball lies to a point where robot 2 (redirect skill, aiming at the middle of their
/// empty goal) shoots it on at the first touch: robot 1 passes it (pass skill, arriving at 2.5 m/s). Each of
/// `passes` attempts draws the ball and the point with `draw(uniform, match)`, redrawn until the
/// pass turns by `min_turn`..`max_turn` rad into the shot. Returns how many were redirected: the ball crossed
/// their goal line inside the mouth within 5 s of the pass, faster than 2 m/s (shot on, not carried), and
/// robot 2 never held it.
template <typename Draw>
int redirected_passes(const Case& c, std::uint64_t first_seed, int passes, double min_turn, double max_turn,
                      Draw draw) {
  std::mt19937 random(static_cast<std::uint32_t>(first_seed));
  const auto uniform = [&](double low, double high) { return std::uniform_real_distribution<double>(low, high)(random); };
  int scored = 0;
  for (int attempt = 0; attempt < passes; ++attempt) {
    LockstepMatch m(c, first_seed + static_cast<std::uint64_t>(attempt));
    for (std::uint32_t id = 0; id < kRobots; ++id) {
      if (id != 1 && id != 2) take_off(m, true, id);
      take_off(m, false, id);
    }
    const double hl = m.half_length();
    const Vec2 goal(hl, 0.0);
    Vec2 ball = Vec2::Zero();
    Vec2 point = Vec2::Zero();
    double turn = 0;
    do {
      std::tie(ball, point) = draw(uniform, m);
      const Vec2 back = (ball - point).normalized();
      turn = std::acos(std::clamp(back.dot((goal - point).normalized()), -1.0, 1.0));
    } while (turn < min_turn || turn > max_turn);
    m.place_ball(ball);
    const Vec2 u = (point - ball).normalized();
    const Vec2 shot = (goal - point).normalized();
    m.place(true, 1, ball - u * 0.5, std::atan2(u.y(), u.x()));
    m.place(true, 2, point - shot * (kR + kBallRadius), std::atan2(shot.y(), shot.x()));
    m.planner(true).override_skill(1, SkillOverride{PassParams{.receiver = point, .arrival_speed = 2.5}});
    m.planner(true).override_skill(2, SkillOverride{RedirectParams{.point = point, .aim = goal, .max_angle = max_turn}});
    m.script({{kWarmUp, RefereeCommand::kForceStart}});
    bool kicked = false;
    bool held = false;
    bool in = false;
    double kicked_at = 0;
    while (m.time() < kWarmUp + 8.0 && !in) {
      m.tick();
      const Truth& truth = m.truth();
      if (!kicked && truth.ball_velocity.norm() > 1.0) {
        kicked = true;
        kicked_at = m.time();
        m.planner(true).override_skill(1, SkillOverride{StopParams{}});  // the passer steps out of it
      }
      if (!kicked) continue;
      if (m.time() > kicked_at + 5.0) break;
      for (const TrueRobot& r : truth.robots) {
        if (r.ours && r.id == 2 && (r.position - truth.ball).norm() < kR + kBallRadius + 0.03 &&
            (truth.ball_velocity - r.velocity).norm() < 0.3) {
          held = true;
        }
      }
      if (truth.ball.x() > hl) {
        in = std::abs(truth.ball.y()) < m.field().goal_width / 2 && truth.ball_velocity.norm() > 2.0;
        break;
      }
    }
    if (!in || held) {
      std::printf("[%s] redirect at (%.2f, %.2f), turning %.2f rad, of a pass from (%.2f, %.2f) missed (kicked: %d, "
                  "held: %d)\n",
                  c.name().c_str(), point.x(), point.y(), turn, ball.x(), ball.y(), kicked ? 1 : 0, held ? 1 : 0);
    }
    scored += in && !held ? 1 : 0;
  }
  return scored;
}

TEST_P(PlannerSimReferee, RedirectShootsAtLeastEightOfTenPassesOnIntoTheGoalAtTheFirstTouch) {
  // The free kick's set play without opponents: the ball lies 0.9-1.6 m in front of their defense area, near
  // the middle; the point 0.4-0.8 m beside the area, where the pass turns by at most 0.8 rad into the shot
  // (TeamPlayParams::redirect_max_angle).
  constexpr int kPasses = 10;
  const int scored = redirected_passes(param(), seed(), kPasses, 0.0, TeamPlayParams{}.redirect_max_angle,
                                       [](const auto& uniform, const LockstepMatch& m) {
    const double area_front = m.half_length() - m.field().penalty_area_depth;
    const Vec2 ball(area_front - uniform(0.9, 1.6), uniform(-0.5, 0.5));
    const double side = uniform(-1, 1) < 0 ? -1.0 : 1.0;
    const Vec2 point(ball.x() + uniform(-0.3, 0.3), side * (m.field().penalty_area_width / 2 + uniform(0.4, 0.8)));
    return std::pair(ball, point);
  });
  std::printf("[%s] redirect: %d of %d passes shot on into the goal\n", param().name().c_str(), scored, kPasses);
  EXPECT_GE(scored, kPasses * 8 / 10);
}

TEST_P(PlannerSimReferee, ACutBackFromTheWingIsShotOnAtTheFirstTouchInAtLeastEightOfTen) {
  // A one-touch pass wider than the free kick's set play turns: the ball lies on the wing beside their
  // defense area, 0.2-1.0 m from their goal line and 0.3-0.9 m outside the area's side; the point in the
  // slot 0.4-1.4 m in front of the area, within the area's width, where the pass turns by more than the set
  // play's 0.8 rad, up to kCutBackMaxTurn (a ball cut back from near their goal line into the slot).
  constexpr int kPasses = 10;
  constexpr double kCutBackMaxTurn = 1.2;  // rad
  const int scored = redirected_passes(param(), seed(), kPasses, TeamPlayParams{}.redirect_max_angle, kCutBackMaxTurn,
                                       [](const auto& uniform, const LockstepMatch& m) {
    const double hl = m.half_length();
    const double half_area = m.field().penalty_area_width / 2;
    const double side = uniform(-1, 1) < 0 ? -1.0 : 1.0;
    const Vec2 ball(hl - uniform(0.2, 1.0), side * (half_area + uniform(0.3, 0.9)));
    const Vec2 point(hl - m.field().penalty_area_depth - uniform(0.4, 1.4), uniform(-half_area, half_area));
    return std::pair(ball, point);
  });
  std::printf("[%s] cut-back: %d of %d passes shot on into the goal\n", param().name().c_str(), scored, kPasses);
  EXPECT_GE(scored, kPasses * 8 / 10);
}

/// Only our robot `id` (and their robots in `theirs`) on the field; the others taken off.
void only(LockstepMatch& m, std::uint32_t id, std::initializer_list<std::uint32_t> theirs = {}) {
  for (std::uint32_t other = 0; other < kRobots; ++other) {
    if (other != id) take_off(m, true, other);
    if (std::find(theirs.begin(), theirs.end(), other) == theirs.end()) take_off(m, false, other);
  }
}

const TrueRobot* true_robot(const LockstepMatch& m, bool ours, std::uint32_t id) {
  for (const TrueRobot& r : m.truth().robots) {
    if (r.ours == ours && r.id == id) return &r;
  }
  return nullptr;
}

/// Ticks until `done` holds or `limit` s of simulated time passed; true when it held.
bool run_until(LockstepMatch& m, double limit, const std::function<bool()>& done) {
  const double until = m.time() + limit;
  while (m.time() < until) {
    m.tick();
    if (done()) return true;
  }
  return false;
}

TEST_P(PlannerSimReferee, TwoAgainstNobodyPassWhenTheShotIsPoorAndScore) {
  // The base strategy, our robots 1 and 2 alone: 1 at the ball near the touch line in their half, where the
  // goal is a narrow slit; 2 in front of their goal. Normal play: 1 passes to 2 (the tree's dynamic pass),
  // 2 takes the ball and scores within 12 s.
  LockstepMatch m(param(), seed());
  for (std::uint32_t id = 0; id < kRobots; ++id) {
    if (id != 1 && id != 2) take_off(m, true, id);
    take_off(m, false, id);
  }
  const double hl = m.half_length();
  const Vec2 ball(hl - 3.5, m.field().field_width / 2 - 0.5);
  m.place_ball(ball);
  m.place(true, 1, ball + Vec2(-0.3, 0), 0.0);
  m.place(true, 2, {hl - 2.0, -0.3}, M_PI / 2);
  m.script({{kWarmUp, RefereeCommand::kForceStart}});
  bool passed = false;
  bool received = false;
  bool scored = false;
  while (m.time() < kWarmUp + 12.0 && !scored) {
    m.tick();
    for (const RoleInfo& role : m.output(true).roles) {
      if (role.robot_id == 1 && role.tactic == "pass") passed = true;
    }
    const TrueRobot* receiver = true_robot(m, true, 2);
    if (passed && receiver && receiver->touching) received = true;
    const Vec2 at = m.truth().ball;
    if (at.x() > hl) {
      scored = std::abs(at.y()) < m.field().goal_width / 2;
      if (!scored) break;
    }
  }
  EXPECT_TRUE(passed) << "robot 1 never played the pass";
  EXPECT_TRUE(received) << "robot 2 never touched the ball after the pass";
  EXPECT_TRUE(scored) << "no goal within 12 s; the ball ended at " << m.truth().ball.transpose();
}

/// Who touched the ball last: nullopt until somebody did.
struct LastTouch {
  std::optional<bool> ours;
  void update(const Truth& truth) {
    for (const TrueRobot& r : truth.robots) {
      if (r.touching) ours = r.ours;
    }
  }
};

/// Where a ball past a goal line went: +1 into their goal, -1 into ours, 0 still in play or out elsewhere.
int goal_of(const LockstepMatch& m) {
  // As the rules judge it: the whole ball over the goal line, between the posts and inside the goal (a ball
  // that rolled past a post round the back of the goal is no goal).
  const Vec2& ball = m.truth().ball;
  const double beyond = std::abs(ball.x()) - m.half_length();
  if (beyond <= kBallRadius || beyond > m.field().goal_depth ||
      std::abs(ball.y()) >= m.field().goal_width / 2 - kBallRadius) {
    return 0;
  }
  return ball.x() > 0 ? 1 : -1;
}

TEST_P(PlannerSimReferee, DefendAgainstAStraightAttacker) {
  // Their one field player plays the ball_chaser strategy (straight at the ball, straight at our goal) from
  // the centre, the ball between it and our half; our whole team plays the base strategy. For 15 s: no goal
  // against us, and one of ours wins the ball (touches it) within 8 s. kNotYetRealistic: their attacker
  // scores in 1-2 of the 8.
  LockstepMatch m(param(), seed(), Strategy::kBase, Strategy::kBallChaser, PlannerConfig().penalty,
                  kNotYetRealistic);
  default_layout(m);
  for (std::uint32_t id = 2; id < kRobots; ++id) take_off(m, false, id);
  const double hl = m.half_length();
  m.place(false, 0, {hl - 0.3, 0}, M_PI);
  m.place(false, 1, {0.6, 0.2}, M_PI);
  m.place_ball({0.3, 0.2});
  m.script({{kWarmUp, RefereeCommand::kForceStart}});
  std::optional<double> won;
  int goal = 0;
  while (m.time() < kWarmUp + 15.0 && goal != -1) {
    m.tick();
    goal = goal_of(m);
    for (const TrueRobot& r : m.truth().robots) {
      if (r.ours && r.touching && !won) won = m.time() - kWarmUp;
    }
  }
  EXPECT_NE(goal, -1) << "their straight attacker scored at " << m.time() - kWarmUp << " s";
  ASSERT_TRUE(won) << "none of ours touched the ball in 15 s";
  EXPECT_LE(*won, 8.0) << "ours won the ball only after " << *won << " s";
  print_figures("StraightAttack", param(), "ball won after " + Always::fmt(*won) + " s");
}

TEST_P(PlannerSimReferee, DefendATwoAgainstOneCounterAttack) {
  // A counter-attack: their two field players (base strategy, passing) start at the centre line with the ball;
  // we have our keeper and one defender, back in our half. For 10 s: no goal against us.
  LockstepMatch m(param(), seed());
  for (std::uint32_t id = 2; id < kRobots; ++id) take_off(m, true, id);
  for (std::uint32_t id = 3; id < kRobots; ++id) take_off(m, false, id);
  const double hl = m.half_length();
  m.place(true, 0, {-hl + 0.3, 0}, 0.0);
  m.place(true, 1, {-2.0, 0.3}, 0.0);
  m.place(false, 0, {hl - 0.3, 0}, M_PI);
  m.place(false, 1, {0.2, 0.6}, M_PI);
  m.place(false, 2, {0.3, -1.2}, M_PI);
  m.place_ball({0.2 - (kR + kBallRadius + 0.005), 0.6});
  m.script({{kWarmUp, RefereeCommand::kForceStart}});
  LastTouch last;
  int goal = 0;
  while (m.time() < kWarmUp + 10.0 && goal != -1) {
    m.tick();
    last.update(m.truth());
    goal = goal_of(m);
  }
  EXPECT_NE(goal, -1) << "their counter-attack scored at " << m.time() - kWarmUp << " s";
  print_figures("Counter2v1", param(),
                std::string("last touch ") + (last.ours ? (*last.ours ? "ours" : "theirs") : "nobody") +
                    ", ball at " + Always::fmt(m.truth().ball.x()) + ", " + Always::fmt(m.truth().ball.y()));
}

TEST_P(PlannerSimReferee, ThreeAgainstThreeKeepPossessionForTenSeconds) {
  // Three field players and a keeper a side, both teams the base strategy: ours have the ball at robot 1's
  // dribbler in our half, far from a shot; theirs stand between us and their goal and press. Normal play for
  // 10 s: none of theirs touches the ball, it stays on the field, and ours pass it among themselves. On
  // division B's field ours reach their third within the 10 s: a poor shot there would give the ball away.
  // kNotYetRealistic: one of theirs touches the ball after 9-10 s in 3 of the 8.
  LockstepMatch m(param(), seed(), kNotYetRealistic);
  for (std::uint32_t id : {4u, 5u}) {
    take_off(m, true, id);
    take_off(m, false, id);
  }
  const double hl = m.half_length();
  m.place(true, 0, {-hl + 0.3, 0}, 0.0);
  m.place(false, 0, {hl - 0.3, 0}, M_PI);
  m.place(true, 1, {-1.5, 0}, 0.0);
  m.place(true, 2, {-0.8, 1.5}, 0.0);
  m.place(true, 3, {-0.8, -1.5}, 0.0);
  m.place(false, 1, {0.3, 0.1}, M_PI);
  m.place(false, 2, {0.8, 1.2}, M_PI);
  m.place(false, 3, {0.8, -1.2}, M_PI);
  m.place_ball({-1.5 + kR + kBallRadius + 0.005, 0});
  m.script({{kWarmUp, RefereeCommand::kForceStart}});
  std::optional<double> lost;  // s: their first touch, or the ball off the field
  std::string how;
  std::optional<std::uint32_t> last_ours;
  int passes = 0;  // touches by one of ours after another of ours touched it
  while (m.time() < kWarmUp + 10.0 && !lost) {
    m.tick();
    const Truth& truth = m.truth();
    for (const TrueRobot& r : truth.robots) {
      if (!r.touching) continue;
      if (!r.ours) {
        lost = m.time() - kWarmUp;
        how = r.name() + " touched it";
      } else {
        if (last_ours && *last_ours != r.id) ++passes;
        last_ours = r.id;
      }
    }
    if (std::abs(truth.ball.x()) > m.half_length() || std::abs(truth.ball.y()) > m.field().field_width / 2) {
      lost = m.time() - kWarmUp;
      how = "the ball left the field at " + Always::fmt(truth.ball.x()) + ", " + Always::fmt(truth.ball.y());
    }
  }
  EXPECT_FALSE(lost) << how << " after " << lost.value_or(0) << " s";
  EXPECT_GE(passes, 1) << "ours never passed";
  print_figures("Keep3v3", param(),
                std::to_string(passes) + " passes" + (lost ? ", lost after " + Always::fmt(*lost) + " s: " + how : ", kept"));
}

/// Their robot 3 runs a round of points in our half at up to `speed` m/s (go_to_point, a new point every
/// 2 s: sprints towards our goal, across it and away, stops and turns); our robot 2 marks it. After 1 s to
/// take up the mark, at every tick: nearer our goal centre than its opponent and within `within` m of it.
void man_mark_round(LockstepMatch& m, double speed, double within, const std::string& scenario) {
  for (std::uint32_t id = 0; id < kRobots; ++id) {
    if (id != 2) take_off(m, true, id);
    if (id != 3) take_off(m, false, id);
  }
  m.place_ball({1.5, 2.0});
  m.place(false, 3, {-1.0, 0.0}, M_PI);
  m.place(true, 2, {-1.5, 0.3}, 0.0);
  // Their points, in OUR frame; their planner works in its own (mirrored) frame.
  const Vec2 round[] = {{-2.0, 1.0}, {-0.5, -1.2}, {-2.5, -0.8}, {-1.0, 1.5}, {-2.2, 0.2}, {0.0, 0.5}, {-1.5, -2.0}};
  m.planner(true).override_skill(2, SkillOverride{ManMarkParams{.opponent = 3}});
  m.script({{kWarmUp, RefereeCommand::kForceStart}});
  Always marked{"man-mark: goal-side of its opponent, within " + Always::fmt(within) + " m"};
  const Vec2 goal(-m.half_length(), 0);
  double farthest = 0;
  double closest = 1e9;
  int leg = -1;
  while (m.time() < kWarmUp + 15.0) {
    const int now_leg = static_cast<int>((m.time() - kWarmUp) / 2.0);
    if (now_leg != leg) {
      leg = now_leg;
      const Vec2 point = round[static_cast<std::size_t>(std::max(leg, 0)) % std::size(round)];
      m.planner(false).override_skill(3, SkillOverride{GoToPointParams{.point = -point, .max_speed = speed}});
    }
    m.tick();
    const double t = m.time();
    if (t < kWarmUp + 1.0) continue;
    const TrueRobot* marker = true_robot(m, true, 2);
    const TrueRobot* opponent = true_robot(m, false, 3);
    ASSERT_TRUE(marker && opponent);
    const double apart = (marker->position - opponent->position).norm();
    const double behind = (opponent->position - goal).norm() - (marker->position - goal).norm();
    farthest = std::max(farthest, apart);
    closest = std::min(closest, apart);
    marked.require(apart <= within && behind > 0, t, [&] {
      return "apart " + Always::fmt(apart) + " m, nearer our goal by " + Always::fmt(behind) + " m";
    });
  }
  marked.report();
  print_figures(scenario, m.test_case(), "apart " + Always::fmt(closest) + "-" + Always::fmt(farthest) + " m");
}

TEST_P(PlannerSimReferee, ManMarkStaysGoalSideWithinHalfAMetreOfAnOpponentRunningAt1Point5MetresPerSecond) {
  // kNotYetRealistic: the marker trails an opponent crossing its way by up to 0.58 m (6 of the 8): the
  // contact guard, planning with the measured delay plus its allowance, keeps it that far back.
  LockstepMatch m(param(), seed(), kNotYetRealistic);
  man_mark_round(m, 1.5, 0.5, "ManMark1.5");
}

TEST_P(PlannerSimReferee, ManMarkStaysGoalSideWithinSeventyCentimetresOfAnOpponentRunningAt2MetresPerSecond) {
  // The contact guard sets the floor here: it lets the marker close in on a robot running straight away at
  // 2 m/s only as far as still stops it if that robot brakes at 3 m/s^2 (TrajectoryMotionParams), 0.45 m
  // centre to centre once both run steadily, and on one running more than 45 degrees off straight away
  // (it may turn towards the marker instead) only as far as the gap itself allows. Half a metre held at
  // some seeds only (PLANNER_SIM_SEED 1-12 x 8 sides and divisions: the worst 0.63 m, median 0.45 m).
  // kNotYetRealistic: up to 0.78 m (5 of the 8), as above.
  LockstepMatch m(param(), seed(), kNotYetRealistic);
  man_mark_round(m, 2.0, 0.7, "ManMark2");
}

TEST_P(PlannerSimReferee, GoToBallThenDribbleAndTurnWithItKeepTheBall) {
  // Go to ball: the ball on the dribbler within 4 s. Go to point with the ball, 2 m away: the dribble stops
  // within the rules' 1 m and the ball is still held. Turn with ball by 90 degrees: heading reached within
  // 0.1 rad in 3 s, the ball still held.
  LockstepMatch m(param(), seed());
  only(m, 1);
  const Vec2 ball(0.5, 0.5);
  m.place_ball(ball);
  m.place(true, 1, {-0.5, -0.3}, 1.0);
  m.planner(true).override_skill(1, SkillOverride{GoToBallParams{}});
  m.script({{kWarmUp, RefereeCommand::kForceStart}});
  const auto holds = [&] { return true_robot(m, true, 1)->dribbler_contact; };
  ASSERT_TRUE(run_until(m, kWarmUp + 4.0, holds)) << "go to ball: no contact";
  const Vec2 start = m.truth().ball;
  const double heading = std::atan2(start.y() - true_robot(m, true, 1)->position.y(),
                                    start.x() - true_robot(m, true, 1)->position.x());
  m.planner(true).override_skill(
      1, SkillOverride{GoToPointParams{.point = start + Vec2(2.0, 0.0), .orientation = heading, .with_ball = true,
                                       .dribble_start = start}});
  double furthest = 0;
  (void)run_until(m, 4.0, [&] {
    furthest = std::max(furthest, (m.truth().ball - start).norm());
    return false;
  });
  EXPECT_LE(furthest, rules::kMaxDribblingDistance) << "dribbled beyond the rules' limit";
  EXPECT_GT(furthest, 0.5) << "the dribble went somewhere";
  EXPECT_TRUE(holds()) << "the ball was lost on the dribble";
  const double turned = heading + M_PI / 2;
  m.planner(true).override_skill(1, SkillOverride{TurnWithBallParams{.orientation = turned}});
  (void)run_until(m, 3.0, [] { return false; });
  const Vec2 facing = (m.truth().ball - true_robot(m, true, 1)->position).normalized();
  EXPECT_NEAR(std::remainder(std::atan2(facing.y(), facing.x()) - turned, 2 * M_PI), 0.0, 0.1)
      << "the ball (in front of the dribbler) turned with the robot";
  EXPECT_TRUE(holds()) << "the ball was lost in the turn";
}

TEST_P(PlannerSimReferee, ClearSendsTheBallOutOfOurHalfAwayFromTheOpponents) {
  // The ball in front of our defense area, two of their robots straight upfield: clear kicks it out of our
  // half within 4 s, past them on the open side. kNotYetRealistic: in division A (4 of the 8) the clear goes
  // 40-45 degrees off upfield, away from both, at the speed that rests it 1 m inside the touch line, and is
  // 0.2-0.5 m short of halfway after 4 s.
  LockstepMatch m(param(), seed(), kNotYetRealistic);
  only(m, 1, {1, 2});
  const double x = -m.half_length() + m.field().penalty_area_depth + 0.5;
  m.place_ball({x, 0.0});
  m.place(true, 1, {x - 0.6, 0.3}, 0.0);
  m.place(false, 1, {x + 1.2, 0.0}, M_PI);
  m.place(false, 2, {x + 1.2, 0.35}, M_PI);
  m.planner(true).override_skill(1, SkillOverride{ClearParams{}});
  m.planner(false).override_skill(1, SkillOverride{StopParams{}});
  m.planner(false).override_skill(2, SkillOverride{StopParams{}});
  m.script({{kWarmUp, RefereeCommand::kForceStart}});
  EXPECT_TRUE(run_until(m, kWarmUp + 4.0, [&] { return m.truth().ball.x() > 0; }))
      << "ball at " << m.truth().ball.transpose();
}

TEST_P(PlannerSimReferee, TheKeeperClearsABallLyingOnOurGoalLineBesideAPost) {
  // The ball at rest on our goal line 7 cm beyond a post, inside our defense area (seen in `./ssl up`: the
  // keeper went for a kicking spot along the line, behind the post, for minutes). Normal play, our keeper
  // alone: within 8 s the ball is out of our defense area, and not in our goal.
  LockstepMatch m(param(), seed());
  only(m, 0);
  const double hl = m.half_length();
  const Vec2 ball(-hl + kBallRadius - 0.012, -(m.field().goal_width / 2 + 0.07));
  m.place_ball(ball);
  m.place(true, 0, {-hl + 0.2, 0.2}, 0.0);
  m.script({{kWarmUp, RefereeCommand::kForceStart}});
  const auto out_of_area = [&] {
    const Vec2& at = m.truth().ball;
    return at.x() > -hl + m.field().penalty_area_depth + kBallRadius ||
           std::abs(at.y()) > m.field().penalty_area_width / 2 + kBallRadius;
  };
  EXPECT_TRUE(run_until(m, kWarmUp + 8.0, out_of_area)) << "ball at " << m.truth().ball.transpose();
  EXPECT_EQ(goal_of(m), 0);
}

TEST_P(PlannerSimReferee, TheKeeperClearsABallLyingStillOnOurDefenseAreasEdgeBesideAnOpponent) {
  // The ball at rest 1.5 mm outside the side of our defense area, an opponent standing 0.45 m from it (seen
  // on grSim: nobody may fetch it from inside our area, the opponent cannot get behind it either, and the
  // keeper left it to the nearer opponent; no autoRef called no progress, and it lay there for 174 s).
  // Normal play, our keeper alone: within 8 s the ball is 0.5 m from where it lay, and not in our goal.
  LockstepMatch m(param(), seed());
  only(m, 0, {1});
  const double hl = m.half_length();
  const Vec2 ball(-hl + m.field().penalty_area_depth - 0.6, -(m.field().penalty_area_width / 2 + 0.0015));
  m.place_ball(ball);
  m.place(true, 0, {-hl + 0.2, 0.0}, 0.0);
  m.place(false, 1, ball + Vec2(0.2, -0.4), M_PI);
  m.planner(false).override_skill(1, SkillOverride{StopParams{}});
  m.script({{kWarmUp, RefereeCommand::kForceStart}});
  EXPECT_TRUE(run_until(m, kWarmUp + 8.0, [&] { return (m.truth().ball - ball).norm() > 0.5; }))
      << "ball at " << m.truth().ball.transpose();
  EXPECT_EQ(goal_of(m), 0);
}

TEST_P(PlannerSimReferee, StopBrakesARunningRobotToAStandstill) {
  // Running at full speed, stop: standing (< 0.05 m/s) within what braking at the simulator's 4 m/s^2
  // takes, plus 0.2 s.
  LockstepMatch m(param(), seed());
  only(m, 1);
  m.place_ball({2.0, 2.0});
  m.place(true, 1, {-2.5, -1.0}, 0.0);
  m.planner(true).override_skill(1, SkillOverride{GoToPointParams{.point = {2.5, -1.0}}});
  m.script({{kWarmUp, RefereeCommand::kForceStart}});
  (void)run_until(m, kWarmUp + 1.2, [] { return false; });
  const double speed = true_robot(m, true, 1)->speed();
  ASSERT_GT(speed, 2.0) << "running";
  m.planner(true).override_skill(1, SkillOverride{StopParams{}});
  const double allowance = speed / m.sim().options().blue_spec.limits.acc_brake_absolute_max + 0.2;
  EXPECT_TRUE(run_until(m, allowance, [&] { return true_robot(m, true, 1)->speed() < kHaltSpeed; }))
      << "still at " << true_robot(m, true, 1)->speed() << " m/s after " << allowance << " s";
}

TEST_P(PlannerSimReferee, OpenSpaceFindsRoomAwayFromTheOpponentsAroundItsAnchor) {
  // Three of their robots around the anchor: the robot ends within 1 m of it, at least 0.6 m from each.
  LockstepMatch m(param(), seed());
  only(m, 1, {1, 2, 3});
  m.place_ball({-1.0, 0.0});
  const Vec2 anchor(0.5, 1.0);
  m.place(false, 1, anchor + Vec2(0.2, 0.0), M_PI);
  m.place(false, 2, anchor + Vec2(-0.3, 0.3), M_PI);
  m.place(false, 3, anchor + Vec2(0.0, -0.4), M_PI);
  for (std::uint32_t id : {1u, 2u, 3u}) m.planner(false).override_skill(id, SkillOverride{StopParams{}});
  m.place(true, 1, {-1.5, 1.5}, 0.0);
  m.planner(true).override_skill(1, SkillOverride{OpenSpaceParams{.anchor = anchor, .radius = 1.0}});
  m.script({{kWarmUp, RefereeCommand::kForceStart}});
  (void)run_until(m, kWarmUp + 4.0, [] { return false; });
  const Vec2 at = true_robot(m, true, 1)->position;
  EXPECT_LE((at - anchor).norm(), 1.05);
  for (std::uint32_t id : {1u, 2u, 3u}) EXPECT_GE((true_robot(m, false, id)->position - at).norm(), 0.6) << id;
}

TEST_P(PlannerSimReferee, BlockStandsInTheMouthThenOnTheLineOfSight) {
  // Their robot 4 with the ball, facing our goal: our blocker ends in its mouth (in front of its kicker,
  // within 0.1 m of the point 0.3 m ahead of it). Turned away from our goal: on its line to our goal centre.
  LockstepMatch m(param(), seed());
  only(m, 1, {4});
  const Vec2 possessor(-1.5, 0.8);
  m.place(false, 4, possessor, M_PI);  // facing our goal
  m.place_ball(possessor + Vec2(-0.11, 0.0));
  m.planner(false).override_skill(4, SkillOverride{StopParams{}});
  m.place(true, 1, {-2.5, -0.5}, 0.0);
  m.planner(true).override_skill(1, SkillOverride{BlockParams{.opponent = 4}});
  m.script({{kWarmUp, RefereeCommand::kForceStart}});
  (void)run_until(m, kWarmUp + 3.0, [] { return false; });
  const Vec2 mouth = possessor + Vec2(-0.3, 0.0);
  EXPECT_LE((true_robot(m, true, 1)->position - mouth).norm(), 0.1)
      << "at " << true_robot(m, true, 1)->position.transpose();
  // Turned to face +y (our frame): away from our goal by more than the facing limit.
  m.place(false, 4, possessor, M_PI / 2);
  (void)run_until(m, 3.0, [] { return false; });
  const Vec2 goal(-m.half_length(), 0);
  const Vec2 sight = possessor + (goal - possessor).normalized() * 0.3;
  EXPECT_LE((true_robot(m, true, 1)->position - sight).norm(), 0.1)
      << "at " << true_robot(m, true, 1)->position.transpose();
}

INSTANTIATE_TEST_SUITE_P(PlannerSim, PlannerSimReferee, ::testing::ValuesIn(all_cases()),
                         [](const ::testing::TestParamInfo<Case>& p) { return p.param.name(); });

// Balls beyond the field lines (between the lines and the walls, 0.3 m of boundary in division B; in
// division A 0.6 m behind the goal lines): the placer may enter the boundary, and a ball too near a wall to be
// approached from behind is first pulled back (taken from the field side and dribbled backwards). One colour
// and side each: the skill does not depend on them.
struct OutsideCase {
  const char* name;
  Vec2 ball;    // team frame
  Vec2 target;  // team frame
  bool division_a = false;
  testing::Conditions conditions = testing::PlannedMatchOptions{}.conditions;
};

class PlannerSimPlacementOutside : public ::testing::TestWithParam<OutsideCase> {};

TEST_P(PlannerSimPlacementOutside, OurPlacerFetchesTheBallFromTheBoundary) {
  const OutsideCase c = GetParam();
  LockstepMatch m({.side = {TeamColor::kBlue, false}, .division_a = c.division_a}, seed(), c.conditions);
  default_layout(m);
  m.place_ball(c.ball);
  run_our_placement(m, c.name, c.target, 20.0);
}

// Field B: 9 x 6 m, walls 0.3 m beyond the lines (x = +-4.8, y = +-3.3).
INSTANTIATE_TEST_SUITE_P(
    PlannerSim, PlannerSimPlacementOutside,
    ::testing::Values(OutsideCase{"TouchLineBoundary", {1.0, 3.1}, {1.0, 2.8}},        // 0.2 m from the wall
                      // 0.05 m from the wall. kNotYetRealistic: one of theirs is 0.589 m from the ball (not
                      // 0.59) when the grace ends.
                      OutsideCase{"AgainstTheWall", {-1.5, 3.25}, {-1.5, 2.8}, false, kNotYetRealistic},
                      OutsideCase{"BesideOurGoal", {-4.65, 1.2}, {-3.5, 2.8}},         // goal kick
                      OutsideCase{"InTheCorner", {-4.7, -3.2}, {-4.3, -2.8}},           // both walls near
                      // Field A: walls 0.6 m behind the goal lines (x = +-6.6); the ball 0.45 m behind
                      // ours, where grSim's out balls come to rest (the placer stopped 0.3 m behind the line).
                      OutsideCase{"BehindTheGoalLineDivA", {-6.45, 1.6}, {-5.0, 2.8}, true}),
    [](const ::testing::TestParamInfo<OutsideCase>& param_info) { return std::string(param_info.param.name); });

// ---- determinism ------------------------------------------------------------------------------------------

sim::WorldSnapshot run_placement(std::uint64_t seed, double seconds) {
  LockstepMatch m({.side = {TeamColor::kBlue, true}, .division_a = false}, seed);
  default_layout(m);
  m.place_ball({1.2, 1.3});
  // Placement, STOP, normal play: dribbling, carrying, kicking and contacts all in one run.
  m.script({{kWarmUp, testing::command_for(Restart::kPlacement, TeamColor::kBlue),
             testing::command_for(Restart::kFreeKick, TeamColor::kBlue), Vec2(-0.6, -0.4)},
            {kWarmUp + seconds * 0.6, RefereeCommand::kStop},
            {kWarmUp + seconds * 0.7, RefereeCommand::kForceStart}});
  while (m.time() < kWarmUp + seconds) m.tick();
  return m.sim().snapshot();
}

TEST(PlannerSimDeterminism, SameSeedSameMatchBitExact) {
  const sim::WorldSnapshot a = run_placement(seed(), 8.0);
  const sim::WorldSnapshot b = run_placement(seed(), 8.0);
  ASSERT_EQ(a.time, b.time);
  ASSERT_EQ(a.robots.size(), b.robots.size());
  EXPECT_EQ(a.ball.position, b.ball.position);
  EXPECT_EQ(a.ball.velocity, b.ball.velocity);
  for (std::size_t i = 0; i < a.robots.size(); ++i) {
    EXPECT_EQ(a.robots[i].key, b.robots[i].key);
    // Bit-exact: == on doubles, no tolerance.
    EXPECT_EQ(a.robots[i].position.x(), b.robots[i].position.x()) << i;
    EXPECT_EQ(a.robots[i].position.y(), b.robots[i].position.y()) << i;
    EXPECT_EQ(a.robots[i].orientation, b.robots[i].orientation) << i;
    EXPECT_EQ(a.robots[i].velocity.x(), b.robots[i].velocity.x()) << i;
    EXPECT_EQ(a.robots[i].velocity.y(), b.robots[i].velocity.y()) << i;
    EXPECT_EQ(a.robots[i].angular_velocity, b.robots[i].angular_velocity) << i;
  }
  // The run did something (the ball was carried away from its start, vision (-1.2, -1.3))...
  EXPECT_GT((a.ball.position.head<2>() - Vec2(-1.2, -1.3)).norm(), 0.5);
  // ... and the seed matters (vision noise -> world model -> planner -> a different match).
  const sim::WorldSnapshot c = run_placement(seed() + 1, 8.0);
  bool differs = c.ball.position != a.ball.position;
  for (std::size_t i = 0; i < a.robots.size() && i < c.robots.size(); ++i) {
    differs |= c.robots[i].position != a.robots[i].position;
  }
  EXPECT_TRUE(differs);
}

}  // namespace
}  // namespace ssl::planner
