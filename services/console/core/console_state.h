// ConsoleState: the latest of everything the console shows, and the page's JSON for it (PROTOCOL.md). Pure:
// the adapter feeds it converted samples with the console host's wall-clock time `now`; it holds no
// thread, socket or clock. Not thread-safe: the adapter serialises calls.
//
//   ConsoleState state(options);
//   state.on_world(TeamColor::kBlue, world, now);
//   std::string frame = state.frame_json(now).dump();   // one SSE "frame" event
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "libs/domain/field.h"
#include "services/console/core/event_log.h"
#include "services/console/core/types.h"
#include "services/referee_gateway/builtin/profile.h"
#include "services/referee_gateway/core/types.h"
#include "tools/sslctl/match_report.h"

namespace ssl::console {

struct ConsoleStateOptions {
  double battery_low_volts = 14.0;   // a robot's battery below this is flagged
  double link_low_quality = 0.5;     // a robot's radio link quality below this is flagged
  double stale_after = 3.0;          // s without a health report: the service is shown as lost
};

class ConsoleState {
 public:
  explicit ConsoleState(ConsoleStateOptions options = {}) : options_(options) {}

  // ---- inputs (now: console host wall clock) ----
  void on_geometry(const FieldGeometry& field);
  void on_vision(const CameraView& camera, time::Timestamp now);
  void on_world(TeamColor team, const TeamWorld& world, time::Timestamp now);
  void on_debug(TeamColor team, const TeamDebug& debug);
  /// Returns true when the referee state changed in what the page shows (command, score, stage, ...).
  bool on_referee(const referee::RefereeState& state, time::Timestamp now);
  void on_referee_event(const referee::RefereeEvent& event, time::Timestamp now);
  void on_health(const ServiceHealth& health, time::Timestamp now);
  void on_feedback(const RobotFeedbackView& feedback, time::Timestamp now);
  void on_estop(const EstopView& estop, time::Timestamp now);
  /// Returns true when it changed what the page shows.
  bool on_parameters(const ParameterStateView& state);
  /// An operator action the console performed (or refused): logged as kind "operator".
  void on_operator(std::string text, time::Timestamp now);
  void set_profile(const referee::RefereeProfile& profile) { profile_ = profile; }

  /// Log entries added since the last call (for the stream's "event" messages), oldest first.
  std::vector<LogEntry> take_new_entries();

  // ---- outputs: the data of each stream event ----
  nlohmann::json hello_json(bool operator_allowed, bool simulator) const;
  nlohmann::json geometry_json() const;
  nlohmann::json frame_json(time::Timestamp now) const;
  nlohmann::json referee_json() const;
  nlohmann::json log_json() const;
  nlohmann::json health_json(time::Timestamp now) const;
  nlohmann::json report_json() const;
  nlohmann::json params_json() const;
  /// The last state of `target`, if it reported one.
  const ParameterStateView* parameters(const std::string& target) const;

  const std::optional<referee::RefereeState>& referee() const { return referee_; }
  /// The ball as raw vision sees it now (the first ball of the freshest camera frame), vision frame.
  std::optional<geom::Vec2> vision_ball() const;
  /// Robot `id` of `team` as raw vision sees it (for placing a robot: its heading).
  std::optional<RobotView> vision_robot(TeamColor team, std::uint32_t id) const;

 private:
  struct TeamSlot {
    std::optional<TeamWorld> world;
    time::Timestamp world_at;
    std::optional<TeamDebug> debug;
  };
  struct HealthSlot {
    ServiceHealth health;
    time::Timestamp at;
  };
  struct FeedbackSlot {
    RobotFeedbackView feedback;
    time::Timestamp at;
  };
  struct CameraSlot {
    CameraView camera;
    time::Timestamp at;
  };

  void log(LogEntry entry);
  nlohmann::json team_json(TeamColor team, const TeamSlot& slot, time::Timestamp now) const;
  nlohmann::json keep_out_json() const;

  ConsoleStateOptions options_;
  FieldGeometry field_;
  bool has_field_ = false;
  std::map<std::uint32_t, CameraSlot> cameras_;
  std::map<TeamColor, TeamSlot> teams_;
  std::optional<referee::RefereeState> referee_;
  std::map<std::string, HealthSlot> health_;
  std::map<std::pair<TeamColor, std::uint32_t>, FeedbackSlot> feedback_;
  std::optional<EstopView> estop_;
  std::map<std::string, ParameterStateView> parameters_;
  std::optional<referee::RefereeProfile> profile_;
  EventLog log_;
  std::vector<LogEntry> new_entries_;
  sslctl::MatchReportBuilder report_;
};

}  // namespace ssl::console
