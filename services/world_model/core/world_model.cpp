#include "services/world_model/core/world_model.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ssl::wm {
namespace {

double seconds(time::Duration d) { return time::to_seconds(d); }

}  // namespace

WorldModel::WorldModel(const WorldModelConfig& config)
    : config_(config),
      frame_(TeamFrame::make(config.team, kBlueOnPositiveHalfAtStart)),
      game_(config.team),
      ball_(config.ball, config.ball_model),
      alignment_(config.camera_alignment),
      noise_(config.detection_noise, {config.robot.position_stddev, config.robot.orientation_stddev}),
      delays_(config.command_delay) {}

time::Timestamp WorldModel::to_vision(time::Timestamp now) const {
  return now - time::duration_from_seconds(offset_.value_or(0));
}

void WorldModel::on_geometry(const Geometry& geometry) {
  field_ = Field(geometry.field);
  alignment_.set_camera_centers(geometry.cameras);
  cameras_ = geometry.cameras;
  if (geometry.ball_model) ball_.set_model(*geometry.ball_model);
}

void WorldModel::on_referee(const RefereeInfo& referee, time::Timestamp now) {
  if (referee.blue_team_on_positive_half) {
    frame_ = TeamFrame::make(config_.team, *referee.blue_team_on_positive_half);
  }
  std::optional<Vec2> ball;
  if (ball_.initialised()) ball = ball_.predict_state(to_vision(now)).head<2>();
  game_.update(referee, frame_, ball);
}

void WorldModel::on_feedback(const RobotFeedback& feedback, time::Timestamp now) {
  if (feedback.id >= kMaxRobotsPerTeam) return;
  ball_in_dribbler_[feedback.id] = feedback.ball_in_dribbler;
  feedback_time_[feedback.id] = now;
}

void WorldModel::on_commands(std::span<const RobotCommand> commands, time::Timestamp now) {
  const time::Timestamp t = to_vision(now);
  for (const RobotCommand& command : commands) {
    if (command.id >= kMaxRobotsPerTeam) continue;
    Track& track = tracks(config_.team)[command.id];
    if (!track) continue;
    track->set_command(command, t);
    delays_.on_command(command.id, Vec2(command.forward, command.left), t);
  }
}

void WorldModel::reconfigure(const WorldModelConfig& config) {
  const TeamColor team = config_.team;
  config_ = config;
  config_.team = team;
}

void WorldModel::update_offset(double sample, time::Timestamp now) {
  constexpr double kWindow = 1.0;  // s of host time per smallest sample
  if (!offset_) {
    offset_ = sample;
    offset_window_ = {now, sample};
  } else {
    const double elapsed = std::max(0.0, seconds(now - offset_updated_));
    offset_ = std::min(sample, *offset_ + config_.offset_drift + offset_rise_rate_ * elapsed);
    offset_window_.smallest = std::min(offset_window_.smallest, sample);
  }
  offset_updated_ = now;
  if (seconds(now - offset_window_.start) < kWindow) return;
  if (last_offset_window_) {
    // A rise of the smallest sample within kJitter is delivery jitter: a steady clock keeps the estimate on
    // its smallest sample, as if nothing drifted.
    constexpr double kJitter = 0.001;  // s per window
    const double span = seconds(offset_window_.start - last_offset_window_->start);
    const double rise = offset_window_.smallest - last_offset_window_->smallest;
    offset_rise_rate_ = rise > kJitter ? std::min(rise / std::max(span, 1e-3), config_.vision_clock_slowness) : 0.0;
    // While the vision clock drifts, the smallest sample of a whole second is an offset the clocks had: the
    // estimate is at least that (it catches up with the drift before the rate was known).
    if (offset_rise_rate_ > 0) offset_ = std::max(*offset_, offset_window_.smallest);
  }
  last_offset_window_ = offset_window_;
  offset_window_ = {now, sample};
}

void WorldModel::on_detection(const DetectionFrame& frame, time::Timestamp now) {
  ++counters_.frames;
  const double sample = seconds(now - frame.sent_time);
  update_offset(sample, now);
  const time::Timestamp t = frame.capture_time;

  update_robots(TeamColor::kBlue, frame.camera_id, frame.robots_blue, t);
  update_robots(TeamColor::kYellow, frame.camera_id, frame.robots_yellow, t);
  predict_dribblers(t);
  update_ball(frame.camera_id, frame.balls, t);
  update_possession(t);
  drop_lost_tracks(t);
  if (ball_.initialised()) game_.update_ball(ball_.predict_state(t).head<2>(), t);
  delays_.update(t);
  if (delays_.delay() != delay_in_filters_) {
    delay_in_filters_ = delays_.delay();
    for (Track& track : tracks(config_.team)) {
      if (track && delay_in_filters_) track->set_command_delay(*delay_in_filters_);
    }
  }

  if (t >= stamp_.capture_time) {
    stamp_.capture_time = t;
    stamp_.receive_time = frame.receive_time;
    stamp_.camera_id = frame.camera_id;
    stamp_.frame_number = frame.frame_number;
  }
}

void WorldModel::update_robots(TeamColor team, std::uint32_t camera_id, std::span<const RobotDetection> detections,
                               time::Timestamp t) {
  TeamTracks& team_tracks = tracks(team);
  for (const RobotDetection& raw : detections) {
    ++counters_.robot_detections;
    if (raw.id >= kMaxRobotsPerTeam) continue;
    if (raw.confidence < config_.min_confidence) {
      ++counters_.low_confidence;
      continue;
    }
    // Robots seen by two cameras at once measure the cameras' calibration disagreement; every detection
    // is then corrected by its camera's estimated error.
    noise_.observe(camera_id, team, raw, t);
    const DetectionNoise noise = noise_.noise(camera_id);
    RobotDetection detection = raw;
    if (config_.align_cameras) {
      alignment_.observe(camera_id, ObjectKey::robot(team, raw.id), raw.position, t);
      detection.position = alignment_.correct(camera_id, raw.position);
    }
    if (team == config_.team) {
      const double heading = detection.has_orientation ? detection.orientation : std::nan("");
      delays_.on_position(detection.id, detection.position, heading, t);
    }
    Track& track = team_tracks[detection.id];
    if (!track) {
      track.emplace(config_.robot, detection, t, noise);
      if (team == config_.team && delay_in_filters_) track->set_command_delay(*delay_in_filters_);
      ++counters_.tracks_created;
      continue;
    }
    switch (track->update(detection, t, in_contact(team, detection.id, detection.position), noise)) {
      case RobotFilter::UpdateResult::kFused: break;
      case RobotFilter::UpdateResult::kOutlier: ++counters_.outliers_rejected; break;
      case RobotFilter::UpdateResult::kTeleported: ++counters_.teleports; break;
    }
  }
}

bool WorldModel::in_contact(TeamColor team, std::uint32_t id, const Vec2& position) const {
  const double reach = 2 * config_.robot_radius + config_.contact_margin;
  for (TeamColor other_team : {TeamColor::kBlue, TeamColor::kYellow}) {
    const TeamTracks& others = tracks(other_team);
    for (std::uint32_t other = 0; other < kMaxRobotsPerTeam; ++other) {
      if (!others[other] || (other_team == team && other == id)) continue;
      if ((others[other]->filter().state().head<2>() - position).squaredNorm() < reach * reach) return true;
    }
  }
  // The walls stand at the outer edge of the boundary strip (wider behind the goal lines in division A).
  const FieldSize& size = field_.size();
  const double wall_x = size.wall_half_length();
  const double wall_y = size.wall_half_width();
  const double wall_reach = config_.robot_radius + config_.contact_margin;
  return std::abs(position.x()) > wall_x - wall_reach || std::abs(position.y()) > wall_y - wall_reach;
}

Vec2 WorldModel::dribbler_point(const RobotFilter::State& x) const {
  const double reach = config_.center_to_dribbler + field_.size().ball_radius;
  return {x(0) + reach * std::cos(x(2)), x(1) + reach * std::sin(x(2))};
}

std::optional<Vec2> WorldModel::held_ball_position(time::Timestamp t, std::uint32_t* holder,
                                                   Vec2* velocity) const {
  // Feedback times are on the host clock: compare with the vision instant mapped back.
  const time::Timestamp now = t + time::duration_from_seconds(offset_.value_or(0));
  const TeamTracks& ours = tracks(config_.team);
  for (std::uint32_t id = 0; id < kMaxRobotsPerTeam; ++id) {
    if (!ball_in_dribbler_[id] || !ours[id]) continue;
    if (std::abs(seconds(now - feedback_time_[id])) > config_.feedback_timeout) continue;
    const RobotFilter::State x = ours[id]->predict_state(t);
    if (holder) *holder = id;
    if (velocity) *velocity = x.segment<2>(3);
    return dribbler_point(x);
  }
  return std::nullopt;
}

void WorldModel::update_ball(std::uint32_t camera_id, std::span<const BallDetection> detections,
                             time::Timestamp t) {
  // Pick the detection closest to the prediction (after the camera's correction); the rest are rejected.
  // Balls only receive the correction: partly hidden balls look shifted differently in each camera, so
  // they would disturb the estimate.
  std::optional<BallDetection> best;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (const BallDetection& raw : detections) {
    ++counters_.ball_detections;
    if (raw.confidence < config_.min_confidence) {
      ++counters_.low_confidence;
      continue;
    }
    BallDetection detection = raw;
    if (config_.align_cameras) detection.position = alignment_.correct(camera_id, raw.position);
    // In a reconstructed flight, compare with where this camera sees the flying ball.
    const std::optional<Vec2> flying = chip_projection(camera_id, t);
    const double d2 = flying ? (detection.position - *flying).squaredNorm() / 1e-4
                             : ball_.distance2(detection.position, t);
    if (d2 < best_d2) {
      if (best) ++counters_.outliers_rejected;
      best = detection;
      best_d2 = d2;
    } else {
      ++counters_.outliers_rejected;
    }
  }

  Vec2 holder_velocity = Vec2::Zero();
  const std::optional<Vec2> held = held_ball_position(t, nullptr, &holder_velocity);
  if (held && (!best || (best->position - *held).norm() > config_.dribbler_capture_distance)) {
    ball_.place(*held, holder_velocity, t);
    ++counters_.dribbler_placements;
    return;
  }
  if (!best) return;
  if (track_chip(camera_id, best->position, t)) return;  // airborne: the ground filter waits for the landing

  bool near_robot = false;
  for (const TeamTracks& team_tracks : tracks_) {
    for (const Track& track : team_tracks) {
      if (track && (track->filter().state().head<2>() - best->position).norm() < config_.near_robot_distance) {
        near_robot = true;
      }
    }
  }
  const BallFilter::UpdateResult result = ball_.update(best->position, t, near_robot);
  if (result != BallFilter::UpdateResult::kOutlier) carrier_ = dribbler_touching(best->position);
  switch (result) {
    case BallFilter::UpdateResult::kInitialised:
    case BallFilter::UpdateResult::kFused: break;
    case BallFilter::UpdateResult::kOutlier: ++counters_.outliers_rejected; break;
    case BallFilter::UpdateResult::kRestarted: ++counters_.ball_restarts; break;
    case BallFilter::UpdateResult::kKick:
      ++counters_.kicks_detected;
      start_chip_tracking();
      break;
  }
}

void WorldModel::predict_dribblers(time::Timestamp t) {
  for (std::size_t team = 0; team < tracks_.size(); ++team) {
    for (std::uint32_t id = 0; id < kMaxRobotsPerTeam; ++id) {
      const Track& track = tracks_[team][id];
      dribblers_[team][id] = track ? std::optional<Vec2>(dribbler_point(track->predict_state(t))) : std::nullopt;
    }
  }
}

std::optional<WorldModel::RobotKey> WorldModel::dribbler_touching(const Vec2& ball) const {
  std::optional<RobotKey> touching;
  double best = config_.possession_distance;
  for (TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) {
    for (std::uint32_t id = 0; id < kMaxRobotsPerTeam; ++id) {
      const std::optional<Vec2>& dribbler = dribblers_[team_index(team)][id];
      if (!dribbler) continue;
      const double gap = (*dribbler - ball).norm();
      if (gap <= best) {
        best = gap;
        touching = RobotKey{team, id};
      }
    }
  }
  return touching;
}

void WorldModel::start_chip_tracking() {
  const std::optional<KickEvent>& kick = ball_.last_kick();
  if (!kick) return;
  ChipKick prior{.position = kick->position, .time = kick->time};
  // The kicker's heading is the chip's horizontal direction (the post-kick detections are projections
  // of a flying ball, so their direction can be off).
  double nearest = config_.robot_radius + 0.15;
  for (const TeamTracks& team_tracks : tracks_) {
    for (const Track& track : team_tracks) {
      if (!track) continue;
      const RobotFilter::State x = track->predict_state(kick->time);
      const double distance = (x.head<2>() - kick->position).norm();
      if (distance < nearest) {
        nearest = distance;
        prior.direction = Vec2(std::cos(x(2)), std::sin(x(2)));
      }
    }
  }
  chip_.estimator.reset(prior);
  chip_.active = true;
  chip_.latched = false;
  chip_.fit.reset();
  chip_.kick_time = kick->time;
}

std::optional<Vec2> WorldModel::chip_projection(std::uint32_t camera_id, time::Timestamp t) const {
  if (!chip_.latched || !chip_.fit || t >= chip_.fit->landing_time) return std::nullopt;
  const Vec3* camera = camera_position(camera_id);
  if (camera == nullptr) return std::nullopt;
  // SSL-Vision reports where the ray from the camera through the ball meets the plane z = ball radius.
  const Vec3 ball = chip_.fit->position_at(t);
  const double radius = field_.size().ball_radius;
  const double scale = (camera->z() - radius) / std::max(camera->z() - ball.z(), 1e-3);
  return Vec2(camera->x() + (ball.x() - camera->x()) * scale, camera->y() + (ball.y() - camera->y()) * scale);
}

bool WorldModel::track_chip(std::uint32_t camera_id, const Vec2& detection, time::Timestamp t) {
  if (!chip_.active) return false;
  if (seconds(t - chip_.kick_time) > config_.chip_window) {
    chip_.active = false;  // never classified, or the flight is over: the ground filter has the ball
    return false;
  }
  if (const Vec3* camera = camera_position(camera_id)) {
    chip_.estimator.add({.detection = detection, .camera = *camera, .t_capture = t});
  }
  if (!chip_.latched) {
    const ChipClassification result = chip_.estimator.classify();
    if (!result.is_chip || !result.chip) return false;
    chip_.latched = true;  // near the threshold the decision may flip back: keep the first one
    ++counters_.chips_detected;
  }
  if (const std::optional<ChipFit> fit = chip_.estimator.fit()) chip_.fit = fit;
  if (!chip_.fit) return false;
  chip_.last_update = t;
  // Landed once past the touchdown by more than its uncertainty (an early fit may still move it).
  if (t < chip_.fit->landing_time + time::duration_from_seconds(3 * chip_.fit->landing_time_stddev)) return true;
  // Landed: the ground filter takes over where and how fast the reconstructed flight says.
  const ChipState landed = chip_.fit->state_at(t);
  ball_.place(landed.position.head<2>(), landed.velocity.head<2>(), t);
  chip_.active = false;
  return true;
}

const Vec3* WorldModel::camera_position(std::uint32_t camera_id) const {
  for (const CameraInfo& camera : cameras_) {
    if (camera.camera_id == camera_id) return &camera.position;
  }
  return nullptr;
}

void WorldModel::update_possession(time::Timestamp t) {
  if (!ball_.initialised()) return;
  std::uint32_t holder = 0;
  if (held_ball_position(t, &holder, nullptr)) {
    possession_ = Possession::kFriendly;
    possessing_robot_ = holder;
    return;
  }
  const Vec2 ball = ball_.predict_state(t).head<2>();
  std::optional<std::uint32_t> friendly, enemy;
  double best_friendly = config_.possession_distance, best_enemy = config_.possession_distance;
  for (TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) {
    for (std::uint32_t id = 0; id < kMaxRobotsPerTeam; ++id) {
      const std::optional<Vec2>& dribbler = dribblers_[team_index(team)][id];
      if (!dribbler) continue;
      // Ball surface to the dribbler's front point (dribbler_point is where the ball centre sits).
      const double gap = (*dribbler - ball).norm();
      const bool ours = team == config_.team;
      double& best = ours ? best_friendly : best_enemy;
      if (gap <= best) {
        best = gap;
        (ours ? friendly : enemy) = id;
      }
    }
  }
  if (friendly && enemy) {
    possession_ = Possession::kContested;
    possessing_robot_ = best_friendly <= best_enemy ? friendly : enemy;
  } else if (friendly) {
    possession_ = Possession::kFriendly;
    possessing_robot_ = friendly;
  } else if (enemy) {
    possession_ = Possession::kEnemy;
    possessing_robot_ = enemy;
  }
  // Nobody touches it: the last toucher stays (possession means "has, or last touched").
}

void WorldModel::drop_lost_tracks(time::Timestamp t) {
  for (TeamTracks& team_tracks : tracks_) {
    for (Track& track : team_tracks) {
      if (track && seconds(t - track->last_update()) > config_.robot_lost_timeout) {
        track.reset();
        ++counters_.tracks_lost;
      }
    }
  }
}

std::optional<KickEvent> WorldModel::last_kick() const {
  std::optional<KickEvent> kick = ball_.last_kick();
  if (kick) {
    kick->position = frame_.point(kick->position);
    kick->velocity = frame_.vector(kick->velocity);
  }
  return kick;
}

WorldState WorldModel::state(time::Timestamp now) const { return state_at_vision_time(to_vision(now)); }

WorldState WorldModel::state_at_vision_time(time::Timestamp t) const {
  WorldState world;
  world.team = config_.team;
  world.stamp = stamp_;
  world.predicted_to = t;
  world.flipped = frame_.flipped();
  world.possession = possession_;
  world.possessing_robot = possessing_robot_;
  world.command_delay = delays_.delay();

  for (TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) {
    std::vector<RobotState>& out = team == config_.team ? world.friendly : world.enemy;
    const TeamTracks& team_tracks = tracks(team);
    for (std::uint32_t id = 0; id < kMaxRobotsPerTeam; ++id) {
      if (!team_tracks[id]) continue;
      const RobotFilter::State x = team_tracks[id]->predict_state(t);
      const double age = std::max(0.0, seconds(stamp_.capture_time - team_tracks[id]->last_update()));
      RobotState robot;
      robot.id = id;
      robot.position = frame_.point(x.head<2>());
      robot.orientation = frame_.angle(x(2));
      robot.velocity = frame_.vector(x.segment<2>(3));
      robot.angular_velocity = x(5);
      robot.visible = age <= config_.visible_timeout;
      robot.confidence = std::clamp(1.0 - age / config_.robot_lost_timeout, 0.0, 1.0);
      out.push_back(robot);
    }
  }

  if (ball_.initialised()) {
    const double age = std::max(0.0, seconds(stamp_.capture_time - ball_.last_update()));
    if (age <= config_.ball_lost_timeout) {
      world.has_ball = true;
      BallFilter::State x = ball_.predict_state(t);
      Vec2 position = x.head<2>();
      Vec2 velocity = x.tail<2>();
      Vec2 holder_velocity = Vec2::Zero();
      if (const std::optional<Vec2> held = held_ball_position(t, nullptr, &holder_velocity)) {
        position = *held;
        velocity = holder_velocity;
        world.ball.in_dribbler = true;
      } else if (const Track* carrier = carrier_ ? &tracks(carrier_->team)[carrier_->id] : nullptr;
                 age > config_.carried_ball_after && age <= config_.carried_ball_timeout && carrier != nullptr &&
                 *carrier) {
        // Hidden right after it was seen at a robot's dribbler: that robot has it (an opponent dribbling
        // it, or ours without feedback), so it moves with the robot, under the camera's view of it.
        const RobotFilter::State carrier_state = (*carrier)->predict_state(t);
        position = dribbler_point(carrier_state);
        velocity = carrier_state.segment<2>(3);
      } else {
        // Predicted through a hidden stretch: a ball cannot pass through a robot; stop it at its hull.
        const double min_gap = config_.robot_radius + field_.size().ball_radius;
        for (const TeamTracks& team_tracks : tracks_) {
          for (const Track& track : team_tracks) {
            if (!track) continue;
            const Vec2 centre = track->predict_state(t).head<2>();
            const Vec2 offset = position - centre;
            if (offset.norm() < min_gap && offset.norm() > 1e-9 && age > 0) {
              position = centre + offset.normalized() * min_gap;
              velocity = track->predict_state(t).segment<2>(3);
            }
          }
        }
      }
      world.ball.position = Vec3(frame_.point(position).x(), frame_.point(position).y(),
                                 field_.size().ball_radius);
      const Vec2 v = frame_.vector(velocity);
      world.ball.velocity = Vec3(v.x(), v.y(), 0);
      world.ball.visible = age <= config_.visible_timeout;
      world.ball.confidence = std::clamp(1.0 - age / config_.ball_lost_timeout, 0.0, 1.0);
      world.ball.last_seen = ball_.last_update();
      if (chip_.active && chip_.latched && chip_.fit) {
        const ChipState flying = chip_.fit->state_at(t);
        world.ball.position = Vec3(frame_.point(flying.position.head<2>()).x(),
                                   frame_.point(flying.position.head<2>()).y(), flying.position.z());
        const Vec2 flying_velocity = frame_.vector(flying.velocity.head<2>());
        world.ball.velocity = Vec3(flying_velocity.x(), flying_velocity.y(), flying.velocity.z());
        world.ball.airborne = flying.position.z() > field_.size().ball_radius + 1e-3;
        world.ball.in_dribbler = false;
        const double flight_age = std::max(0.0, seconds(stamp_.capture_time - chip_.last_update));
        world.ball.visible = flight_age <= config_.visible_timeout;
        world.ball.last_seen = chip_.last_update;
      }
    }
  }
  return world;
}

}  // namespace ssl::wm
