#include "services/simulator/core/vision/vision_model.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "services/simulator/core/vision/vision_test_util.h"

namespace ssl::sim {
namespace {

using namespace ssl::sim::testing;

VisionConfig config_with(int cameras, const RealismConfig& realism = RealismConfig::none()) {
  VisionConfig config;
  config.camera_count = cameras;
  config.realism = realism;
  return config;
}

// Mean and sample standard deviation.
struct Moments {
  double mean = 0;
  double stddev = 0;
};
Moments moments(const std::vector<double>& values) {
  double sum = 0;
  for (double v : values) sum += v;
  const double mean = sum / static_cast<double>(values.size());
  double squares = 0;
  for (double v : values) squares += (v - mean) * (v - mean);
  return {mean, std::sqrt(squares / static_cast<double>(values.size() - 1))};
}

// ---------------------------------------------------------------------------------------------------------
// Camera schedule, tiling through the model, frame numbers

TEST(SimVisionScheduleTest, EachCameraProducesFrameRateFramesPerSecondWithConsecutiveNumbers) {
  for (int count : {1, 2, 4, 8}) {
    for (double step : {0.001, 1.0 / 600.0, 0.0007}) {
      SCOPED_TRACE("cameras " + std::to_string(count) + " step " + std::to_string(step));
      VisionModel model(FieldGeometry::division_a(), config_with(count), 1);
      const std::vector<SentFrame> sent = run(model, snapshot_at({}, {0, 0, kBallRadius}), 100.0, 1.0, step);
      std::map<std::uint32_t, std::vector<std::uint32_t>> numbers;
      for (const SentFrame& s : sent) numbers[s.frame.camera_id].push_back(s.frame.frame_number);
      ASSERT_EQ(numbers.size(), static_cast<std::size_t>(count));
      for (const auto& [camera, frame_numbers] : numbers) {
        EXPECT_NEAR(static_cast<double>(frame_numbers.size()), 75.0, 1.0) << "camera " << camera;
        for (std::size_t i = 1; i < frame_numbers.size(); ++i) {
          ASSERT_EQ(frame_numbers[i], frame_numbers[i - 1] + 1);
        }
      }
      EXPECT_EQ(model.stats().capture_slots_skipped, 0u);
    }
  }
}

TEST(SimVisionScheduleTest, CamerasAreStaggeredEvenly) {
  VisionModel model(FieldGeometry::division_a(), config_with(4), 1);
  const std::vector<SentFrame> sent = run(model, snapshot_at({}, {0, 0, kBallRadius}), 0.0, 0.05, 0.0001);
  std::map<std::uint32_t, time::Timestamp> first;
  for (const SentFrame& s : sent) first.emplace(s.frame.camera_id, s.frame.capture_time);
  ASSERT_EQ(first.size(), 4u);
  // Period 1/75 s = 13.33 ms, so the cameras start 3.33 ms apart (to the 0.1 ms step).
  for (std::uint32_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(time::to_seconds(first[i] - first[0]), i / 300.0, 1e-4) << i;
  }
}

TEST(SimVisionScheduleTest, LongStepsCaptureOnceAndCountSkippedSlots) {
  VisionModel model(FieldGeometry::division_b(), config_with(1), 1);
  const std::vector<SentFrame> sent = run(model, snapshot_at({}, {0, 0, kBallRadius}), 0.0, 1.0, 0.05);
  // 21 updates 50 ms apart; each one captures (a slot passed) and ~2.75 slots are skipped per step.
  EXPECT_EQ(sent.size(), 21u);
  for (std::size_t i = 1; i < sent.size(); ++i) {
    EXPECT_EQ(sent[i].frame.frame_number, sent[i - 1].frame.frame_number + 1);
  }
  // Slots 0..75 lie in [0, 1 s]: each was either captured or skipped.
  EXPECT_EQ(model.stats().capture_slots_skipped + model.stats().frames_captured, 76u);
}

TEST(SimVisionScheduleTest, EveryPointOfFieldAndBoundaryIsSeenByACamera) {
  for (const FieldGeometry& field : {FieldGeometry::division_a(), FieldGeometry::division_b()}) {
    const geom::Rectangle area = covered_area(field);
    for (int count : {1, 2, 4, 8}) {
      SCOPED_TRACE("cameras " + std::to_string(count));
      VisionModel model(field, config_with(count), 1);
      // Robots on a grid of 16 x 2 points per pass (32 robot keys), including edges and corners.
      std::vector<Vec2> points;
      for (int i = 0; i <= 24; ++i) {
        for (int j = 0; j <= 16; ++j) {
          points.emplace_back(area.min().x() + area.width() * i / 24,
                              area.min().y() + area.height() * j / 16);
        }
      }
      double start = 0.0;
      for (std::size_t first = 0; first < points.size(); first += 32) {
        std::vector<RobotState> robots;
        for (std::size_t k = first; k < std::min(points.size(), first + 32); ++k) {
          const auto index = static_cast<std::uint32_t>(k - first);
          robots.push_back(robot_at(index < 16 ? TeamColor::kBlue : TeamColor::kYellow, index % 16,
                                    points[k].x(), points[k].y()));
        }
        // A little over one frame period: every camera captures at least once.
        const std::vector<SentFrame> sent =
            run(model, snapshot_at({}, {0, 0, kBallRadius}, robots), start, 0.016, 0.001);
        start += 1.0;
        std::vector<int> seen(robots.size(), 0);
        for (const SentFrame& s : sent) {
          for (const RobotDetection& r : s.frame.robots_blue) ++seen[r.robot_id];
          for (const RobotDetection& r : s.frame.robots_yellow) ++seen[16 + r.robot_id];
        }
        for (std::size_t k = 0; k < robots.size(); ++k) {
          EXPECT_GE(seen[k], 1) << robots[k].position.transpose();
        }
      }
    }
  }
}

TEST(SimVisionScheduleTest, ThePointNearTheCentreIsSeenByAllFourCameras) {
  VisionModel model(FieldGeometry::division_a(), config_with(4), 1);
  const WorldSnapshot world =
      snapshot_at({}, {0.1, -0.1, kBallRadius}, {robot_at(TeamColor::kYellow, 3, -0.05, 0.05)});
  const std::vector<SentFrame> sent = run(model, world, 0.0, 1.0 / 75.0, 0.001);
  std::vector<std::uint32_t> robot_cameras;
  std::vector<std::uint32_t> ball_cameras;
  for (const SentFrame& s : sent) {
    if (!s.frame.robots_yellow.empty()) robot_cameras.push_back(s.frame.camera_id);
    if (!s.frame.balls.empty()) ball_cameras.push_back(s.frame.camera_id);
  }
  EXPECT_EQ(robot_cameras.size(), 4u);
  EXPECT_EQ(ball_cameras.size(), 4u);
  // Far from the centre only one camera sees it.
  VisionModel corner_model(FieldGeometry::division_a(), config_with(4), 1);
  const std::vector<SentFrame> corner =
      run(corner_model, snapshot_at({}, {5.5, 4.0, kBallRadius}), 0.0, 1.0 / 75.0, 0.001);
  int with_ball = 0;
  for (const SentFrame& s : corner) with_ball += s.frame.balls.empty() ? 0 : 1;
  EXPECT_EQ(with_ball, 1);
}

// ---------------------------------------------------------------------------------------------------------
// Realism none: exact truth

TEST(SimVisionNoneTest, DetectionsEqualTheTruthAndAreSentAtOnce) {
  VisionModel model(FieldGeometry::division_a(), config_with(4), 3);
  RobotSpec yellow_spec;
  yellow_spec.height = 0.14;
  model.set_robot_spec(TeamColor::kYellow, yellow_spec);
  const WorldSnapshot world = snapshot_at(
      {}, {1.234, -0.567, kBallRadius},
      {robot_at(TeamColor::kBlue, 0, 2.5, 1.5, 0.3), robot_at(TeamColor::kBlue, 7, -4.0, -3.0, -2.9),
       robot_at(TeamColor::kYellow, 2, 0.7, 0.2, 3.1)});
  const std::vector<SentFrame> sent = run(model, world, 5.0, 0.1, 0.001);
  ASSERT_FALSE(sent.empty());
  int balls = 0;
  int robots = 0;
  for (const SentFrame& s : sent) {
    const DetectionFrame& frame = s.frame;
    EXPECT_EQ(frame.sent_time, frame.capture_time);
    EXPECT_EQ(s.returned_at, frame.capture_time);
    for (const BallDetection& ball : frame.balls) {
      ++balls;
      EXPECT_EQ(ball.x, 1.234);
      EXPECT_EQ(ball.y, -0.567);
      EXPECT_FALSE(ball.has_z);
      EXPECT_EQ(ball.confidence, 1.0f);
      EXPECT_GT(ball.area, 0u);
    }
    for (const RobotDetection& r : frame.robots_blue) {
      ++robots;
      const RobotState& truth = world.robots[r.robot_id == 0 ? 0 : 1];
      EXPECT_EQ(r.x, truth.position.x());
      EXPECT_EQ(r.y, truth.position.y());
      EXPECT_EQ(r.orientation, truth.orientation);
      EXPECT_EQ(r.height, 0.15);
      EXPECT_EQ(r.confidence, 1.0f);
    }
    for (const RobotDetection& r : frame.robots_yellow) {
      ++robots;
      EXPECT_EQ(r.robot_id, 2u);
      EXPECT_EQ(r.x, 0.7);
      EXPECT_EQ(r.y, 0.2);
      EXPECT_EQ(r.orientation, 3.1);
      EXPECT_EQ(r.height, 0.14);
    }
  }
  EXPECT_GT(balls, 0);
  EXPECT_GT(robots, 0);
  EXPECT_EQ(model.stats().balls_missed + model.stats().robots_missed + model.stats().balls_occluded, 0u);
}

TEST(SimVisionNoneTest, PixelsMapBackToTheReportedPositionThroughThePublishedCalibration) {
  for (const RealismConfig& realism : {RealismConfig::none(), RealismConfig::competition()}) {
    VisionModel model(FieldGeometry::division_a(), config_with(4, realism), 11);
    const WorldSnapshot world =
        snapshot_at({}, {1.5, 2.0, kBallRadius}, {robot_at(TeamColor::kBlue, 4, -3.0, 1.0)});
    for (const SentFrame& s : run(model, world, 0.0, 1.0, 0.001)) {
      const CameraCalibration& calibration = model.geometry().calibrations.at(s.frame.camera_id);
      for (const BallDetection& ball : s.frame.balls) {
        const Vec3 back = pixel_to_world(calibration, {ball.pixel_x, ball.pixel_y}, kBallRadius);
        EXPECT_NEAR(back.x(), ball.x, 1e-5);  // float pixels: ~1e-4 px of ~3 mm
        EXPECT_NEAR(back.y(), ball.y, 1e-5);
      }
      for (const RobotDetection& robot : s.frame.robots_blue) {
        const Vec3 back = pixel_to_world(calibration, {robot.pixel_x, robot.pixel_y}, robot.height);
        EXPECT_NEAR(back.x(), robot.x, 1e-5);
        EXPECT_NEAR(back.y(), robot.y, 1e-5);
      }
    }
  }
}

TEST(SimVisionNoneTest, GeometryIsDueWithTheFirstFramesAndThenEveryNFrames) {
  VisionConfig config = config_with(4);
  config.geometry_every_frames = 30;
  VisionModel model(FieldGeometry::division_a(), config, 1);
  const std::vector<SentFrame> sent = run(model, snapshot_at({}, {0, 0, kBallRadius}), 0.0, 2.0, 0.001);
  ASSERT_FALSE(sent.empty());
  EXPECT_TRUE(sent.front().geometry_due);
  std::vector<std::size_t> due_at;
  for (std::size_t i = 0; i < sent.size(); ++i) {
    if (sent[i].geometry_due) due_at.push_back(i);
  }
  ASSERT_GE(due_at.size(), 2u);
  for (std::size_t i = 1; i < due_at.size(); ++i) EXPECT_EQ(due_at[i] - due_at[i - 1], 30u);
  // A changed field makes it due with the next frames.
  model.set_field(FieldGeometry::division_b());
  const std::vector<SentFrame> after = run(model, snapshot_at({}, {0, 0, kBallRadius}), 3.0, 0.05, 0.001);
  ASSERT_FALSE(after.empty());
  EXPECT_TRUE(after.front().geometry_due);
  EXPECT_DOUBLE_EQ(model.geometry().field.field_length, 9.0);
}

// ---------------------------------------------------------------------------------------------------------
// Noise, misses, false balls

TEST(SimVisionNoiseTest, PositionAndOrientationNoiseHaveTheConfiguredStatistics) {
  const RealismConfig realism = RealismConfig::realistic();
  VisionModel model(FieldGeometry::division_a(), config_with(1, realism), 2024);
  // Robots spread out so none hides the ball.
  const WorldSnapshot world = snapshot_at(
      {}, {0.5, 0.5, kBallRadius},
      {robot_at(TeamColor::kBlue, 1, -2.0, 1.0, 1.0), robot_at(TeamColor::kYellow, 5, 3.0, -2.0, -1.0)});
  std::vector<double> ball_dx, ball_dy, robot_dx, robot_dy, robot_dphi;
  for (const SentFrame& s : run(model, world, 0.0, 60.0, 0.002)) {
    for (const BallDetection& ball : s.frame.balls) {
      ball_dx.push_back(ball.x - 0.5);
      ball_dy.push_back(ball.y - 0.5);
    }
    for (const RobotDetection& r : s.frame.robots_blue) {
      robot_dx.push_back(r.x + 2.0);
      robot_dy.push_back(r.y - 1.0);
      robot_dphi.push_back(r.orientation - 1.0);
    }
    for (const RobotDetection& r : s.frame.robots_yellow) {
      robot_dx.push_back(r.x - 3.0);
      robot_dy.push_back(r.y + 2.0);
      robot_dphi.push_back(r.orientation + 1.0);
    }
  }
  ASSERT_GT(ball_dx.size(), 4000u);  // 60 s at 75 Hz, minus 3 % misses
  ASSERT_GT(robot_dx.size(), 8000u);
  const auto expect_stats = [](const std::vector<double>& errors, double stddev, const char* what) {
    const Moments m = moments(errors);
    EXPECT_NEAR(m.stddev, stddev, 0.2 * stddev) << what;
    EXPECT_NEAR(m.mean, 0.0, 5.0 * stddev / std::sqrt(static_cast<double>(errors.size()))) << what;
  };
  expect_stats(ball_dx, realism.ball_position_stddev, "ball x");
  expect_stats(ball_dy, realism.ball_position_stddev, "ball y");
  expect_stats(robot_dx, realism.robot_position_stddev, "robot x");
  expect_stats(robot_dy, realism.robot_position_stddev, "robot y");
  expect_stats(robot_dphi, realism.robot_orientation_stddev, "robot orientation");
}

TEST(SimVisionNoiseTest, MissedDetectionRatesMatchTheProbabilities) {
  RealismConfig realism;
  realism.ball_missing_probability = 0.2;
  realism.robot_missing_probability = 0.07;
  VisionModel model(FieldGeometry::division_b(), config_with(1, realism), 99);
  std::vector<RobotState> robots;
  for (std::uint32_t id = 0; id < 6; ++id) robots.push_back(robot_at(TeamColor::kBlue, id, -3.0 + id, 1.5));
  const std::vector<SentFrame> sent =
      run(model, snapshot_at({}, {0, -1, kBallRadius}, robots), 0.0, 40.0, 0.002);
  std::size_t frames = sent.size();
  std::size_t balls = 0;
  std::size_t robot_detections = 0;
  for (const SentFrame& s : sent) {
    balls += s.frame.balls.size();
    robot_detections += s.frame.robots_blue.size();
  }
  ASSERT_GT(frames, 2900u);
  const double ball_miss_rate = 1.0 - static_cast<double>(balls) / frames;
  const double robot_miss_rate = 1.0 - static_cast<double>(robot_detections) / (6.0 * frames);
  // 5 standard errors: sqrt(0.2 * 0.8 / 3000) = 0.0073; sqrt(0.07 * 0.93 / 18000) = 0.0019.
  EXPECT_NEAR(ball_miss_rate, 0.2, 0.037);
  EXPECT_NEAR(robot_miss_rate, 0.07, 0.01);
  EXPECT_EQ(model.stats().balls_missed, frames - balls);
  EXPECT_EQ(model.stats().robots_missed, 6 * frames - robot_detections);
}

TEST(SimVisionNoiseTest, FalseBallsAppearInViewWithLowConfidence) {
  RealismConfig realism;
  realism.false_ball_probability = 0.25;
  realism.false_ball_max_confidence = 0.5;
  VisionModel model(FieldGeometry::division_a(), config_with(4, realism), 5);
  const std::vector<SentFrame> sent =
      run(model, snapshot_at({}, {-3.0, -2.0, kBallRadius}), 0.0, 10.0, 0.001);
  const std::vector<CameraView> cameras = model.cameras();
  std::size_t frames = 0;
  std::size_t false_balls = 0;
  for (const SentFrame& s : sent) {
    ++frames;
    for (const BallDetection& ball : s.frame.balls) {
      if (ball.x == -3.0 && ball.y == -2.0) {
        EXPECT_EQ(ball.confidence, 1.0f);
        EXPECT_EQ(&ball, &s.frame.balls.front());  // most confident first
        continue;
      }
      ++false_balls;
      EXPECT_LT(ball.confidence, 0.5f);
      EXPECT_TRUE(cameras[s.frame.camera_id].view.contains(Vec2(ball.x, ball.y)));
    }
  }
  EXPECT_EQ(false_balls, model.stats().false_balls);
  EXPECT_NEAR(static_cast<double>(false_balls) / frames, 0.25, 0.04);  // 3000 frames: 5 standard errors
}

TEST(SimVisionNoiseTest, CalibrationErrorShiftsEachCameraConsistently) {
  RealismConfig realism;
  realism.camera_position_error = 0.02;
  VisionModel model(FieldGeometry::division_a(), config_with(4, realism), 8);
  const std::vector<CameraView> cameras = model.cameras();
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    EXPECT_NEAR((model.geometry().calibrations[i].derived_world - cameras[i].position).norm(), 0.02, 1e-12);
  }
  // A robot in the middle is seen by all four cameras at four slightly different places, each within the
  // error (horizontal shift + height error times the ray's slope: < 0.05 m here).
  const WorldSnapshot world = snapshot_at({}, {3, 3, kBallRadius}, {robot_at(TeamColor::kBlue, 0, 0.1, 0.1)});
  std::map<std::uint32_t, Vec2> seen;
  for (const SentFrame& s : run(model, world, 0.0, 0.5, 0.001)) {
    for (const RobotDetection& r : s.frame.robots_blue) {
      const Vec2 position(r.x, r.y);
      EXPECT_LT((position - Vec2(0.1, 0.1)).norm(), 0.05);
      EXPECT_GT((position - Vec2(0.1, 0.1)).norm(), 0.0);
      const auto [it, inserted] = seen.emplace(s.frame.camera_id, position);
      if (!inserted) {
        EXPECT_EQ(it->second, position);  // constant per camera
      }
    }
  }
  ASSERT_EQ(seen.size(), 4u);
  EXPECT_NE(seen[0], seen[1]);
}

// ---------------------------------------------------------------------------------------------------------
// Delay

TEST(SimVisionDelayTest, SentTimeIsCaptureTimePlusTheDelay) {
  RealismConfig realism;
  realism.vision_delay = 0.012;
  VisionModel model(FieldGeometry::division_a(), config_with(4, realism), 1);
  const std::vector<SentFrame> sent = run(model, snapshot_at({}, {0, 0, kBallRadius}), 0.0, 1.0, 0.001);
  ASSERT_GT(sent.size(), 280u);
  for (const SentFrame& s : sent) {
    EXPECT_EQ(s.frame.sent_time - s.frame.capture_time, std::chrono::milliseconds(12));
    EXPECT_EQ(s.returned_at, s.frame.sent_time);  // 1 ms steps hit the send times exactly
  }
}

TEST(SimVisionDelayTest, JitteredFramesComeOutOnlyOnceTheirSendTimeHasCome) {
  RealismConfig realism;
  realism.vision_delay = 0.010;
  realism.processing_time_jitter = 0.005;
  VisionModel model(FieldGeometry::division_a(), config_with(4, realism), 77);
  const double step = 0.0007;
  const std::vector<SentFrame> sent = run(model, snapshot_at({}, {0, 0, kBallRadius}), 0.0, 2.0, step);
  ASSERT_GT(sent.size(), 580u);
  double min_delay = 1.0;
  double max_delay = 0.0;
  std::map<std::uint32_t, time::Timestamp> last_sent;
  for (std::size_t i = 0; i < sent.size(); ++i) {
    const DetectionFrame& frame = sent[i].frame;
    const double delay = time::to_seconds(frame.sent_time - frame.capture_time);
    min_delay = std::min(min_delay, delay);
    max_delay = std::max(max_delay, delay);
    EXPECT_GE(delay, 0.010);
    EXPECT_LT(delay, 0.015 + 1e-9);
    EXPECT_LE(frame.sent_time, sent[i].returned_at);                                      // not early
    EXPECT_GT(frame.sent_time, sent[i].returned_at - time::duration_from_seconds(step));  // not late
    if (i > 0) {
      EXPECT_GE(frame.sent_time, sent[i - 1].frame.sent_time);  // in send order
    }
    if (last_sent.contains(frame.camera_id)) {
      EXPECT_GE(frame.sent_time, last_sent[frame.camera_id]);  // each camera in order
    }
    last_sent[frame.camera_id] = frame.sent_time;
  }
  EXPECT_LT(min_delay, 0.0105);  // the jitter really spreads over its range
  EXPECT_GT(max_delay, 0.0145);
  EXPECT_LE(model.pending_frames(), 8u);
}

TEST(SimVisionDelayTest, RealismCanChangeAtRunTime) {
  VisionModel model(FieldGeometry::division_a(), config_with(4), 1);
  const WorldSnapshot world = snapshot_at({}, {0, 0, kBallRadius});
  for (const SentFrame& s : run(model, world, 0.0, 0.5, 0.001)) {
    EXPECT_EQ(s.frame.sent_time, s.frame.capture_time);
  }
  RealismConfig delayed;
  delayed.vision_delay = 0.02;
  model.set_realism(delayed);
  EXPECT_EQ(model.realism(), delayed);
  const std::vector<SentFrame> later = run(model, world, 0.501, 0.5, 0.001);
  ASSERT_FALSE(later.empty());
  for (const SentFrame& s : later) {
    EXPECT_EQ(s.frame.sent_time - s.frame.capture_time, std::chrono::milliseconds(20));
  }
  RealismConfig invalid;
  invalid.vision_delay = -1.0;
  EXPECT_THROW(model.set_realism(invalid), std::invalid_argument);
  EXPECT_EQ(model.realism(), delayed);
}

TEST(SimVisionDelayTest, TimeGoingBackwardsRestartsTheSchedule) {
  RealismConfig realism;
  realism.vision_delay = 0.05;
  VisionModel model(FieldGeometry::division_a(), config_with(4, realism), 1);
  run(model, snapshot_at({}, {0, 0, kBallRadius}), 10.0, 0.2, 0.001);
  EXPECT_GT(model.pending_frames(), 0u);
  const std::size_t pending = model.pending_frames();
  const std::vector<SentFrame> sent = run(model, snapshot_at({}, {0, 0, kBallRadius}), 0.0, 0.2, 0.001);
  EXPECT_EQ(model.stats().frames_discarded, pending);
  ASSERT_FALSE(sent.empty());
  EXPECT_LT(sent.front().frame.capture_time, at_seconds(1.0));
}

TEST(SimVisionDelayTest, NextEventTimeIsWhenUpdateFirstProducesSomething) {
  RealismConfig realism;
  realism.vision_delay = 0.012;
  realism.processing_time_jitter = 0.004;
  VisionModel model(FieldGeometry::division_a(), config_with(4, realism), 3);
  EXPECT_EQ(model.next_event_time(), time::Timestamp());
  WorldSnapshot world = snapshot_at(at_seconds(2.0), {0, 0, kBallRadius});
  model.update(world);
  for (int i = 0; i < 200; ++i) {
    const time::Timestamp next = model.next_event_time();
    ASSERT_GT(next, world.time);
    const VisionStats before = model.stats();
    world.time = next - std::chrono::nanoseconds(1);
    EXPECT_TRUE(model.update(world).frames.empty());
    EXPECT_EQ(model.stats(), before);  // nothing captured or sent just before
    world.time = next;
    const VisionOutput out = model.update(world);
    EXPECT_TRUE(!out.frames.empty() || model.stats().frames_captured > before.frames_captured);
  }
}

// ---------------------------------------------------------------------------------------------------------
// Occlusion

// One camera over a Division B field hangs at (0, 0, 4). The robot stands at (2, 0), 2 m from the camera's
// foot.
class SimVisionOcclusionTest : public ::testing::Test {
 protected:
  static std::vector<SentFrame> frames_with_ball_at(Vec2 ball, bool occlusion, double robot_orientation) {
    RealismConfig realism;
    realism.ball_occlusion = occlusion;
    VisionModel model(FieldGeometry::division_b(), config_with(1, realism), 1);
    const WorldSnapshot world = snapshot_at({}, {ball.x(), ball.y(), kBallRadius},
                                            {robot_at(TeamColor::kYellow, 1, 2.0, 0.0, robot_orientation)});
    return run(model, world, 0.0, 0.2, 0.001);
  }
  static std::size_t balls_in(const std::vector<SentFrame>& sent) {
    std::size_t balls = 0;
    for (const SentFrame& s : sent) balls += s.frame.balls.size();
    return balls;
  }
  static constexpr double kFacingCamera = 3.14159;  // rad: flat front towards the camera
  // Centre distance of a ball 2 mm from the robot's round side.
  static constexpr double kTouching = 0.09 + kBallRadius + 0.002;
};

TEST_F(SimVisionOcclusionTest, BallBehindARobotSeenFromTheCameraIsHidden) {
  const std::vector<SentFrame> sent = frames_with_ball_at({2.0 + kTouching, 0.0}, true, kFacingCamera);
  ASSERT_GT(sent.size(), 10u);
  EXPECT_EQ(balls_in(sent), 0u);
  for (const SentFrame& s : sent) EXPECT_EQ(s.frame.robots_yellow.size(), 1u);
}

TEST_F(SimVisionOcclusionTest, BallInFrontOfTheRobotOrInTheOpenIsSeen) {
  const std::vector<SentFrame> near_side = frames_with_ball_at({2.0 - kTouching, 0.0}, true, kFacingCamera);
  EXPECT_EQ(balls_in(near_side), near_side.size());
  const std::vector<SentFrame> open = frames_with_ball_at({2.5, 0.0}, true, kFacingCamera);
  EXPECT_EQ(balls_in(open), open.size());
  for (const SentFrame& s : open) EXPECT_EQ(s.frame.balls.at(0).x, 2.5);  // nothing hidden: unshifted
}

TEST_F(SimVisionOcclusionTest, WithoutOcclusionTheHiddenBallIsReported) {
  const std::vector<SentFrame> sent = frames_with_ball_at({2.0 + kTouching, 0.0}, false, kFacingCamera);
  EXPECT_EQ(balls_in(sent), sent.size());
}

TEST_F(SimVisionOcclusionTest, PartlyHiddenBallAppearsShiftedAwayFromTheRobotAndSmaller) {
  // The robot's shadow reaches 2 m * (0.15 - z) / (4 - z) ~ 0.065 m beyond it for the ball's centre; 0.072 m
  // behind the robot about 60 % of the ball peeks out on the far side.
  const double x = 2.0 + 0.09 + 0.072;
  const std::vector<SentFrame> sent = frames_with_ball_at({x, 0.0}, true, kFacingCamera);
  const std::vector<SentFrame> open = frames_with_ball_at({x, 0.0}, false, kFacingCamera);
  ASSERT_EQ(balls_in(sent), sent.size());
  ASSERT_EQ(balls_in(open), open.size());
  const std::uint32_t whole_area = open.at(0).frame.balls.at(0).area;
  for (const SentFrame& s : sent) {
    EXPECT_GT(s.frame.balls.at(0).x, x + 0.002);
    EXPECT_LT(s.frame.balls.at(0).x, x + kBallRadius);
    EXPECT_LT(s.frame.balls.at(0).area, 0.8 * whole_area);
  }
}

TEST_F(SimVisionOcclusionTest, TheFlatFrontHidesLessThanTheRoundBack) {
  // A ball at the dribbler (0.078 m + ball radius from the centre) beside the robot as the camera sees it:
  // with the flat front towards the ball every sight line clears the body; the round back (a full cylinder
  // there) would cover the ball's inner edge and shift it outwards.
  const Vec2 ball(2.0, 0.078 + kBallRadius + 0.0005);
  const std::vector<SentFrame> front = frames_with_ball_at(ball, true, 3.14159 / 2);
  ASSERT_EQ(balls_in(front), front.size());
  for (const SentFrame& s : front) EXPECT_EQ(s.frame.balls.at(0).y, ball.y());
  const std::vector<SentFrame> back = frames_with_ball_at(ball, true, -3.14159 / 2);
  ASSERT_EQ(balls_in(back), back.size());
  for (const SentFrame& s : back) EXPECT_GT(s.frame.balls.at(0).y, ball.y() + 0.001);
}

// ---------------------------------------------------------------------------------------------------------
// Airborne ball

TEST(SimVisionChipTest, AirborneBallIsProjectedAwayFromTheCamera) {
  VisionModel model(FieldGeometry::division_b(), config_with(1), 1);  // camera at (0, 0, 4)
  const Vec3 ball(2.0, 1.0, 0.5);
  const std::vector<SentFrame> sent = run(model, snapshot_at({}, ball), 0.0, 0.1, 0.001);
  ASSERT_FALSE(sent.empty());
  // The camera ray through the ball meets z = radius at (x, y) * (4 - r) / (4 - 0.5).
  const double scale = (4.0 - kBallRadius) / (4.0 - 0.5);
  for (const SentFrame& s : sent) {
    ASSERT_EQ(s.frame.balls.size(), 1u);
    const BallDetection& detection = s.frame.balls[0];
    EXPECT_NEAR(detection.x, 2.0 * scale, 1e-12);
    EXPECT_NEAR(detection.y, 1.0 * scale, 1e-12);
    EXPECT_GT(std::hypot(detection.x, detection.y), std::hypot(2.0, 1.0));
    EXPECT_FALSE(detection.has_z);
  }
}

TEST(SimVisionChipTest, EachCameraProjectsAlongItsOwnRay) {
  VisionModel model(FieldGeometry::division_a(), config_with(4), 1);
  const Vec3 ball(0.0, 0.0, 0.3);  // above the centre: seen by all four cameras
  std::map<std::uint32_t, Vec2> seen;
  for (const SentFrame& s : run(model, snapshot_at({}, ball), 0.0, 0.1, 0.001)) {
    if (!s.frame.balls.empty()) seen[s.frame.camera_id] = Vec2(s.frame.balls[0].x, s.frame.balls[0].y);
  }
  ASSERT_EQ(seen.size(), 4u);
  const std::vector<CameraView> cameras = model.cameras();
  for (const auto& [id, position] : seen) {
    const Vec2 camera_foot(cameras[id].position.x(), cameras[id].position.y());
    EXPECT_LT(position.dot(camera_foot), 0.0) << id;  // on the far side of the centre from this camera
  }
}

TEST(SimVisionChipTest, HeightCanBeReportedInstead) {
  VisionConfig config = config_with(1);
  config.report_ball_height = true;
  VisionModel model(FieldGeometry::division_b(), config, 1);
  const std::vector<SentFrame> sent = run(model, snapshot_at({}, {2.0, 1.0, 0.5}), 0.0, 0.1, 0.001);
  ASSERT_FALSE(sent.empty());
  for (const SentFrame& s : sent) {
    ASSERT_EQ(s.frame.balls.size(), 1u);
    EXPECT_EQ(s.frame.balls[0].x, 2.0);
    EXPECT_EQ(s.frame.balls[0].y, 1.0);
    EXPECT_EQ(s.frame.balls[0].z, 0.5);
    EXPECT_TRUE(s.frame.balls[0].has_z);
  }
}

// ---------------------------------------------------------------------------------------------------------
// Determinism

// Runs one busy match (22 moving robots, a rising ball, competition realism) through several models at once,
// each with its own seed, and returns what each sent.
std::vector<std::vector<SentFrame>> busy_match(const std::vector<std::uint64_t>& seeds) {
  std::vector<VisionModel> models;
  for (std::uint64_t seed : seeds) {
    models.emplace_back(FieldGeometry::division_a(), config_with(4, RealismConfig::competition()), seed);
  }
  std::vector<std::vector<SentFrame>> sent(seeds.size());
  for (int step = 0; step < 1500; ++step) {
    const double t = step * 0.001;
    std::vector<RobotState> robots;
    for (std::uint32_t id = 0; id < 11; ++id) {
      robots.push_back(
          robot_at(TeamColor::kBlue, id, -5.0 + id + 0.3 * std::sin(t + id), std::cos(t * id) * 3.0, t));
    }
    for (std::uint32_t id = 0; id < 11; ++id) {
      robots.push_back(robot_at(TeamColor::kYellow, id, 5.0 - id, std::sin(t * id) * 3.0 + 0.5, -t));
    }
    const WorldSnapshot world = snapshot_at(time::Timestamp::from_milliseconds(step),
                                            {std::sin(t) * 4.0, 0.3, kBallRadius + t * 0.2}, robots);
    for (std::size_t m = 0; m < models.size(); ++m) {
      VisionOutput out = models[m].update(world);
      for (DetectionFrame& frame : out.frames) {
        sent[m].push_back({std::move(frame), world.time, out.geometry_due});
      }
    }
  }
  return sent;
}

TEST(SimVisionDeterminismTest, SameSeedSameFramesOtherSeedOtherNoise) {
  const std::vector<std::vector<SentFrame>> runs = busy_match({123, 123, 124});
  const std::vector<SentFrame>& a = runs[0];
  const std::vector<SentFrame>& b = runs[1];
  const std::vector<SentFrame>& c = runs[2];
  ASSERT_GT(a.size(), 400u);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].frame, b[i].frame) << i;
    ASSERT_EQ(a[i].returned_at, b[i].returned_at) << i;
  }
  std::size_t differing = 0;
  for (std::size_t i = 0; i < std::min(a.size(), c.size()); ++i) {
    differing += a[i].frame == c[i].frame ? 0 : 1;
  }
  EXPECT_GT(differing, a.size() / 2);
  // A later run in the same process gives the same frames again (no hidden state outside the model).
  const std::vector<std::vector<SentFrame>> again = busy_match({123});
  ASSERT_EQ(again[0].size(), a.size());
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(again[0][i].frame, a[i].frame) << i;
}

}  // namespace
}  // namespace ssl::sim
