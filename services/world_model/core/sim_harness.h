// Test-only harness: drives ssl::sim::Simulator in-process and feeds its vision frames to a WorldModel,
// keeping the true world at every capture instant so that tests and the benchmark can compare the raw
// detections and the filtered state with the ground truth. Simulated clock = vision clock = host clock.
//
//   SimHarness h({.robots_per_team = 2, .realism = sim::RealismConfig::realistic(), .seed = 7});
//   h.run(2s, [&](SimHarness& h) { h.command(...); }, [&](const sim::DetectionFrame& f) { ... });
#pragma once

#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <vector>

#include "services/simulator/core/simulator.h"
#include "services/world_model/core/world_model.h"

namespace ssl::wm::testing {

inline DetectionFrame from_sim(const sim::DetectionFrame& in) {
  DetectionFrame out;
  out.camera_id = in.camera_id;
  out.frame_number = in.frame_number;
  out.capture_time = in.capture_time;
  out.sent_time = in.sent_time;
  out.receive_time = in.sent_time;
  for (const sim::BallDetection& b : in.balls) {
    out.balls.push_back({.position = Vec2(b.x, b.y), .z = b.z, .has_z = b.has_z, .confidence = b.confidence});
  }
  auto robots = [](const std::vector<sim::RobotDetection>& detections, std::vector<RobotDetection>& into) {
    for (const sim::RobotDetection& r : detections) {
      into.push_back({.id = r.robot_id, .position = Vec2(r.x, r.y), .orientation = r.orientation,
                      .has_orientation = true, .confidence = r.confidence});
    }
  };
  robots(in.robots_yellow, out.robots_yellow);
  robots(in.robots_blue, out.robots_blue);
  return out;
}

inline Geometry from_sim(const sim::GeometryData& in) {
  Geometry out;
  out.field = in.field;
  out.field.ball_radius = in.ball_radius;
  out.field.max_robot_radius = in.max_robot_radius;
  for (const auto& c : in.calibrations) out.cameras.push_back({c.camera_id, c.derived_world});
  out.ball_model = BallModel{in.ball_models.acc_slide, in.ball_models.acc_roll, in.ball_models.k_switch};
  return out;
}

/// Root mean square of the values added (errors, in their unit).
struct Rms {
  double sum = 0;
  std::size_t n = 0;
  void add(double e) {
    sum += e * e;
    ++n;
  }
  void add(const Rms& other) {
    sum += other.sum;
    n += other.n;
  }
  double value() const { return n ? std::sqrt(sum / static_cast<double>(n)) : 0; }
};

/// The hard continuous curves the accuracy test and the benchmark drive: a LOCAL velocity command (m/s,
/// rad/s) whose speed, sideways part and turn rate all change all the time, at time t (s); `phase` (rad)
/// sets each robot apart.
inline sim::RobotCommand curve_command(double t, double phase) {
  sim::RobotCommand c;
  c.move = sim::RobotCommand::Move::kLocalVelocity;
  c.velocity = sim::Vec3(1.2 + 0.6 * std::sin(0.9 * t + phase), 0.3 * std::sin(1.3 * t + phase),
                         2.0 * std::sin(0.7 * t + 2 * phase));
  return c;
}

struct HarnessOptions {
  std::uint32_t robots_per_team = 0;
  sim::RealismConfig realism = sim::RealismConfig::realistic();
  sim::RobotResponse response = sim::RobotResponse::ideal();  // how robots answer commands
  std::uint64_t seed = 1;
  int camera_count = 4;
  sim::FieldGeometry field = sim::FieldGeometry::division_a();
};

class SimHarness {
 public:
  static constexpr time::Duration kStep = std::chrono::milliseconds(2);
  static constexpr time::Duration kTruthKept = std::chrono::seconds(2);

  explicit SimHarness(const HarnessOptions& options, const WorldModelConfig& config = {})
      : sim_(make_options(options)), model_(config) {
    model_.on_geometry(from_sim(sim_.geometry()));
    const sim::WorldSnapshot first = sim_.snapshot();
    truth_[first.time.nanoseconds()] = first;
  }

  sim::Simulator& sim() { return sim_; }
  const sim::Simulator& sim() const { return sim_; }
  WorldModel& model() { return model_; }
  const WorldModel& model() const { return model_; }
  time::Timestamp now() const { return sim_.time(); }

  /// The true world at a capture instant (the latest snapshot at or before t; kept for kTruthKept).
  const sim::WorldSnapshot& truth(time::Timestamp t) const {
    auto it = truth_.upper_bound(t.nanoseconds());
    if (it != truth_.begin()) --it;
    return it->second;
  }

  /// Steps the simulator for `duration`; before each step calls `before_step`, and after each frame was
  /// given to the model calls `after_frame(frame)`.
  void run(time::Duration duration, const std::function<void(SimHarness&)>& before_step,
           const std::function<void(const sim::DetectionFrame&)>& after_frame) {
    const time::Timestamp end = now() + duration;
    while (now() < end) {
      if (before_step) before_step(*this);
      sim::StepOutput out = sim_.step(kStep);
      const sim::WorldSnapshot snapshot = sim_.snapshot();
      truth_[snapshot.time.nanoseconds()] = snapshot;
      // Frames are captured at most a vision delay ago: older truth is not asked for (a whole match would
      // otherwise keep every 2 ms snapshot).
      truth_.erase(truth_.begin(), truth_.lower_bound((snapshot.time - kTruthKept).nanoseconds()));
      for (const sim::DetectionFrame& frame : out.frames) {
        model_.on_detection(from_sim(frame), now());
        if (after_frame) after_frame(frame);
      }
    }
  }

  /// Sets local-velocity commands for `team` in the simulator and, for our team, tells the model.
  void command(TeamColor team, const std::vector<sim::RobotCommandFor>& commands, bool tell_model) {
    sim_.set_commands(team, commands);
    if (!tell_model) return;
    std::vector<RobotCommand> ours;
    for (const auto& c : commands) {
      ours.push_back({c.id, c.command.velocity.x(), c.command.velocity.y(), c.command.velocity.z()});
    }
    model_.on_commands(ours, now());
  }

 private:
  static sim::SimulatorOptions make_options(const HarnessOptions& options) {
    sim::SimulatorOptions out;
    out.field = options.field;
    out.robots_per_team = options.robots_per_team;
    out.seed = options.seed;
    out.vision.camera_count = options.camera_count;
    out.vision.realism = options.realism;
    out.response = options.response;
    return out;
  }

  sim::Simulator sim_;
  WorldModel model_;
  std::map<std::int64_t, sim::WorldSnapshot> truth_;
};

}  // namespace ssl::wm::testing
