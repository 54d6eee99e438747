// CommandDelayEstimator on synthetic motion: robots that follow their commands exactly `delay` late under
// the ramp of their limits (libs/domain/robot_motion.h), seen at 75 Hz with or without noise.
#include "services/world_model/core/command_delay.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "libs/domain/robot_motion.h"

namespace ssl::wm {
namespace {

using geom::Vec2;

struct Drive {
  double delay = 0.04;            // s, true
  double noise = 0;               // m, per axis
  bool changing_commands = true;  // false: one constant command
};

/// Four robots for `seconds`: commands at 100 Hz (a new random target velocity every 0.3 s per robot),
/// motion by the ramp (3 m/s^2 up, 4 down) from the command `delay` ago, detections at 75 Hz.
CommandDelayEstimator drive(const Drive& how, double seconds,
                            CommandDelayEstimator estimator = CommandDelayEstimator()) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> speed(-2.0, 2.0);
  std::normal_distribution<double> noise(0.0, 1.0);
  struct Robot {
    Vec2 target = Vec2(1.0, 0.0);
    std::vector<std::pair<double, Vec2>> sent;  // time, velocity
    Vec2 position = Vec2::Zero();
    Vec2 velocity = Vec2::Zero();
  };
  std::vector<Robot> robots(4);
  if (!how.changing_commands) {
    for (Robot& r : robots) r.velocity = r.target;
  }
  const double h = 0.001;
  double next_command = 0, next_frame = 0;
  const time::Timestamp start = time::Timestamp::from_seconds(1000);
  for (double t = 0; t < seconds; t += h) {
    for (std::uint32_t id = 0; id < robots.size(); ++id) {
      Robot& r = robots[id];
      if (t >= next_command) {
        if (how.changing_commands && std::fmod(t + 0.1 * id, 0.3) < 0.01) r.target = Vec2(speed(random), speed(random));
        r.sent.emplace_back(t, r.target);
        estimator.on_command(id, r.target, start + time::duration_from_seconds(t));
      }
      // Before its first command acts, a robot of a constant command already cruises at it.
      Vec2 aimed = how.changing_commands ? Vec2::Zero() : r.target;
      for (const auto& [at, v] : r.sent) {
        if (at <= t - how.delay) aimed = v;
      }
      r.velocity = ramp_velocity(r.velocity, aimed, 3.0, 4.0, h);
      r.position += r.velocity * h;
    }
    if (t >= next_command) next_command += 0.01;
    if (t >= next_frame) {
      const time::Timestamp capture = start + time::duration_from_seconds(t);
      for (std::uint32_t id = 0; id < robots.size(); ++id) {
        const Vec2 seen = robots[id].position + how.noise * Vec2(noise(random), noise(random));
        estimator.on_position(id, seen, 0.0, capture);  // heading 0: local commands are field velocities
      }
      estimator.update(capture);
      next_frame += 1.0 / 75;
    }
  }
  return estimator;
}

TEST(CommandDelayEstimator, FindsTheDelayOfRobotsThatFollowTheirCommandsLate) {
  for (double delay : {0.0, 0.025, 0.04, 0.085, 0.15}) {
    const CommandDelayEstimator estimator = drive({.delay = delay}, 4.0);
    ASSERT_TRUE(estimator.delay()) << delay;
    EXPECT_NEAR(*estimator.delay(), delay, 0.003) << delay;
  }
}

TEST(CommandDelayEstimator, FindsItUnderTwoMillimetresOfVisionNoise) {
  const CommandDelayEstimator estimator = drive({.delay = 0.06, .noise = 0.002}, 6.0);
  ASSERT_TRUE(estimator.delay());
  EXPECT_NEAR(*estimator.delay(), 0.06, 0.006);
}

TEST(CommandDelayEstimator, GivesNoEstimateWhileTheRobotsCruiseAtOneCommand) {
  // Robots cruising at one constant command: every delay explains the cruise equally well.
  const CommandDelayEstimator estimator = drive({.delay = 0.05, .changing_commands = false}, 6.0);
  EXPECT_FALSE(estimator.delay());
}

TEST(CommandDelayEstimator, GivesNothingWhenDisabledAndRejectsABadGrid) {
  EXPECT_FALSE(drive({}, 3.0, CommandDelayEstimator(CommandDelayParams{.estimate = false})).delay());
  EXPECT_THROW(CommandDelayEstimator(CommandDelayParams{.min_delay = 0.1, .max_delay = 0.05}), std::invalid_argument);
  EXPECT_THROW(CommandDelayEstimator(CommandDelayParams{.resolution = 0}), std::invalid_argument);
}

}  // namespace
}  // namespace ssl::wm
