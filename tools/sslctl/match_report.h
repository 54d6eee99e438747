// MatchReport: what a match was, from its referee stream (and, for stalls, the ball): the score and the
// goals with their times, time in play / stopped / halted, restarts and commands, game events by type and
// team, the longest stall, side and stage changes, and whether the final whistle came. Pure: no sockets,
// no clocks, no protobuf; the caller feeds samples with their times (any one clock, e.g. a log file's
// receive times or the simulated clock of a lockstep match). `sslctl match report` feeds it from a live
// referee (and vision) multicast or an SSL log file; the lockstep match test and bench/match_lockstep feed
// it the built-in referee's state and the simulator's ball.
//
// Rules of the account:
//  * in play: NORMAL_START, FORCE_START and DIRECT_FREE_* (the game runs and the halves' clock with it);
//    halted: HALT (also the breaks between halves); stopped: everything else (STOP, placement, a kickoff or
//    penalty being prepared, a timeout). Each interval between two referee samples counts for the state of
//    the earlier one.
//  * each game event counts once: the Referee message repeats its game_events until the ball is in play
//    again, so events are recognised by ssl::referee::event_key (their id when the referee gave one).
//  * a stall: while in play, the longest time the ball stayed within kStallDistance of where it was; it
//    ends when the ball moves that far or play stops. Unknown without ball samples.
//
//   MatchReportBuilder builder;
//   builder.on_referee(state, t);    // every referee sample, in time order
//   builder.on_ball(position, t);    // every ball observation (m, vision frame), in time order
//   builder.on_frame(ball, robots, t);  // or the ball with every robot seen: also passes, shots, possession
//   std::cout << to_text(builder.report());
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "libs/geometry/vec2.h"
#include "libs/time/time.h"
#include "services/referee_gateway/core/types.h"
#include "tools/sslctl/play_account.h"

namespace ssl::sslctl {

struct MatchReport {
  struct TeamLine {
    std::string name;
    std::uint32_t score = 0;
    std::uint32_t fouls = 0;  // the referee's foul counter at the end
    std::uint32_t yellow_cards = 0;
    std::uint32_t red_cards = 0;
    TeamPlay play;  // passes, shots, possession (PlayAccount), from frames with robots
  };
  struct Goal {
    double at = 0;  // s since the first referee sample
    referee::Stage stage = referee::Stage::kNormalFirstHalf;
    std::optional<double> stage_time_left;  // s, as the referee said at the time
    referee::Team team = referee::Team::kUnknown;  // the scoring team
    std::optional<std::uint32_t> by_bot;
  };
  struct EventCount {
    referee::GameEventType type = referee::GameEventType::kUnknown;
    referee::Team team = referee::Team::kUnknown;
    std::uint32_t count = 0;
  };
  struct Stall {
    double seconds = 0;
    double from = 0;  // s since the first referee sample
    geom::Vec2 ball = geom::Vec2::Zero();
  };
  struct StageChange {
    double at = 0;
    referee::Stage stage = referee::Stage::kNormalFirstHalfPre;
  };
  struct SideChange {
    double at = 0;
    bool blue_on_positive_half = false;
  };

  std::string source;  // the referee's source_identifier
  std::uint64_t referee_samples = 0;
  std::uint64_t ball_samples = 0;
  std::uint64_t robot_frames = 0;  // frames with robots (on_frame): the play figures count
  double duration = 0;  // s from the first to the last referee sample
  TeamLine yellow;
  TeamLine blue;
  std::vector<Goal> goals;
  double in_play = 0;  // s
  double stopped = 0;  // s
  double halted = 0;   // s
  std::map<referee::Command, std::uint32_t> commands;  // how often each command was issued
  std::vector<EventCount> events;                       // by type, then team
  std::optional<Stall> longest_stall;                   // nullopt without ball samples
  std::vector<StageChange> stages;
  std::vector<SideChange> sides;
  referee::Stage final_stage = referee::Stage::kNormalFirstHalfPre;
  bool final_whistle = false;  // POST_GAME was reached
  std::uint64_t malformed = 0;  // packets that did not decode (set by the reader, not the builder)
};

class MatchReportBuilder {
 public:
  static constexpr double kStallDistance = 0.05;  // m: the ball moved (rules: in play after 0.05 m)

  /// One referee sample at `t` (samples before the previous one are ignored).
  void on_referee(const referee::RefereeState& state, time::Timestamp t);
  /// One ball observation at `t`, metres in any fixed frame.
  void on_ball(const geom::Vec2& ball, time::Timestamp t);
  /// The ball and every robot seen at `t` (the same frame): on_ball, and the play account's passes, shots
  /// and possession.
  void on_frame(const geom::Vec2& ball, std::span<const PlayAccount::Robot> robots, time::Timestamp t);
  /// The field's length and goal width (m), for shots.
  void set_field(double length, double goal_width) { play_.set_field(length, goal_width); }
  bool final_whistle() const { return report_.final_whistle; }
  /// Counts a packet that did not decode.
  void on_malformed() { ++report_.malformed; }

  /// The report so far (the open interval and stall up to the last sample included).
  MatchReport report() const;

 private:
  enum class Activity { kInPlay, kStopped, kHalted };
  static Activity activity_of(referee::Command command);
  double since_start(time::Timestamp t) const;
  void close_stall(time::Timestamp t);

  MatchReport report_;
  std::optional<time::Timestamp> first_;
  std::optional<time::Timestamp> last_;  // of the latest referee sample
  std::optional<referee::RefereeState> previous_;
  std::optional<Restart> prepared_;  // the kickoff or penalty prepared last, until another command than NORMAL_START
  std::set<std::string> seen_events_;
  std::map<std::pair<referee::GameEventType, referee::Team>, std::uint32_t> event_counts_;
  // The stall being measured: where the ball rests since when (only while in play).
  std::optional<std::pair<geom::Vec2, time::Timestamp>> stall_anchor_;
  std::optional<time::Timestamp> last_ball_time_;
  PlayAccount play_;
};

/// Human-readable, one fact per line.
std::string to_text(const MatchReport& report);
/// The same as one JSON object (names: the league's for commands, stages and event types).
std::string to_json(const MatchReport& report);

}  // namespace ssl::sslctl
