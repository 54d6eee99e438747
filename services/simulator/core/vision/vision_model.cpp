#include "services/simulator/core/vision/vision_model.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

#include <Eigen/Geometry>

#include "libs/geometry/angle.h"
#include "libs/geometry/circle.h"
#include "libs/geometry/distance.h"
#include "libs/geometry/intersect.h"
#include "libs/geometry/segment.h"

namespace ssl::sim {
namespace {

// The ball is sampled for occlusion on a (2n+1)^2 grid of points, spacing radius / n, kept inside the disc:
// 25 samples for n = 3 (ER-Force's simulator samples the same way).
constexpr int kBallSampleSteps = 3;

// Nanoseconds from slot 0 to slot k of a camera at `rate` Hz, rounded (computed from k, so no drift).
std::int64_t slot_offset_ns(std::uint64_t slot, double rate) {
  return std::llround(static_cast<double>(slot) * 1e9 / rate);
}

}  // namespace

VisionModel::TeamBody VisionModel::body_of(const RobotSpec& spec) {
  return {spec.height, spec.radius, spec.center_to_dribbler};
}

VisionModel::VisionModel(const FieldGeometry& field, const VisionConfig& config, std::uint64_t seed)
    : field_(field), config_(config), random_(seed) {
  config_.validate();
  bodies_ = {body_of(RobotSpec{}), body_of(RobotSpec{})};
  const std::size_t count = static_cast<std::size_t>(config_.camera_count);
  cameras_.resize(count);
  // First draws of the stream: one uniformly random 3D direction per camera for its calibration error, drawn
  // whether or not the error is enabled so that enabling it later gives the same directions.
  for (Camera& camera : cameras_) {
    Vec3 direction;
    do {
      direction = Vec3(random_.normal(), random_.normal(), random_.normal());
    } while (direction.squaredNorm() < 1e-12);
    camera.error_direction = direction.normalized();
  }
  for (std::size_t i = 0; i < count; ++i) {
    cameras_[i].phase =
        time::Duration(std::llround(static_cast<double>(i) * 1e9 / (config_.frame_rate * count)));
  }
  rebuild_cameras();
}

void VisionModel::rebuild_cameras() {
  std::vector<CameraView> views = make_camera_layout(field_, config_);
  for (std::size_t i = 0; i < cameras_.size(); ++i) {
    Camera& camera = cameras_[i];
    camera.view = views[i];
    camera.believed_position =
        camera.view.position + config_.realism.camera_position_error * camera.error_direction;
    camera.rotation = camera_rotation(camera.view.calibration);
    camera.published = camera.view.calibration;
    const Vec3 translation = -(camera.rotation * camera.believed_position);
    camera.published.tx = translation.x();
    camera.published.ty = translation.y();
    camera.published.tz = translation.z();
    camera.published.derived_world = camera.believed_position;
  }
  rebuild_geometry();
}

void VisionModel::rebuild_geometry() {
  geometry_.field = field_;
  geometry_.ball_radius = config_.ball_radius;
  geometry_.max_robot_radius = config_.max_robot_radius;
  geometry_.lines = make_field_lines(field_);
  geometry_.arcs = make_field_arcs(field_);
  geometry_.calibrations.clear();
  for (const Camera& camera : cameras_) geometry_.calibrations.push_back(camera.published);
  geometry_.ball_models = config_.ball_models;
  geometry_changed_ = true;
}

void VisionModel::set_realism(const RealismConfig& realism) {
  realism.validate();
  const bool calibration_changed = realism.camera_position_error != config_.realism.camera_position_error;
  config_.realism = realism;
  if (calibration_changed) rebuild_cameras();
}

void VisionModel::set_robot_spec(TeamColor team, const RobotSpec& spec) {
  bodies_[team == TeamColor::kBlue ? 0 : 1] = body_of(spec);
}

void VisionModel::set_field(const FieldGeometry& field) {
  field_ = field;
  rebuild_cameras();
}

std::vector<CameraView> VisionModel::cameras() const {
  std::vector<CameraView> views;
  views.reserve(cameras_.size());
  for (const Camera& camera : cameras_) views.push_back(camera.view);
  return views;
}

time::Timestamp VisionModel::slot_time(const Camera& camera, std::uint64_t slot) const {
  return anchor_ + camera.phase + time::Duration(slot_offset_ns(slot, config_.frame_rate));
}

time::Timestamp VisionModel::next_event_time() const {
  if (!started_) return time::Timestamp();
  time::Timestamp next = time::Timestamp::max();
  for (const Camera& camera : cameras_) next = std::min(next, slot_time(camera, camera.next_slot));
  if (!pending_.empty()) next = std::min(next, pending_.front().frame.sent_time);
  return next;
}

void VisionModel::restart_schedule(time::Timestamp now) {
  stats_.frames_discarded += pending_.size();
  pending_.clear();
  anchor_ = now;
  for (Camera& camera : cameras_) {
    camera.next_slot = 0;
    camera.last_sent = time::Timestamp::min();
  }
  started_ = true;
}

VisionOutput VisionModel::update(const WorldSnapshot& snapshot) {
  const time::Timestamp now = snapshot.time;
  if (!started_ || now < last_time_) restart_schedule(now);
  last_time_ = now;

  for (Camera& camera : cameras_) {
    if (slot_time(camera, camera.next_slot) > now) continue;
    capture(camera, snapshot);
    // Next slot strictly after now; estimate it from the elapsed time, then settle rounding either way.
    const double elapsed_ns = static_cast<double>((now - anchor_ - camera.phase).count());
    std::uint64_t next = std::max<std::uint64_t>(
        camera.next_slot + 1,
        static_cast<std::uint64_t>(std::floor(elapsed_ns * config_.frame_rate / 1e9)) + 1);
    while (slot_time(camera, next) <= now) ++next;
    while (next > camera.next_slot + 1 && slot_time(camera, next - 1) > now) --next;
    stats_.capture_slots_skipped += next - camera.next_slot - 1;
    camera.next_slot = next;
  }

  VisionOutput output;
  std::size_t ready = 0;
  while (ready < pending_.size() && pending_[ready].frame.sent_time <= now) ++ready;
  if (ready == 0) return output;
  output.frames.reserve(ready);
  for (std::size_t i = 0; i < ready; ++i) output.frames.push_back(std::move(pending_[i].frame));
  pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(ready));
  stats_.frames_sent += ready;

  frames_since_geometry_ += ready;
  const std::uint32_t every = config_.geometry_every_frames;
  if (geometry_changed_ || (every > 0 && frames_since_geometry_ >= every)) {
    output.geometry_due = true;
    geometry_changed_ = false;
    frames_since_geometry_ = 0;
  }
  return output;
}

void VisionModel::capture(Camera& camera, const WorldSnapshot& snapshot) {
  const RealismConfig& realism = config_.realism;
  Pending pending;
  DetectionFrame& frame = pending.frame;
  frame.camera_id = camera.view.camera_id;
  frame.frame_number = camera.next_frame_number++;
  frame.capture_time = snapshot.time;

  detect_ball(camera, snapshot, frame);
  for (const RobotState& robot : snapshot.robots) detect_robot(camera, robot, frame);
  if (random_.bernoulli(realism.false_ball_probability)) add_false_ball(camera, frame);
  std::stable_sort(
      frame.balls.begin(), frame.balls.end(),
      [](const BallDetection& a, const BallDetection& b) { return a.confidence > b.confidence; });

  double delay = realism.vision_delay;
  if (realism.processing_time_jitter > 0.0) delay += random_.uniform(0.0, realism.processing_time_jitter);
  frame.sent_time = std::max(snapshot.time + time::duration_from_seconds(delay), camera.last_sent);
  camera.last_sent = frame.sent_time;

  ++stats_.frames_captured;
  pending.sequence = next_sequence_++;
  const auto position = std::upper_bound(
      pending_.begin(), pending_.end(), frame.sent_time,
      [](time::Timestamp sent, const Pending& other) { return sent < other.frame.sent_time; });
  pending_.insert(position, std::move(pending));
}

Vec3 VisionModel::believed_point(const Camera& camera, const Vec3& point, double plane_z) const {
  if (config_.realism.camera_position_error == 0.0) return point;
  // The pixel of `point` is on the true camera's ray through it; the vision system intersects the same
  // direction from where it believes the camera is with the same plane.
  const Vec3& real = camera.view.position;
  const Vec3& believed = camera.believed_position;
  return believed + (point - real) * ((believed.z() - plane_z) / (real.z() - plane_z));
}

Eigen::Vector2d VisionModel::pixel_of(const Camera& camera, const Vec3& reported) const {
  const Vec3 p = camera.rotation * (reported - camera.believed_position);
  const CameraCalibration& c = camera.published;
  return {c.focal_length * p.x() / p.z() + c.principal_point_x,
          c.focal_length * p.y() / p.z() + c.principal_point_y};
}

float VisionModel::draw_confidence() {
  const double spread = config_.realism.confidence_spread;
  if (spread <= 0.0) return 1.0f;
  return static_cast<float>(1.0 - spread * random_.uniform01());
}

void VisionModel::detect_ball(const Camera& camera, const WorldSnapshot& snapshot, DetectionFrame& frame) {
  const RealismConfig& realism = config_.realism;
  const Vec3& eye = camera.view.position;
  const double radius = config_.ball_radius;
  Vec3 ball = snapshot.ball.position;
  if (!ball.allFinite() || ball.z() >= eye.z() - radius) return;  // nonsense, or at the camera's height

  // Where this camera reports a ball centred at `center` (before noise), and on which plane.
  const auto reported_point = [&](const Vec3& center, double& plane_z) {
    if (config_.report_ball_height) {
      plane_z = center.z();
      return believed_point(camera, center, plane_z);
    }
    plane_z = radius;
    Vec3 on_plane = center;
    if (center.z() > radius) on_plane = eye + (center - eye) * ((eye.z() - radius) / (eye.z() - center.z()));
    on_plane.z() = radius;
    return believed_point(camera, on_plane, plane_z);
  };

  double plane_z = radius;
  Vec3 reported = reported_point(ball, plane_z);
  if (!camera.view.view.contains(Vec2(reported.x(), reported.y()))) return;

  double visibility = 1.0;
  if (realism.ball_occlusion) {
    Vec3 visible_center = ball;
    visibility = ball_visibility(camera, ball, snapshot.robots, visible_center);
    if (visibility <= 0.0 || visibility < realism.ball_visibility_threshold) {
      ++stats_.balls_occluded;
      return;
    }
    if (visible_center != ball) {
      ball = visible_center;
      reported = reported_point(ball, plane_z);
    }
  }
  if (random_.bernoulli(realism.ball_missing_probability)) {
    ++stats_.balls_missed;
    return;
  }
  if (realism.ball_position_stddev > 0.0) {
    reported.x() += realism.ball_position_stddev * random_.normal();
    reported.y() += realism.ball_position_stddev * random_.normal();
  }
  // Blob area: the ball's disc as the camera images it, scaled by the visible part, plus noise.
  const double depth = (camera.rotation * (ball - eye)).z();
  const double radius_px = camera.published.focal_length * radius / depth;
  double area = std::numbers::pi * radius_px * radius_px;
  if (realism.ball_area_stddev > 0.0) area += realism.ball_area_stddev * random_.normal();
  area = std::max(0.0, area * visibility);

  BallDetection detection;
  detection.x = reported.x();
  detection.y = reported.y();
  if (config_.report_ball_height) {
    detection.z = reported.z();
    detection.has_z = true;
  }
  detection.confidence = draw_confidence();
  detection.area = static_cast<std::uint32_t>(std::lround(area));
  const Eigen::Vector2d pixel = pixel_of(camera, reported);
  detection.pixel_x = static_cast<float>(pixel.x());
  detection.pixel_y = static_cast<float>(pixel.y());
  frame.balls.push_back(detection);
  ++stats_.ball_detections;
}

void VisionModel::detect_robot(const Camera& camera, const RobotState& robot, DetectionFrame& frame) {
  const RealismConfig& realism = config_.realism;
  const TeamBody& team = body(robot.key.team);
  Vec3 reported =
      believed_point(camera, Vec3(robot.position.x(), robot.position.y(), team.height), team.height);
  if (!reported.allFinite() || !camera.view.view.contains(Vec2(reported.x(), reported.y()))) return;
  if (random_.bernoulli(realism.robot_missing_probability)) {
    ++stats_.robots_missed;
    return;
  }
  if (realism.robot_position_stddev > 0.0) {
    reported.x() += realism.robot_position_stddev * random_.normal();
    reported.y() += realism.robot_position_stddev * random_.normal();
  }
  double orientation = robot.orientation;
  if (realism.robot_orientation_stddev > 0.0) {
    orientation += realism.robot_orientation_stddev * random_.normal();
  }

  RobotDetection detection;
  detection.robot_id = robot.key.id;
  detection.x = reported.x();
  detection.y = reported.y();
  detection.orientation = geom::Angle::from_radians(orientation).radians();
  detection.confidence = draw_confidence();
  detection.height = team.height;
  const Eigen::Vector2d pixel = pixel_of(camera, reported);
  detection.pixel_x = static_cast<float>(pixel.x());
  detection.pixel_y = static_cast<float>(pixel.y());
  (robot.key.team == TeamColor::kBlue ? frame.robots_blue : frame.robots_yellow).push_back(detection);
  ++stats_.robot_detections;
}

void VisionModel::add_false_ball(const Camera& camera, DetectionFrame& frame) {
  const RealismConfig& realism = config_.realism;
  const geom::Rectangle& view = camera.view.view;
  const double radius = config_.ball_radius;
  const Vec3 reported(random_.uniform(view.min().x(), view.max().x()),
                      random_.uniform(view.min().y(), view.max().y()), radius);
  BallDetection detection;
  detection.x = reported.x();
  detection.y = reported.y();
  if (config_.report_ball_height) {
    detection.z = radius;
    detection.has_z = true;
  }
  detection.confidence = static_cast<float>(realism.false_ball_max_confidence * random_.uniform01());
  // A smaller, irregular orange blob: 30-100 % of a real ball's area there.
  const double depth = (camera.rotation * (reported - camera.believed_position)).z();
  const double radius_px = camera.published.focal_length * radius / depth;
  const double area = std::numbers::pi * radius_px * radius_px * random_.uniform(0.3, 1.0);
  detection.area = static_cast<std::uint32_t>(std::lround(area));
  const Eigen::Vector2d pixel = pixel_of(camera, reported);
  detection.pixel_x = static_cast<float>(pixel.x());
  detection.pixel_y = static_cast<float>(pixel.y());
  frame.balls.push_back(detection);
  ++stats_.false_balls;
}

double VisionModel::ball_visibility(const Camera& camera, const Vec3& ball,
                                    const std::vector<RobotState>& robots, Vec3& visible_center) {
  const Vec3& eye = camera.view.position;
  const double radius = config_.ball_radius;
  visible_center = ball;

  // Robots that can hide any part of the ball: the part of the sight line from the ball's centre to the
  // camera below the robot's top passes within (robot radius + 2 ball radii) of its centre.
  occluders_.clear();
  for (const RobotState& robot : robots) {
    const TeamBody& team = body(robot.key.team);
    if (ball.z() - radius >= team.height) continue;  // the whole ball is above the robot
    const double t_top = std::clamp((team.height - ball.z()) / (eye.z() - ball.z()), 0.0, 1.0);
    const Vec2 start(ball.x(), ball.y());
    const Vec2 end = start + t_top * Vec2(eye.x() - ball.x(), eye.y() - ball.y());
    const double reach = team.radius + 2.0 * radius;
    if (geom::squared_distance(robot.position, geom::Segment{start, end}) > reach * reach) continue;
    occluders_.push_back({robot.position, Vec2(std::cos(robot.orientation), std::sin(robot.orientation)),
                          team.radius, team.height, team.center_to_dribbler});
  }
  if (occluders_.empty()) return 1.0;

  // Is the sight line from `sample` to the camera blocked by a robot body (a cylinder cut flat at the
  // dribbler: the disc of `radius` around the centre, minus the part more than `front` ahead)?
  const auto blocked = [&](const Vec3& sample) {
    for (const Occluder& robot : occluders_) {
      if (sample.z() >= robot.height) continue;  // the sight line only rises from here
      const double t_top = (robot.height - sample.z()) / (eye.z() - sample.z());
      const Vec2 start(sample.x(), sample.y());
      const Vec2 along = t_top * Vec2(eye.x() - sample.x(), eye.y() - sample.y());
      // Keep the part of the 2D sight segment (parameter s in [0, 1]) behind the dribbler plane.
      double s0 = 0.0;
      double s1 = 1.0;
      const double ahead_at_start = (start - robot.center).dot(robot.heading) - robot.front;
      const double ahead_rate = along.dot(robot.heading);
      if (ahead_rate == 0.0) {
        if (ahead_at_start > 0.0) continue;
      } else {
        const double s_plane = -ahead_at_start / ahead_rate;
        if (ahead_rate > 0.0) {
          s1 = std::min(s1, s_plane);
        } else {
          s0 = std::max(s0, s_plane);
        }
        if (s0 > s1) continue;
      }
      if (geom::intersects(geom::Segment{start + s0 * along, start + s1 * along},
                           geom::Circle{robot.center, robot.radius})) {
        return true;
      }
    }
    return false;
  };

  // Sample the disc of the ball's radius that faces the camera.
  const Vec3 to_eye = (eye - ball).normalized();
  Vec3 side = to_eye.cross(Vec3::UnitZ());
  if (side.squaredNorm() < 1e-12) side = Vec3::UnitX();  // camera straight above the ball
  side.normalize();
  const Vec3 up = to_eye.cross(side);
  int samples = 0;
  int visible = 0;
  Vec3 visible_sum = Vec3::Zero();
  constexpr int n = kBallSampleSteps;
  for (int i = -n; i <= n; ++i) {
    for (int j = -n; j <= n; ++j) {
      if (i * i + j * j >= n * n) continue;
      ++samples;
      const Vec3 offset = (radius / n) * (i * side + j * up);
      if (blocked(ball + offset)) continue;
      ++visible;
      visible_sum += offset;
    }
  }
  if (visible == 0) return 0.0;
  if (visible == samples) return 1.0;
  // The camera finds the middle of the visible pixels; keep the centre's height so the projection is
  // unchanged for a ball on the ground.
  Vec3 shift = visible_sum / visible;
  shift.z() = 0.0;
  visible_center = ball + shift;
  return static_cast<double>(visible) / samples;
}

}  // namespace ssl::sim
