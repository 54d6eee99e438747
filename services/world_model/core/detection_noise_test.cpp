// DetectionNoiseEstimator on synthetic detections (seeded Gaussian noise): it finds each camera's robot
// position and heading noise from the detections of moving robots, keeps the configured noise until it has
// enough residuals, ignores collisions and gaps, wraps headings, and stays within its bounds.
#include "services/world_model/core/detection_noise.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "libs/geometry/angle.h"

namespace ssl::wm {
namespace {

const time::Timestamp kStart = time::Timestamp::from_seconds(100.0);
constexpr double kFramePeriod = 1.0 / 75;
const DetectionNoise kConfigured{0.002, 0.01};

/// Robot `id` at frame `frame`: driving a circle of 1 m at 2 m/s (4 m/s^2 towards its centre), turning at
/// 2 rad/s, with Gaussian noise of the given standard deviations (m, rad) on x, y and the heading.
struct NoisyRobots {
  double position_stddev = 0.002;
  double orientation_stddev = 0.01;
  double heading_offset = 0;  // rad, added to the true heading (near pi: wrapping)
  std::mt19937 rng{11};

  RobotDetection detect(std::uint32_t id, int frame) {
    std::normal_distribution<double> unit(0, 1);
    const double t = frame * kFramePeriod;
    const double phase = id * 0.7;
    const Vec2 truth(std::cos(2 * t + phase), std::sin(2 * t + phase));
    const double heading = geom::Angle::from_radians(heading_offset + 2 * t + phase).radians();
    return {.id = id,
            .position = truth + position_stddev * Vec2(unit(rng), unit(rng)),
            .orientation = geom::Angle::from_radians(heading + orientation_stddev * unit(rng)).radians(),
            .has_orientation = true};
  }
};

time::Timestamp frame_time(int frame) { return kStart + time::duration_from_seconds(frame * kFramePeriod); }

/// Feeds `frames` frames of 6 robots seen by `camera`.
void feed(DetectionNoiseEstimator& estimator, std::uint32_t camera, NoisyRobots& robots, int frames,
          int first_frame = 0) {
  for (int f = first_frame; f < first_frame + frames; ++f) {
    for (std::uint32_t id = 0; id < 6; ++id) {
      estimator.observe(camera, TeamColor::kYellow, robots.detect(id, f), frame_time(f));
    }
  }
}

TEST(DetectionNoise, FindsTheNoiseOfEachCameraFromMovingRobots) {
  DetectionNoiseEstimator estimator({}, kConfigured);
  NoisyRobots sharp{.position_stddev = 0.0015, .orientation_stddev = 0.008};
  NoisyRobots blurred{.position_stddev = 0.005, .orientation_stddev = 0.03};
  feed(estimator, 0, sharp, 600);
  feed(estimator, 1, blurred, 600);
  const DetectionNoise zero = estimator.noise(0);
  const DetectionNoise one = estimator.noise(1);
  std::printf("[DetectionNoise] camera 0 (1.5 mm, 8 mrad): %.2f mm, %.1f mrad; camera 1 (5 mm, 30 mrad): %.2f mm, "
              "%.1f mrad\n",
              zero.position_stddev * 1e3, zero.orientation_stddev * 1e3, one.position_stddev * 1e3,
              one.orientation_stddev * 1e3);
  EXPECT_NEAR(zero.position_stddev, 0.0015, 0.0015 * 0.1);
  EXPECT_NEAR(zero.orientation_stddev, 0.008, 0.008 * 0.1);
  EXPECT_NEAR(one.position_stddev, 0.005, 0.005 * 0.1);
  EXPECT_NEAR(one.orientation_stddev, 0.03, 0.03 * 0.1);
  ASSERT_EQ(estimator.estimates().size(), 2u);
  EXPECT_EQ(estimator.estimates()[1].camera_id, 1u);
  EXPECT_EQ(estimator.estimates()[1].samples, 6u * (600 - 2));  // one residual per detection after two
}

TEST(DetectionNoise, KeepsTheConfiguredNoiseUntilACameraHasMinSamplesResiduals) {
  DetectionNoiseParams params;
  params.min_samples = 60;
  DetectionNoiseEstimator estimator(params, kConfigured);
  NoisyRobots robots{.position_stddev = 0.006};
  EXPECT_EQ(estimator.noise(0).position_stddev, kConfigured.position_stddev);  // never seen
  // 6 robots: their first two frames make no residual, each later frame 6. 11 frames: 54 residuals.
  feed(estimator, 0, robots, 11);
  EXPECT_EQ(estimator.estimates()[0].samples, 54u);
  EXPECT_EQ(estimator.noise(0).position_stddev, kConfigured.position_stddev);
  feed(estimator, 0, robots, 1, 11);  // 60
  EXPECT_GT(estimator.noise(0).position_stddev, kConfigured.position_stddev);
}

TEST(DetectionNoise, ACollisionOrATeleportDoesNotCountAsNoise) {
  DetectionNoiseEstimator clean({}, kConfigured);
  DetectionNoiseEstimator bumped({}, kConfigured);
  NoisyRobots a, b;  // the same seed: the same noise
  for (int f = 0; f < 900; ++f) {
    for (std::uint32_t id = 0; id < 6; ++id) {
      const RobotDetection d = a.detect(id, f);
      clean.observe(0, TeamColor::kBlue, d, frame_time(f));
      RobotDetection jumped = b.detect(id, f);
      if (f % 50 == 0) jumped.position += Vec2(0.3, 0);  // a robot jumps 30 cm for one frame
      bumped.observe(0, TeamColor::kBlue, jumped, frame_time(f));
    }
  }
  EXPECT_NEAR(bumped.noise(0).position_stddev, clean.noise(0).position_stddev,
              0.1 * clean.noise(0).position_stddev);
}

TEST(DetectionNoise, DetectionsFartherApartThanMaxSpanMakeNoResidual) {
  DetectionNoiseParams params;
  params.max_span = 0.05;
  DetectionNoiseEstimator estimator(params, kConfigured);
  NoisyRobots robots;
  // Every other frame dropped: 3 detections span 4 frame periods = 53 ms > 50 ms.
  for (int f = 0; f < 40; f += 2) estimator.observe(0, TeamColor::kBlue, robots.detect(1, f), frame_time(f));
  EXPECT_EQ(estimator.estimates()[0].samples, 0u);
  // Consecutive frames: 2 periods = 26.7 ms.
  for (int f = 40; f < 43; ++f) estimator.observe(0, TeamColor::kBlue, robots.detect(1, f), frame_time(f));
  EXPECT_EQ(estimator.estimates()[0].samples, 2u);  // (38, 40, 41) spans 40 ms; (40, 41, 42)
}

TEST(DetectionNoise, HeadingsAreWrappedAcrossPlusMinusPi) {
  DetectionNoiseEstimator estimator({}, kConfigured);
  NoisyRobots robots{.heading_offset = std::numbers::pi};  // the headings cross +-pi all the time
  feed(estimator, 0, robots, 600);
  EXPECT_NEAR(estimator.noise(0).orientation_stddev, 0.01, 0.001);
}

TEST(DetectionNoise, TheEstimateStaysWithinItsBoundsAndIsOffWhenDisabled) {
  DetectionNoiseEstimator bounded({}, kConfigured);  // factors 0.25 .. 4
  NoisyRobots wild{.position_stddev = 0.05};
  feed(bounded, 0, wild, 600);
  EXPECT_DOUBLE_EQ(bounded.noise(0).position_stddev, 4 * kConfigured.position_stddev);

  DetectionNoiseParams off;
  off.estimate = false;
  DetectionNoiseEstimator disabled(off, kConfigured);
  NoisyRobots blurred{.position_stddev = 0.005};
  feed(disabled, 0, blurred, 600);
  EXPECT_EQ(disabled.noise(0).position_stddev, kConfigured.position_stddev);
  EXPECT_TRUE(disabled.estimates().empty());
}

TEST(DetectionNoise, AnOutOfOrderFrameRestartsThatRobotsHistory) {
  DetectionNoiseEstimator estimator({}, kConfigured);
  NoisyRobots robots;
  for (int f = 0; f < 5; ++f) estimator.observe(0, TeamColor::kBlue, robots.detect(1, f), frame_time(f));
  EXPECT_EQ(estimator.estimates()[0].samples, 3u);
  // A repeated (older) frame restarts the history: neither it nor the next frame makes a residual.
  estimator.observe(0, TeamColor::kBlue, robots.detect(1, 3), frame_time(3));
  estimator.observe(0, TeamColor::kBlue, robots.detect(1, 5), frame_time(5));
  EXPECT_EQ(estimator.estimates()[0].samples, 3u);
  estimator.observe(0, TeamColor::kBlue, robots.detect(1, 6), frame_time(6));
  EXPECT_EQ(estimator.estimates()[0].samples, 4u);
}

}  // namespace
}  // namespace ssl::wm
