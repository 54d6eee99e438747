// WorldModelNode: the DDS adapter of the world model. It owns the readers of vision.detection,
// vision.geometry, referee.state, and (in our team's partition) robot.feedback and robot.commands, and the
// writer of world.state in our partition; it converts samples once (convert.h), feeds the pure core and
// publishes. One thread: run() polls the readers (no user code on Fast DDS threads, so the core needs no
// lock).
//
// Publishing (publish_mode): `on_frame` (default) writes world.state after every camera frame, i.e. at the
// vision rate (cameras x frame rate, e.g. 4 x 75 Hz), each predicted to the host wall clock at publish
// time (latency compensation); `fixed_rate` writes at publish_rate Hz instead. Health ("world_model/<team>")
// once per second: output rate, per-frame processing time p50/p99, the core's counters, and WARN while no
// camera frame arrived within stale_vision_timeout.
//
//   auto node = WorldModelNode::create(participant, config, clock);
//   node->run(shutdown);
#pragma once

#include <memory>

#include <cstdint>
#include <optional>
#include <vector>

#include "libs/common/result.h"
#include "libs/common/shutdown.h"
#include "libs/dds/health.h"
#include "libs/dds/participant.h"
#include "libs/service/parameters.h"
#include "libs/time/clock.h"
#include "services/world_model/core/world_model.h"
#include "services/world_model/world_model_config.h"

namespace ssl::wm {

class WorldModelNode {
 public:
  /// Run-time parameters (world_model_runtime_parameters) arrive for "world_model/<team>" and apply from
  /// the next frame; saved to `saved_parameters` when asked.
  static Result<WorldModelNode> create(dds::Participant& participant, const WorldModelServiceConfig& config,
                                       time::Clock& wall_clock, const std::string& saved_parameters = "");

  /// Processes inputs and publishes until `shutdown` is requested.
  void run(ShutdownSignal& shutdown);

  /// One iteration: takes every pending sample, processes it, publishes; returns frames processed.
  std::size_t poll();

  const WorldModel& model() const { return model_; }

 private:
  WorldModelNode(const WorldModelServiceConfig& config, time::Clock& wall_clock,
                 dds::Reader<idl::vision::DetectionFrame> detections, dds::Reader<idl::vision::Geometry> geometry,
                 dds::Reader<idl::referee::RefereeState> referee, dds::Reader<idl::robot::RobotFeedback> feedback,
                 dds::Reader<idl::robot::RobotCommands> commands, dds::Writer<idl::world::WorldState> writer,
                 dds::HealthReporter health);
  void publish(time::Timestamp now);
  void report_health(time::Timestamp now);

  WorldModelServiceConfig config_;
  std::unique_ptr<service::LiveConfig<WorldModelServiceConfig>> parameters_;
  time::Clock* clock_;
  WorldModel model_;
  dds::Reader<idl::vision::DetectionFrame> detections_;
  dds::Reader<idl::vision::Geometry> geometry_;
  dds::Reader<idl::referee::RefereeState> referee_;
  dds::Reader<idl::robot::RobotFeedback> feedback_;
  dds::Reader<idl::robot::RobotCommands> commands_;
  dds::Writer<idl::world::WorldState> writer_;
  dds::HealthReporter health_;
  std::uint64_t sequence_ = 0;
  std::uint64_t published_in_period_ = 0;
  std::uint64_t malformed_ = 0;           // detection frames with a non-finite number
  std::uint64_t rejected_geometry_ = 0;   // vision.geometry samples the shared conversion refused
  std::uint64_t rejected_referee_ = 0;    // referee.state samples the shared conversion refused
  std::uint64_t write_failures_ = 0;
  std::vector<double> processing_times_;  // s, this health period
  std::optional<time::Timestamp> last_frame_wall_;
  time::Timestamp next_health_;
  time::Timestamp last_health_;  // the previous report, or the start: its rates are since then
  time::Timestamp next_publish_;
};

}  // namespace ssl::wm
