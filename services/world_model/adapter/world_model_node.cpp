#include "services/world_model/adapter/world_model_node.h"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <string>

#include "libs/common/percentile.h"
#include "services/world_model/adapter/convert.h"

namespace ssl::wm {
namespace {

using namespace std::chrono_literals;

}  // namespace

Result<WorldModelNode> WorldModelNode::create(dds::Participant& participant, const WorldModelServiceConfig& config,
                                              time::Clock& wall_clock, const std::string& saved_parameters) {
  namespace topics = dds::topics;
  auto detections = participant.make_reader(topics::kVisionDetection);
  if (!detections) return detections.error();
  auto geometry = participant.make_reader(topics::kVisionGeometry);
  if (!geometry) return geometry.error();
  auto referee = participant.make_reader(topics::kRefereeState);
  if (!referee) return referee.error();
  auto feedback = participant.make_reader(topics::kRobotFeedback, config.team);
  if (!feedback) return feedback.error();
  auto commands = participant.make_reader(topics::kRobotCommands, config.team);
  if (!commands) return commands.error();
  auto writer = participant.make_writer(topics::kWorldState, config.team);
  if (!writer) return writer.error();
  const std::string instance = "world_model/" + std::string(to_string(config.team));
  auto health = dds::HealthReporter::create(participant, instance);
  if (!health) return health.error();
  // Up (READY) once it hears a vision gateway.
  health->ready_when([reader = *detections] { return reader.counters().matched_writers > 0; });
  health->exit_when_stalled();
  auto params = world_model_runtime_parameters(config);
  if (!params) return params.error();
  auto live = service::LiveConfig<WorldModelServiceConfig>::create(participant, instance, std::move(*params),
                                                                    saved_parameters);
  if (!live) return live.error();
  WorldModelNode node(config, wall_clock, std::move(*detections), std::move(*geometry), std::move(*referee),
                      std::move(*feedback), std::move(*commands), std::move(*writer), std::move(*health));
  node.parameters_ = std::move(*live);
  return node;
}

WorldModelNode::WorldModelNode(const WorldModelServiceConfig& config, time::Clock& wall_clock,
                               dds::Reader<idl::vision::DetectionFrame> detections,
                               dds::Reader<idl::vision::Geometry> geometry,
                               dds::Reader<idl::referee::RefereeState> referee,
                               dds::Reader<idl::robot::RobotFeedback> feedback,
                               dds::Reader<idl::robot::RobotCommands> commands,
                               dds::Writer<idl::world::WorldState> writer, dds::HealthReporter health)
    : config_(config),
      clock_(&wall_clock),
      model_(config.core),
      detections_(std::move(detections)),
      geometry_(std::move(geometry)),
      referee_(std::move(referee)),
      feedback_(std::move(feedback)),
      commands_(std::move(commands)),
      writer_(std::move(writer)),
      health_(std::move(health)) {
  processing_times_.reserve(4096);
  last_health_ = clock_->now();
  next_health_ = last_health_ + health_.period();
  next_publish_ = clock_->now();
}

std::size_t WorldModelNode::poll() {
  if (std::optional<WorldModelServiceConfig> next = parameters_->poll()) {
    config_ = *next;
    model_.reconfigure(config_.core);
  }
  for (auto& s : geometry_.take()) {
    Result<Geometry> geometry = from_idl(s.data);
    if (geometry) {
      model_.on_geometry(*geometry);
    } else {
      ++rejected_geometry_;
    }
  }
  for (auto& s : referee_.take()) {
    Result<RefereeInfo> referee = from_idl(s.data);
    if (referee) {
      model_.on_referee(*referee, clock_->now());
    } else {
      ++rejected_referee_;
    }
  }
  for (auto& s : feedback_.take()) model_.on_feedback(from_idl(s.data), clock_->now());
  for (auto& s : commands_.take()) {
    // In force from when the planner published them (same host clock family), unless that stamp is
    // missing or implausible (another host with a skewed clock): then from now.
    const time::Timestamp now = clock_->now();
    const time::Timestamp published = time::Timestamp::from_nanoseconds(s.data.publish_unix_ns());
    const bool plausible = s.data.publish_unix_ns() > 0 && std::abs(time::to_seconds(now - published)) < 0.1;
    model_.on_commands(from_idl(s.data), plausible ? std::min(published, now) : now);
  }
  std::size_t frames = 0;
  dds::Sample<idl::vision::DetectionFrame> sample;
  while (detections_.take_next(sample)) {
    const std::optional<DetectionFrame> frame = from_idl(sample.data);
    if (!frame) {
      ++malformed_;
      continue;
    }
    const time::Timestamp start = clock_->now();
    model_.on_detection(*frame, start);
    processing_times_.push_back(time::to_seconds(clock_->now() - start));
    last_frame_wall_ = start;
    ++frames;
    if (config_.publish_mode == PublishMode::kOnFrame) publish(clock_->now());
  }
  const time::Timestamp now = clock_->now();
  if (config_.publish_mode == PublishMode::kFixedRate && now >= next_publish_ && last_frame_wall_) {
    publish(now);
    next_publish_ = std::max(next_publish_ + time::duration_from_seconds(1.0 / config_.publish_rate), now);
  }
  if (now >= next_health_) {
    report_health(now);
    next_health_ = now + health_.period();
  }
  return frames;
}

void WorldModelNode::publish(time::Timestamp now) {
  const WorldState world = model_.state(now);
  if (!writer_.write(to_idl(world, ++sequence_, now.nanoseconds()))) ++write_failures_;
  ++published_in_period_;
}

void WorldModelNode::report_health(time::Timestamp now) {
  const WorldModelCounters& c = model_.counters();
  dds::HealthReport report;
  const bool stale =
      !last_frame_wall_ || time::to_seconds(now - *last_frame_wall_) > config_.stale_vision_timeout;
  report.level = stale ? dds::HealthLevel::kWarn : dds::HealthLevel::kOk;
  report.status = stale ? "vision stale" : "running";
  // Our robots' measured delay from command to motion, in the status that sslctl health and the console show.
  if (const std::optional<double> delay = model_.command_delay()) {
    report.status += ", command delay " + std::to_string(std::lround(*delay * 1e3)) + " ms";
  }
  report.rate_hz = static_cast<double>(published_in_period_) / std::max(1e-3, time::to_seconds(now - last_health_));
  report.latency_p50 = percentile(processing_times_, 0.5);
  report.latency_p99 = percentile(processing_times_, 0.99);
  report.errors = write_failures_;
  report.dropped = malformed_ + rejected_geometry_ + rejected_referee_ + c.low_confidence;
  report.counters = {{"frames", c.frames},
                     {"outliers_rejected", c.outliers_rejected},
                     {"tracks_created", c.tracks_created},
                     {"tracks_lost", c.tracks_lost},
                     {"teleports", c.teleports},
                     {"kicks_detected", c.kicks_detected},
                     {"ball_restarts", c.ball_restarts},
                     {"dribbler_placements", c.dribbler_placements},
                     {"malformed_frames", malformed_},
                     {"rejected_geometry", rejected_geometry_},
                     {"rejected_referee", rejected_referee_},
                     {"low_confidence_detections", c.low_confidence}};
  // Each camera's robot detection noise as the filters assume it (estimated, or configured until enough).
  for (const auto& camera : model_.detection_noise().estimates()) {
    const std::string prefix = "camera" + std::to_string(camera.camera_id);
    report.counters.emplace_back(prefix + "_robot_noise_um",
                                 static_cast<std::uint64_t>(std::lround(camera.noise.position_stddev * 1e6)));
    report.counters.emplace_back(prefix + "_heading_noise_mrad",
                                 static_cast<std::uint64_t>(std::lround(camera.noise.orientation_stddev * 1e3)));
  }
  // The same delay as a counter (what the planner compensates).
  if (const std::optional<double> delay = model_.command_delay()) {
    report.counters.emplace_back("command_delay_ms", static_cast<std::uint64_t>(std::lround(*delay * 1e3)));
  }
  (void)health_.publish(report);
  processing_times_.clear();
  published_in_period_ = 0;
  last_health_ = now;
}

void WorldModelNode::run(ShutdownSignal& shutdown) {
  while (!shutdown.requested()) {
    detections_.wait_for_data(5ms);
    poll();
  }
}

}  // namespace ssl::wm
