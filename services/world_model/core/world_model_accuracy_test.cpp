// Accuracy of the world model against the simulator's ground truth (ssl::simulator_core in-process,
// `realistic` vision: 2 mm robot / 3 mm ball noise, 0.01 rad heading noise, dropped detections, 12+3 ms
// delay, occlusion). Errors are measured at each frame's capture instant: the raw detection vs the truth,
// and the filtered state (after fusing that frame) vs the truth. Figures are printed.
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <algorithm>

#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "services/world_model/core/sim_harness.h"

namespace ssl::wm {
namespace {

using namespace std::chrono_literals;
using testing::HarnessOptions;
using testing::Rms;
using testing::SimHarness;

const sim::RobotState* find_robot(const sim::WorldSnapshot& world, TeamColor team, std::uint32_t id) {
  for (const auto& r : world.robots) {
    if (r.key.team == team && r.key.id == id) return &r;
  }
  return nullptr;
}

const RobotState* find_state(const std::vector<RobotState>& robots, std::uint32_t id) {
  for (const auto& r : robots) {
    if (r.id == id) return &r;
  }
  return nullptr;
}

sim::RobotCommand local(double forward, double left, double angular, double kick = 0) {
  sim::RobotCommand c;
  c.move = sim::RobotCommand::Move::kLocalVelocity;
  c.velocity = sim::Vec3(forward, left, angular);
  c.kick_speed = kick;
  return c;
}

// A reference for what kinematics alone can do on a motion: causal sliding-window polynomial fits. The
// estimate at each detection is the least-squares polynomial (degree 1-4) through that robot's detections
// of the last `window` seconds, evaluated at the detection's instant; the best degree and window are
// chosen with hindsight (an advantage no real filter has).
struct EnemySample {
  double t = 0;  // s
  std::uint32_t id = 0;
  Vec2 detected = Vec2::Zero();
  Vec2 truth = Vec2::Zero();
};

struct PolynomialFit {
  double reduction_pct = -1e9;  // position RMS error below the raw detections'
  int degree = 0;
  double window = 0;  // s
};

/// The yellow (enemy) detections of `frame`, captured `t` s after the start, with the truth then.
void add_enemy_samples(const sim::DetectionFrame& frame, const sim::WorldSnapshot& truth, double t,
                       std::vector<EnemySample>& samples) {
  for (const auto& d : frame.robots_yellow) {
    samples.push_back({t, d.robot_id, Vec2(d.x, d.y), find_robot(truth, TeamColor::kYellow, d.robot_id)->position});
  }
}

PolynomialFit best_polynomial_fit(std::vector<EnemySample> samples, double measure_from) {
  std::stable_sort(samples.begin(), samples.end(), [](const auto& a, const auto& b) { return a.t < b.t; });
  double raw = 0;
  for (const EnemySample& s : samples) {
    if (s.t >= measure_from) raw += (s.detected - s.truth).squaredNorm();
  }
  PolynomialFit best;
  for (int degree = 1; degree <= 4; ++degree) {
    for (double window : {0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.6, 0.8, 1.0}) {
      std::map<std::uint32_t, std::vector<const EnemySample*>> history;
      double error = 0;
      for (const EnemySample& s : samples) {
        std::vector<const EnemySample*>& h = history[s.id];
        h.push_back(&s);
        if (s.t < measure_from) continue;
        std::vector<const EnemySample*> used;
        for (const EnemySample* past : h) {
          if (past->t >= s.t - window) used.push_back(past);
        }
        const int d = std::min<int>(degree, static_cast<int>(used.size()) - 1);
        Eigen::MatrixXd a(used.size(), d + 1);
        Eigen::MatrixXd b(used.size(), 2);
        for (std::size_t i = 0; i < used.size(); ++i) {
          for (int k = 0; k <= d; ++k) a(i, k) = std::pow(used[i]->t - s.t, k);
          b.row(i) = used[i]->detected.transpose();
        }
        const Eigen::MatrixXd coefficients = a.colPivHouseholderQr().solve(b);
        error += (Vec2(coefficients(0, 0), coefficients(0, 1)) - s.truth).squaredNorm();
      }
      const double reduction = 100 * (1 - std::sqrt(error / raw));
      if (reduction > best.reduction_pct) best = {reduction, degree, window};
    }
  }
  return best;
}

// Ball errors at each frame's capture time: the first raw detection and the filtered state vs the truth,
// and the filtered velocity vs finite differences of the raw detections.
struct BallErrors {
  Rms raw_pos, filt_pos, filt_vel, naive_vel;
  std::optional<std::pair<time::Timestamp, Vec2>> last_raw;

  void add(const sim::DetectionFrame& frame, const WorldState& world, const sim::WorldSnapshot& truth) {
    const Vec2 true_ball = truth.ball.position.head<2>();
    const Vec2 true_velocity = truth.ball.velocity.head<2>();
    const Vec2 raw(frame.balls[0].x, frame.balls[0].y);
    raw_pos.add((raw - true_ball).norm());
    filt_pos.add((world.ball.position.head<2>() - true_ball).norm());
    filt_vel.add((world.ball.velocity.head<2>() - true_velocity).norm());
    if (last_raw) {
      const double dt = time::to_seconds(frame.capture_time - last_raw->first);
      if (dt > 0.005) naive_vel.add(((raw - last_raw->second) / dt - true_velocity).norm());
    }
    last_raw = {frame.capture_time, raw};
  }

  /// add() for a frame of the harness' run captured after `from` that shows the ball (the model must too).
  void add_after(const SimHarness& h, const sim::DetectionFrame& frame, time::Timestamp from) {
    if (frame.capture_time < from || frame.balls.empty()) return;
    const WorldState world = h.model().state_at_vision_time(frame.capture_time);
    ASSERT_TRUE(world.has_ball);
    add(frame, world, h.truth(frame.capture_time));
  }
};


// Robots of both teams drive along changing curves; blue (ours) tells the model its commands.
TEST(WorldModelAccuracy, RobotPositionAndVelocityRmsAtLeastHalfOfRawUnderRealisticNoise) {
  SimHarness h({.robots_per_team = 6, .seed = 11});
  Rms raw_pos, filt_pos, raw_ori, filt_ori, filt_vel, naive_vel, enemy_raw, enemy_filt;
  std::vector<EnemySample> enemy_samples;
  std::map<std::pair<int, std::uint32_t>, std::pair<time::Timestamp, Vec2>> last_raw;
  time::Timestamp t_cmd;
  const time::Timestamp start = h.now();
  auto drive = [&](SimHarness& harness) {
    if (harness.now() < t_cmd) return;
    t_cmd = harness.now() + 10ms;
    const double t = time::to_seconds(harness.now() - start);
    for (TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) {
      std::vector<sim::RobotCommandFor> commands;
      for (std::uint32_t id = 0; id < 6; ++id) {
        commands.push_back({id, testing::curve_command(t, id + (team == TeamColor::kYellow ? 0.5 : 0))});
      }
      harness.command(team, commands, team == TeamColor::kBlue);
    }
  };
  h.run(8s, drive, [&](const sim::DetectionFrame& frame) {
    const double t = time::to_seconds(frame.capture_time - start);
    const sim::WorldSnapshot& truth = h.truth(frame.capture_time);
    add_enemy_samples(frame, truth, t, enemy_samples);
    if (t < 1.0) return;
    const WorldState world = h.model().state_at_vision_time(frame.capture_time);
    for (TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) {
      const auto& detections = team == TeamColor::kBlue ? frame.robots_blue : frame.robots_yellow;
      const auto& states = team == TeamColor::kBlue ? world.friendly : world.enemy;
      for (const auto& d : detections) {
        const sim::RobotState* r = find_robot(truth, team, d.robot_id);
        const RobotState* s = find_state(states, d.robot_id);
        ASSERT_NE(r, nullptr);
        ASSERT_NE(s, nullptr);
        if (team == TeamColor::kYellow) {
          enemy_raw.add((Vec2(d.x, d.y) - r->position).norm());
          enemy_filt.add((s->position - r->position).norm());
          continue;
        }
        raw_pos.add((Vec2(d.x, d.y) - r->position).norm());
        filt_pos.add((s->position - r->position).norm());
        raw_ori.add(geom::Angle::from_radians(d.orientation - r->orientation).radians());
        filt_ori.add(geom::Angle::from_radians(s->orientation - r->orientation).radians());
        filt_vel.add((s->velocity - r->velocity).norm());
        auto key = std::make_pair(static_cast<int>(team), d.robot_id);
        auto it = last_raw.find(key);
        if (it != last_raw.end()) {
          const double dt = time::to_seconds(frame.capture_time - it->second.first);
          if (dt > 0.005) naive_vel.add(((Vec2(d.x, d.y) - it->second.second) / dt - r->velocity).norm());
        }
        last_raw[key] = {frame.capture_time, Vec2(d.x, d.y)};
      }
    }
  });
  std::printf("[WorldModel] our robots (realistic, commands as control input, %zu samples): position RMS raw %.2f mm, filtered %.2f mm "
              "(%.0f%% lower); orientation RMS raw %.4f rad, filtered %.4f rad; velocity RMS filtered %.3f m/s "
              "vs raw finite difference %.3f m/s\n",
              raw_pos.n, raw_pos.value() * 1e3, filt_pos.value() * 1e3,
              100 * (1 - filt_pos.value() / raw_pos.value()), raw_ori.value(), filt_ori.value(), filt_vel.value(),
              naive_vel.value());
  const PolynomialFit reference = best_polynomial_fit(enemy_samples, 1.0);
  const double enemy_reduction = 100 * (1 - enemy_filt.value() / enemy_raw.value());
  std::printf("[WorldModel] enemy robots (no commands known): position RMS raw %.2f mm, filtered %.2f mm "
              "(%.0f%% lower); best causal polynomial fit %.0f%% lower (degree %d, %.2f s window)\n",
              enemy_raw.value() * 1e3, enemy_filt.value() * 1e3, enemy_reduction, reference.reduction_pct,
              reference.degree, reference.window);
  EXPECT_GT(raw_pos.n, 1000u);
  // Our robots (commands known): the design's >= 50 % (measured 58 %, seed 11). Enemy robots (no commands:
  // IMM over Singer jerk densities) measured 42 % (43 % at seeds 3 and 7), guarded at 35 %. This motion
  // never rests (every robot turns and changes speed all the time, against walls and each other), and
  // without its commands no kinematic estimator gets to 50 % here: the best causal polynomial fit over any
  // window (degree 1-4, chosen with hindsight) reaches 26 %. A match's motion is measured in tests/simulated/
  // world_model_match_accuracy_test (opponents 44-56 % lower there).
  EXPECT_LE(filt_pos.value(), 0.5 * raw_pos.value());
  EXPECT_LE(enemy_filt.value(), 0.65 * enemy_raw.value());
  EXPECT_GT(enemy_reduction, reference.reduction_pct + 5);
  EXPECT_LE(filt_vel.value(), 0.5 * naive_vel.value());
  EXPECT_LT(filt_ori.value(), raw_ori.value());
  EXPECT_EQ(h.model().counters().tracks_created, 12u);
}

// Vision twice as noisy as the config assumes (4 mm, 0.02 rad): each camera's noise is estimated from the
// detections, and the enemies' tracks (no commands) are closer to the truth with the estimate than with
// the configured 2 mm (a second model, estimation off, fed the same frames).
TEST(WorldModelAccuracy, EachCamerasRobotNoiseIsEstimatedAndTheFiltersUseIt) {
  sim::RealismConfig blurred = sim::RealismConfig::realistic();
  blurred.robot_position_stddev = 0.004;
  blurred.robot_orientation_stddev = 0.02;
  SimHarness h({.robots_per_team = 6, .realism = blurred, .seed = 11});
  WorldModelConfig configured_only;
  configured_only.detection_noise.estimate = false;
  WorldModel fixed(configured_only);
  fixed.on_geometry(testing::from_sim(h.sim().geometry()));
  Rms raw, estimated, assumed;
  time::Timestamp t_cmd;
  const time::Timestamp start = h.now();
  auto drive = [&](SimHarness& harness) {
    if (harness.now() < t_cmd) return;
    t_cmd = harness.now() + 10ms;
    const double t = time::to_seconds(harness.now() - start);
    std::vector<sim::RobotCommandFor> commands;
    for (std::uint32_t id = 0; id < 6; ++id) commands.push_back({id, testing::curve_command(t, id)});
    harness.command(TeamColor::kYellow, commands, false);
  };
  h.run(8s, drive, [&](const sim::DetectionFrame& frame) {
    fixed.on_detection(testing::from_sim(frame), h.now());
    if (time::to_seconds(frame.capture_time - start) < 2.0) return;
    const WorldState with_estimate = h.model().state_at_vision_time(frame.capture_time);
    const WorldState with_config = fixed.state_at_vision_time(frame.capture_time);
    for (const auto& d : frame.robots_yellow) {
      const sim::RobotState* r = find_robot(h.truth(frame.capture_time), TeamColor::kYellow, d.robot_id);
      const RobotState* a = find_state(with_estimate.enemy, d.robot_id);
      const RobotState* b = find_state(with_config.enemy, d.robot_id);
      ASSERT_TRUE(r && a && b);
      raw.add((Vec2(d.x, d.y) - r->position).norm());
      estimated.add((a->position - r->position).norm());
      assumed.add((b->position - r->position).norm());
    }
  });
  const auto estimates = h.model().detection_noise().estimates();
  ASSERT_EQ(estimates.size(), 4u);
  for (const auto& camera : estimates) {
    std::printf("[WorldModel] camera %u (4 mm, 20 mrad; config 2 mm, 10 mrad): %llu residuals, estimated %.2f mm, "
                "%.1f mrad\n",
                camera.camera_id, static_cast<unsigned long long>(camera.samples),
                camera.noise.position_stddev * 1e3, camera.noise.orientation_stddev * 1e3);
    EXPECT_NEAR(camera.noise.position_stddev, 0.004, 0.0004);
    EXPECT_NEAR(camera.noise.orientation_stddev, 0.02, 0.002);
  }
  std::printf("[WorldModel] enemies under 4 mm vision (config 2 mm): raw %.2f mm; filtered %.2f mm with the "
              "estimated noise (%.0f%% lower), %.2f mm with the configured (%.0f%% lower)\n",
              raw.value() * 1e3, estimated.value() * 1e3, 100 * (1 - estimated.value() / raw.value()),
              assumed.value() * 1e3, 100 * (1 - assumed.value() / raw.value()));
  EXPECT_LT(estimated.value(), 0.85 * assumed.value());
}

// Robots driven the way a planner drives them: each follows a smooth path inside the field, its global
// velocity re-aimed at 100 Hz (feed-forward plus a position term, sent as LOCAL commands turned by the
// robot's heading) while it spins on its own schedule; robots pass each other closely now and then.
TEST(WorldModelAccuracy, PlannerDrivenRobotsPositionRmsAtLeastHalfOfRawForOurs) {
  SimHarness h({.robots_per_team = 6, .seed = 12});
  Rms raw_pos, filt_pos, enemy_raw, enemy_filt, filt_vel;
  std::vector<EnemySample> enemy_samples;
  time::Timestamp t_cmd;
  const time::Timestamp start = h.now();
  auto drive = [&](SimHarness& harness) {
    if (harness.now() < t_cmd) return;
    t_cmd = harness.now() + 10ms;
    const double t = time::to_seconds(harness.now() - start);
    const sim::WorldSnapshot& now = harness.sim().snapshot();
    for (TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) {
      std::vector<sim::RobotCommandFor> commands;
      for (std::uint32_t id = 0; id < 6; ++id) {
        const double phase = id + (team == TeamColor::kYellow ? 0.5 : 0);
        const double k = static_cast<double>(id);
        const Vec2 centre((team == TeamColor::kBlue ? -3.0 : 3.0) + (id % 2 == 0 ? -1.2 : 1.2), -3.0 + 1.2 * k);
        const double ax = 1.8, ay = 0.5, wx = 0.55 + 0.05 * k, wy = 1.1 + 0.07 * k;
        const Vec2 target = centre + Vec2(ax * std::sin(wx * t + phase), ay * std::sin(wy * t + 2 * phase));
        const Vec2 feed_forward(ax * wx * std::cos(wx * t + phase), ay * wy * std::cos(wy * t + 2 * phase));
        const sim::RobotState* robot = find_robot(now, team, id);
        const Vec2 global = feed_forward + 3.0 * (target - robot->position);
        const double c = std::cos(robot->orientation), s = std::sin(robot->orientation);
        commands.push_back({id, local(c * global.x() + s * global.y(), -s * global.x() + c * global.y(),
                                      2.0 * std::sin(0.7 * t + 2 * phase))});
      }
      harness.command(team, commands, team == TeamColor::kBlue);
    }
  };
  h.run(8s, drive, [&](const sim::DetectionFrame& frame) {
    const double t = time::to_seconds(frame.capture_time - start);
    const sim::WorldSnapshot& truth = h.truth(frame.capture_time);
    add_enemy_samples(frame, truth, t, enemy_samples);
    if (t < 1.0) return;  // robots converge onto their paths
    const WorldState world = h.model().state_at_vision_time(frame.capture_time);
    for (TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) {
      const auto& detections = team == TeamColor::kBlue ? frame.robots_blue : frame.robots_yellow;
      const auto& states = team == TeamColor::kBlue ? world.friendly : world.enemy;
      for (const auto& d : detections) {
        const sim::RobotState* r = find_robot(truth, team, d.robot_id);
        const RobotState* s = find_state(states, d.robot_id);
        ASSERT_NE(r, nullptr);
        ASSERT_NE(s, nullptr);
        (team == TeamColor::kBlue ? raw_pos : enemy_raw).add((Vec2(d.x, d.y) - r->position).norm());
        (team == TeamColor::kBlue ? filt_pos : enemy_filt).add((s->position - r->position).norm());
        if (team == TeamColor::kBlue) filt_vel.add((s->velocity - r->velocity).norm());
      }
    }
  });
  const PolynomialFit reference = best_polynomial_fit(enemy_samples, 1.0);
  const double enemy_reduction = 100 * (1 - enemy_filt.value() / enemy_raw.value());
  std::printf("[WorldModel] planner-driven robots (realistic, %zu samples): ours position RMS raw %.2f mm, filtered "
              "%.2f mm (%.0f%% lower), velocity RMS %.3f m/s; enemies raw %.2f mm, filtered %.2f mm (%.0f%% lower; "
              "best causal polynomial fit %.0f%%, degree %d, %.2f s window)\n",
              raw_pos.n, raw_pos.value() * 1e3, filt_pos.value() * 1e3, 100 * (1 - filt_pos.value() / raw_pos.value()),
              filt_vel.value(), enemy_raw.value() * 1e3, enemy_filt.value() * 1e3, enemy_reduction,
              reference.reduction_pct, reference.degree, reference.window);
  EXPECT_GT(raw_pos.n, 1000u);
  EXPECT_LE(filt_pos.value(), 0.5 * raw_pos.value());      // measured 56 % lower (seed 12)
  // Enemies: measured 43 % (41-42 % at seeds 3 and 7), guarded at 35 %. The best causal polynomial fit over any
  // window (chosen with hindsight) reaches 37 %; robots saturate their acceleration when they fall behind
  // their paths or touch each other, and even a fit told by the truth where the acceleration jumps gets
  // 40 % (measured offline).
  EXPECT_LE(enemy_filt.value(), 0.65 * enemy_raw.value());
  EXPECT_GT(enemy_reduction, reference.reduction_pct + 2);
}

// The ball slides and rolls across the field, stops, and a robot kicks it.
TEST(WorldModelAccuracy, BallPositionRmsAtLeastHalfOfRawWhileRollingAndKicked) {
  SimHarness h({.robots_per_team = 1, .seed = 5});
  sim::ControlRequest setup;
  setup.ball = sim::BallTeleport{.x = -3.0, .y = -1.0, .vx = 2.0, .vy = 0.5};
  setup.robots.push_back({.key = {TeamColor::kBlue, 0}, .x = -4.0, .y = 3.0, .orientation = 0.0});
  setup.robots.push_back({.key = {TeamColor::kYellow, 0}, .x = 4.0, .y = 3.0, .orientation = 0.0});
  ASSERT_TRUE(h.sim().apply(setup).empty());
  BallErrors errors;
  bool kicking = false;
  const time::Timestamp start = h.now();
  auto script = [&](SimHarness& harness) {
    if (!kicking && time::to_seconds(harness.now() - start) > 5.0) {
      kicking = true;
      const auto ball = harness.sim().snapshot().ball.position;
      sim::ControlRequest place;
      place.robots.push_back({.key = {TeamColor::kBlue, 0}, .x = ball.x() - 0.25, .y = ball.y(), .orientation = 0.0});
      harness.sim().apply(place);
      harness.command(TeamColor::kBlue, {{0, local(0.8, 0, 0, 4.0)}}, true);
    }
  };
  h.run(8s, script, [&](const sim::DetectionFrame& frame) {
    errors.add_after(h, frame, start + 300ms);
  });
  const auto& [raw_pos, filt_pos, filt_vel, naive_vel, last_raw] = errors;
  std::printf("[WorldModel] ball (realistic, rolling + kick, %zu samples): position RMS raw %.2f mm, filtered "
              "%.2f mm (%.0f%% lower); velocity RMS filtered %.3f m/s vs raw finite difference %.3f m/s; "
              "kicks detected %llu\n",
              raw_pos.n, raw_pos.value() * 1e3, filt_pos.value() * 1e3,
              100 * (1 - filt_pos.value() / raw_pos.value()), filt_vel.value(), naive_vel.value(),
              static_cast<unsigned long long>(h.model().counters().kicks_detected));
  EXPECT_GT(raw_pos.n, 300u);
  // The design's target: >= 50% lower (measured 66%, seed 5).
  EXPECT_LE(filt_pos.value(), 0.5 * raw_pos.value());
  EXPECT_LE(filt_vel.value(), 0.5 * naive_vel.value());
  EXPECT_GE(h.model().counters().kicks_detected, 1u);
}

// Passes: three of our robots kick the ball to each other (2 to 5.5 m/s) past three standing enemies;
// the ball bounces off robots and walls, slides, rolls and is kicked again, never for long on its own.
TEST(WorldModelAccuracy, BallPositionRmsAtLeastHalfOfRawWhilePassedBetweenRobots) {
  SimHarness h({.robots_per_team = 3, .seed = 21});
  sim::ControlRequest setup;
  setup.ball = sim::BallTeleport{.x = -2.0, .y = -1.0};
  setup.robots.push_back({.key = {TeamColor::kBlue, 0}, .x = -2.25, .y = -1.0, .orientation = 0.0});
  setup.robots.push_back({.key = {TeamColor::kBlue, 1}, .x = 1.0, .y = 1.2, .orientation = 3.14});
  setup.robots.push_back({.key = {TeamColor::kBlue, 2}, .x = 1.5, .y = -2.0, .orientation = 2.0});
  setup.robots.push_back({.key = {TeamColor::kYellow, 0}, .x = -0.5, .y = 0.13, .orientation = 0.0});
  setup.robots.push_back({.key = {TeamColor::kYellow, 1}, .x = 1.3, .y = -0.3, .orientation = 1.0});
  setup.robots.push_back({.key = {TeamColor::kYellow, 2}, .x = -0.3, .y = -1.65, .orientation = 2.0});
  ASSERT_TRUE(h.sim().apply(setup).empty());
  const time::Timestamp start = h.now();
  const double kick_speeds[] = {4.0, 2.5, 5.5, 3.0, 4.5, 2.0};
  bool kicking = false;
  int kicks = 0, true_kicks = 0;
  double last_kick = -10, previous_speed = 0;
  auto all_blue = [](int kicker, double kick_speed) {
    std::vector<sim::RobotCommandFor> commands;
    for (std::uint32_t id = 0; id < 3; ++id) {
      commands.push_back({id, static_cast<int>(id) == kicker ? local(0.6, 0, 0, kick_speed) : local(0, 0, 0)});
    }
    return commands;
  };
  // When the ball is slow (or 3 s after the last kick), the blue robot nearest to it is put 0.2 m behind
  // it, facing a team mate, and drives into it with its kicker armed; it stops once the ball is away.
  auto script = [&](SimHarness& harness) {
    const double t = time::to_seconds(harness.now() - start);
    const sim::WorldSnapshot& world = harness.sim().snapshot();
    const Vec2 ball = world.ball.position.head<2>();
    const double speed = world.ball.velocity.head<2>().norm();
    if (speed > previous_speed + 1.0) ++true_kicks;  // within one 2 ms step: a kick
    previous_speed = speed;
    if (kicking && (speed > 1.0 || t - last_kick > 1.5)) {
      kicking = false;
      harness.command(TeamColor::kBlue, all_blue(-1, 0), true);
    }
    if (kicking || t - last_kick < 1.0 || (speed >= 0.15 && t - last_kick < 3.0)) return;
    const sim::RobotState* kicker = nullptr;
    for (const auto& r : world.robots) {
      if (r.key.team == TeamColor::kBlue && (!kicker || (r.position - ball).norm() < (kicker->position - ball).norm())) {
        kicker = &r;
      }
    }
    const std::uint32_t target_id = (kicker->key.id + 1 + static_cast<std::uint32_t>(kicks % 2)) % 3;
    const Vec2 dir = (find_robot(world, TeamColor::kBlue, target_id)->position - ball).normalized();
    const Vec2 p = ball - 0.2 * dir;
    const int kicker_id = static_cast<int>(kicker->key.id);
    sim::ControlRequest place;
    place.robots.push_back({.key = {TeamColor::kBlue, kicker->key.id}, .x = p.x(), .y = p.y(),
                            .orientation = std::atan2(dir.y(), dir.x())});
    harness.sim().apply(place);
    harness.command(TeamColor::kBlue, all_blue(kicker_id, kick_speeds[kicks % 6]), true);
    kicking = true;
    last_kick = t;
    ++kicks;
  };
  BallErrors errors;
  h.run(14s, script, [&](const sim::DetectionFrame& frame) {
    errors.add_after(h, frame, start + 300ms);
  });
  const auto& [raw_pos, filt_pos, filt_vel, naive_vel, last_raw] = errors;
  std::printf("[WorldModel] ball passed between robots (realistic, %d kicks, %zu samples): position RMS raw %.2f mm, "
              "filtered %.2f mm (%.0f%% lower); velocity RMS filtered %.3f m/s vs raw finite difference %.3f m/s; "
              "kicks detected %llu\n",
              true_kicks, raw_pos.n, raw_pos.value() * 1e3, filt_pos.value() * 1e3,
              100 * (1 - filt_pos.value() / raw_pos.value()), filt_vel.value(), naive_vel.value(),
              static_cast<unsigned long long>(h.model().counters().kicks_detected));
  EXPECT_GT(raw_pos.n, 1000u);
  EXPECT_GE(true_kicks, 5);
  // The design's target: >= 50% lower (measured 59%, seed 21; 56-59% over seeds 21-24).
  EXPECT_LE(filt_pos.value(), 0.5 * raw_pos.value());
  EXPECT_LE(filt_vel.value(), 0.5 * naive_vel.value());
  EXPECT_GE(h.model().counters().kicks_detected, static_cast<std::uint64_t>(true_kicks));
}

TEST(WorldModelAccuracy, KickIsDetectedWithinThreeFramesWithSpeedAndDirection) {
  SimHarness h({.robots_per_team = 1, .seed = 3});
  sim::ControlRequest setup;
  setup.ball = sim::BallTeleport{.x = 0.25 * std::cos(0.3), .y = 0.5 + 0.25 * std::sin(0.3)};
  setup.robots.push_back({.key = {TeamColor::kBlue, 0}, .x = 0.0, .y = 0.5, .orientation = 0.3});
  setup.robots.push_back({.key = {TeamColor::kYellow, 0}, .x = 4.0, .y = 3.0, .orientation = 0.0});
  ASSERT_TRUE(h.sim().apply(setup).empty());
  h.run(300ms, nullptr, nullptr);  // filters settle
  ASSERT_EQ(h.model().counters().kicks_detected, 0u);
  h.command(TeamColor::kBlue, {{0, local(0.6, 0, 0, 5.0)}}, true);
  std::optional<time::Timestamp> detected_capture;
  std::vector<time::Timestamp> ball_frames;
  h.run(1s, nullptr, [&](const sim::DetectionFrame& frame) {
    if (!frame.balls.empty()) ball_frames.push_back(frame.capture_time);
    if (!detected_capture && h.model().counters().kicks_detected > 0) detected_capture = frame.capture_time;
  });
  ASSERT_TRUE(detected_capture.has_value());
  // True kick: the first instant the ball is faster than 1 m/s.
  std::optional<time::Timestamp> kicked;
  for (time::Timestamp t = h.now() - 1s; t < h.now(); t += SimHarness::kStep) {
    if (h.truth(t).ball.velocity.head<2>().norm() > 1.0) {
      kicked = t;
      break;
    }
  }
  ASSERT_TRUE(kicked.has_value());
  int frames_after = 0;
  for (time::Timestamp t : ball_frames) {
    if (t >= *kicked && t <= *detected_capture) ++frames_after;
  }
  const auto kick = h.model().last_kick();
  ASSERT_TRUE(kick.has_value());
  const Vec2 true_velocity = h.truth(*detected_capture).ball.velocity.head<2>();
  std::printf("[WorldModel] kick detection: %.1f ms after the kick, %d ball frames; speed %.2f m/s (true %.2f), "
              "direction error %.3f rad\n",
              time::to_seconds(*detected_capture - *kicked) * 1e3, frames_after, kick->speed, true_velocity.norm(),
              std::abs(geom::Angle::from_radians(std::atan2(kick->velocity.y(), kick->velocity.x()) -
                                                 std::atan2(true_velocity.y(), true_velocity.x()))
                           .radians()));
  EXPECT_LE(frames_after, 3);
  EXPECT_EQ(h.model().counters().chips_detected, 0u) << "a flat kick is not a chip";
  EXPECT_NEAR(kick->speed, true_velocity.norm(), 0.6);
  EXPECT_NEAR(std::atan2(kick->velocity.y(), kick->velocity.x()), 0.3, 0.1);
}

// Detections of a ball rolling past a robot vanish for 250 ms (hidden behind it).
TEST(WorldModelAccuracy, OcclusionKeepsAPlausiblePredictionAndReappearsWithoutAJump) {
  SimHarness h({.robots_per_team = 1, .seed = 9});
  sim::ControlRequest setup;
  setup.ball = sim::BallTeleport{.x = -1.0, .y = 0.0, .vx = 1.5, .vy = 0.0, .roll = true};
  setup.robots.push_back({.key = {TeamColor::kBlue, 0}, .x = 0.0, .y = 0.2, .orientation = 0.0});
  setup.robots.push_back({.key = {TeamColor::kYellow, 0}, .x = 4.0, .y = 3.0, .orientation = 0.0});
  ASSERT_TRUE(h.sim().apply(setup).empty());
  const time::Timestamp start = h.now();
  double max_hidden_error = 0, max_step_after = 0;
  std::optional<Vec2> previous;
  bool was_hidden = false;
  int frames_after = 0;
  // Hide by dropping ball detections in the model's input: wrap the harness loop by hand.
  while (h.now() < start + 1500ms) {
    sim::StepOutput out = h.sim().step(SimHarness::kStep);
    for (const auto& frame : out.frames) {
      DetectionFrame f = testing::from_sim(frame);
      const double t = time::to_seconds(frame.capture_time - start);
      const bool hidden = t > 0.55 && t < 0.8;
      if (hidden) f.balls.clear();
      h.model().on_detection(f, h.now());
      const WorldState world = h.model().state_at_vision_time(frame.capture_time);
      const Vec2 ball = world.ball.position.head<2>();
      const Vec2 truth = h.sim().snapshot().ball.position.head<2>();  // within 2 ms of the capture + delay
      if (hidden) {
        was_hidden = true;
        max_hidden_error = std::max(max_hidden_error, (ball - (truth - Vec2(h.sim().snapshot().ball.velocity.x(), 0) *
                                                                time::to_seconds(h.now() - frame.capture_time)))
                                                          .norm());
      } else if (was_hidden && frames_after < 20 && previous) {
        ++frames_after;
        max_step_after = std::max(max_step_after, (ball - *previous).norm());
      }
      previous = ball;
    }
  }
  std::printf("[WorldModel] occlusion: max error while hidden (250 ms) %.1f mm; max frame-to-frame step after "
              "reappearing %.1f mm\n", max_hidden_error * 1e3, max_step_after * 1e3);
  EXPECT_TRUE(was_hidden);
  EXPECT_LT(max_hidden_error, 0.05);
  EXPECT_LT(max_step_after, 0.03);  // 1.4 m/s * 3.3 ms between cameras + noise, no jump
}

// A robot standing where two (four) camera views overlap: one track, no jitter between cameras.
TEST(WorldModelAccuracy, TwoCameraOverlapGivesOneTrackWithoutJitter) {
  SimHarness h({.robots_per_team = 1, .seed = 4});
  sim::ControlRequest setup;
  setup.robots.push_back({.key = {TeamColor::kBlue, 0}, .x = 0.0, .y = 1.5, .orientation = 0.0});
  setup.robots.push_back({.key = {TeamColor::kYellow, 0}, .x = 0.05, .y = -0.05, .orientation = 1.0});
  ASSERT_TRUE(h.sim().apply(setup).empty());
  std::set<std::uint32_t> cameras;
  Rms raw, filtered;
  std::optional<Vec2> previous;
  double max_step = 0;
  h.run(300ms, nullptr, nullptr);
  h.run(1500ms, nullptr, [&](const sim::DetectionFrame& frame) {
    for (const auto& d : frame.robots_blue) {
      cameras.insert(frame.camera_id);
      const Vec2 truth = find_robot(h.truth(frame.capture_time), TeamColor::kBlue, 0)->position;
      const WorldState world = h.model().state_at_vision_time(frame.capture_time);
      ASSERT_EQ(world.friendly.size(), 1u);
      raw.add((Vec2(d.x, d.y) - truth).norm());
      filtered.add((world.friendly[0].position - truth).norm());
      if (previous) max_step = std::max(max_step, (world.friendly[0].position - *previous).norm());
      previous = world.friendly[0].position;
    }
  });
  std::printf("[WorldModel] overlap: robot seen by %zu cameras; raw RMS %.2f mm, filtered %.2f mm, max step "
              "between frames %.2f mm\n", cameras.size(), raw.value() * 1e3, filtered.value() * 1e3, max_step * 1e3);
  EXPECT_GE(cameras.size(), 2u);
  EXPECT_EQ(h.model().counters().tracks_created, 2u);
  EXPECT_LT(max_step, 0.003);                       // below one raw sigma-norm (2.8 mm): no camera jitter
  EXPECT_LE(filtered.value(), 0.6 * raw.value());   // measured 49% lower (seed 4)
}

// Competition vision: each camera's calibration is 2 cm off, so a robot crossing the overlaps jumps between
// the cameras' views. With the camera alignment on, the cameras' estimated errors are removed: the track
// is smoother and closer to the consensus of the cameras.
TEST(WorldModelAccuracy, CameraAlignmentRemovesTheJumpsBetweenMiscalibratedCameras) {
  auto run = [](bool align) {
    WorldModelConfig config;
    config.align_cameras = align;
    SimHarness h({.robots_per_team = 6, .realism = sim::RealismConfig::competition(), .seed = 4}, config);
    time::Timestamp t_cmd;
    const time::Timestamp start = h.now();
    Rms step_jitter;
    std::map<std::uint32_t, std::pair<Vec2, Vec2>> last;  // id -> filtered position, velocity
    time::Timestamp last_capture;
    auto drive = [&](SimHarness& harness) {
      if (harness.now() < t_cmd) return;
      t_cmd = harness.now() + 10ms;
      const double t = time::to_seconds(harness.now() - start);
      const sim::WorldSnapshot& now = harness.sim().snapshot();
      std::vector<sim::RobotCommandFor> commands;
      for (std::uint32_t id = 0; id < 6; ++id) {
        // Slow ellipses across the centre, where the four cameras overlap.
        const double k = static_cast<double>(id);
        const Vec2 target(1.5 * std::cos(0.4 * t + k), 1.0 * std::sin(0.4 * t + k));
        const Vec2 feed_forward(-0.6 * std::sin(0.4 * t + k), 0.4 * std::cos(0.4 * t + k));
        const sim::RobotState* robot = find_robot(now, TeamColor::kBlue, id);
        const Vec2 global = feed_forward + 3.0 * (target - robot->position);
        const double c = std::cos(robot->orientation), s = std::sin(robot->orientation);
        commands.push_back({id, local(c * global.x() + s * global.y(), -s * global.x() + c * global.y(), 0)});
      }
      harness.command(TeamColor::kBlue, commands, true);
    };
    h.run(20s, drive, [&](const sim::DetectionFrame& frame) {
      if (time::to_seconds(frame.capture_time - start) < 10.0) return;  // calibrated by then
      const WorldState world = h.model().state_at_vision_time(frame.capture_time);
      const double dt = time::to_seconds(frame.capture_time - last_capture);
      for (const RobotState& r : world.friendly) {
        // Jitter: the change of the filtered position beyond what its velocity explains, per frame.
        auto it = last.find(r.id);
        if (it != last.end() && dt > 0 && dt < 0.02) {
          step_jitter.add((r.position - it->second.first - it->second.second * dt).norm());
        }
        last[r.id] = {r.position, r.velocity};
      }
      last_capture = frame.capture_time;
    });
    return std::make_pair(step_jitter.value(), h.model().camera_alignment().offset(0).calibrated);
  };
  const auto [without, calibrated_without] = run(false);
  const auto [with, calibrated_with] = run(true);
  std::printf("[WorldModel] competition vision (2 cm calibration errors): frame-to-frame step RMS of our tracks "
              "%.2f mm without camera alignment, %.2f mm with\n", without * 1e3, with * 1e3);
  EXPECT_TRUE(calibrated_with);
  EXPECT_LT(with, 0.8 * without);
}

// A chip kick across camera boundaries: the post-kick detections are projections of a flying ball, which
// the model recognises as a chip and reconstructs in 3D (with the cameras' positions) until it lands.
TEST(WorldModelAccuracy, ChipKickIsReconstructedInThreeDimensionsUntilItLands) {
  SimHarness h({.robots_per_team = 1, .seed = 21});
  sim::ControlRequest setup;
  setup.ball = sim::BallTeleport{.x = -1.0 + 0.1, .y = 0.3};
  setup.robots.push_back({.key = {TeamColor::kBlue, 0}, .x = -1.0, .y = 0.3, .orientation = 0.0});
  setup.robots.push_back({.key = {TeamColor::kYellow, 0}, .x = 4.0, .y = 3.0, .orientation = 0.0});
  ASSERT_TRUE(h.sim().apply(setup).empty());
  h.run(300ms, nullptr, nullptr);
  sim::RobotCommand chip = local(0.3, 0, 0, 4.0);
  chip.kick_angle = 0.8;  // rad: about 2.8 m/s up, 2.8 m/s forward -> ~0.4 m apex, ~1.6 m flight
  h.command(TeamColor::kBlue, {{0, chip}}, true);
  Rms flight_error;
  std::vector<double> errors;  // per airborne frame, in order
  double max_height_seen = 0;
  bool flagged_airborne = false;
  h.run(1500ms, [&](SimHarness& harness) {
    if (harness.sim().snapshot().ball.velocity.norm() > 1.0) harness.command(TeamColor::kBlue, {{0, local(0, 0, 0)}}, true);
  }, [&](const sim::DetectionFrame& frame) {
    const WorldState world = h.model().state_at_vision_time(frame.capture_time);
    if (!world.ball.airborne) return;
    flagged_airborne = true;
    const Vec3 truth = h.truth(frame.capture_time).ball.position;
    flight_error.add((world.ball.position - truth).norm());  // blue on the negative half: frames agree
    max_height_seen = std::max(max_height_seen, world.ball.position.z());
    errors.push_back((world.ball.position - truth).norm());
  });
  Rms late_error;  // the second half of the flight: a second camera sees it by then (overlap at x = 0)
  for (std::size_t i = errors.size() / 2; i < errors.size(); ++i) late_error.add(errors[i]);
  std::printf("[WorldModel] chip: %llu chip(s) detected; 3D position RMS while airborne %.1f mm over %zu frames "
              "(%.1f mm in the second half, seen by two cameras); highest reconstructed centre %.2f m\n",
              static_cast<unsigned long long>(h.model().counters().chips_detected), flight_error.value() * 1e3,
              flight_error.n, late_error.value() * 1e3, max_height_seen);
  EXPECT_EQ(h.model().counters().chips_detected, 1u);
  EXPECT_TRUE(flagged_airborne);
  EXPECT_GT(flight_error.n, 10u);
  // Seen by one camera, a ball rising along that camera's ray barely moves in its image: height and
  // horizontal speed are hard to separate until a second camera sees it (measured 94 mm RMS overall,
  // 2-5 mm once two cameras see it).
  EXPECT_LT(flight_error.value(), 0.15);
  EXPECT_GT(late_error.n, 5u);
  EXPECT_LT(late_error.value(), 0.02);
  EXPECT_GT(max_height_seen, 0.3);  // true apex 0.44 m
}

// An opponent dribbles the ball along a curve and its body hides the ball from the cameras (no robot
// feedback for opponents): the ball stays at that robot's dribbler instead of rolling on straight.
TEST(WorldModelAccuracy, HiddenBallAtAnOpponentsDribblerMovesWithThatRobot) {
  // Max error while hidden, and the ball's distance from the robot centre at the end.
  auto run = [](double carried_ball_timeout) {
    WorldModelConfig config;
    config.carried_ball_timeout = carried_ball_timeout;
    SimHarness h({.robots_per_team = 1, .seed = 8}, config);
    sim::ControlRequest setup;
    setup.robots.push_back({.key = {TeamColor::kYellow, 0}, .x = 0.0, .y = 0.0, .orientation = 0.0});
    setup.robots.push_back({.key = {TeamColor::kBlue, 0}, .x = -4.0, .y = 3.0, .orientation = 0.0});
    setup.ball = sim::BallTeleport{.x = 0.11, .y = 0.0};
    EXPECT_TRUE(h.sim().apply(setup).empty());
    sim::RobotCommand dribble = local(0.8, 0, 1.5);
    dribble.dribbler_rpm = 10000;
    h.command(TeamColor::kYellow, {{0, dribble}}, false);
    const time::Timestamp start = h.now();
    double max_hidden_error = 0;
    while (h.now() < start + 1200ms) {
      sim::StepOutput out = h.sim().step(SimHarness::kStep);
      for (const auto& frame : out.frames) {
        DetectionFrame f = testing::from_sim(frame);
        const double t = time::to_seconds(frame.capture_time - start);
        const bool hidden = t > 0.8 && t < 1.1;  // the robot turns ~0.45 rad meanwhile
        if (hidden) f.balls.clear();
        h.model().on_detection(f, h.now());
        if (!hidden) continue;
        const WorldState world = h.model().state_at_vision_time(frame.capture_time);
        const sim::WorldSnapshot& now = h.sim().snapshot();  // within 2 ms of the capture + delay
        const Vec2 truth = now.ball.position.head<2>() -
                           now.ball.velocity.head<2>() * time::to_seconds(h.now() - frame.capture_time);
        // The model's frame is blue's, with blue on the negative half: it equals the vision frame.
        max_hidden_error = std::max(max_hidden_error, (world.ball.position.head<2>() - truth).norm());
      }
    }
    const sim::WorldSnapshot& end = h.sim().snapshot();
    return std::make_pair(max_hidden_error,
                          (end.ball.position.head<2>() - find_robot(end, TeamColor::kYellow, 0)->position).norm());
  };
  const auto [carried, ball_to_robot] = run(1.0);
  const auto [rolled_on, ignored] = run(0.0);
  std::printf("[WorldModel] opponent dribbling on a curve, ball hidden 300 ms: max error %.1f mm moving it with the "
              "robot, %.1f mm predicting it on its own\n", carried * 1e3, rolled_on * 1e3);
  ASSERT_LT(ball_to_robot, 0.13) << "the simulated robot lost the ball";
  EXPECT_LT(carried, 0.03);
  EXPECT_LT(carried, 0.5 * rolled_on);
}

}  // namespace
}  // namespace ssl::wm
