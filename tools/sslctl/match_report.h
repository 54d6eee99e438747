// MatchReport: what a match was, from its referee stream (and vision: the ball, the robots): the score and
// the goals with their times, time in play / stopped / halted and in play from vision, restarts and
// commands, game events by type and team, each avoidable foul, placements and balls out per team, the
// longest stall, the closest two robots and the contact frames, side and stage changes, and whether the
// final whistle came. Pure: no sockets, no clocks, no protobuf; the caller feeds samples with their times
// (any one clock, e.g. a log file's receive times or the simulated clock of a lockstep match). `sslctl match
// report` feeds it from a live referee (and vision) multicast or an SSL log file; the lockstep match test and
// bench/match_lockstep feed it the built-in referee's state and the simulator's ball.
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
//  * in play from vision: time in play (as above) with the ball seen inside the field (not yet wholly over a
//    field line). Each interval between two ball observations counts for the earlier one, at most
//    kBallUnseenAfter (a ball unseen longer is not seen). Unknown without the field's size (set_field).
//  * robots (on_frame, on_robots), whatever the referee says: the closest two robots (centres, any teams) and
//    the contact frames, frames with two centres closer than kContactDistance. Counted per frame as
//    delivered: vision sends one frame per camera, so an instant seen by two cameras counts twice, and two
//    robots in contact on the seam between two cameras count once per camera that sees both. Each pair's
//    contacts are also told as episodes: one lasts while frames with the pair in contact come at most
//    kContactEpisodeGap apart; it keeps the closest distance, the referee command at its start and the ball's
//    distance from the nearer robot at the closest frame (nullopt without a ball observation).
//  * per team: placements (BALL_PLACEMENT_<team> commands issued) and balls out (BALL_LEFT_FIELD_TOUCH_LINE
//    and _GOAL_LINE events by the team, which kicked it out).
//  * each avoidable foul (referee::is_avoidable_foul) once, with the time of the sample that first carried
//    it, its team, robot and place as the referee gave them and the command of that sample.
//
//   MatchReportBuilder builder;
//   builder.on_referee(state, t);    // every referee sample, in time order
//   builder.on_ball(position, t);    // every ball observation (m, vision frame), in time order
//   builder.on_frame(ball, robots, t);  // or the ball with every robot seen: also passes, shots, possession
//   builder.on_robots(robots, t);       // a frame with robots and no ball: the robots' figures only
//   std::cout << to_text(builder.report());
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "libs/common/team.h"
#include "libs/domain/field.h"
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
    std::uint32_t placements = 0;  // BALL_PLACEMENT_<team> commands: this team placed the ball
    std::uint32_t balls_out = 0;   // BALL_LEFT_FIELD_* events by this team: it kicked the ball out
    TeamPlay play;  // passes, shots, possession (PlayAccount), from frames with robots
  };
  struct Goal {
    double at = 0;  // s since the first referee sample
    referee::Stage stage = referee::Stage::kNormalFirstHalf;
    std::optional<double> stage_time_left;  // s, as the referee said at the time
    referee::Team team = referee::Team::kUnknown;  // the scoring team
    std::optional<std::uint32_t> by_bot;
  };
  /// A foul the team could have avoided (referee::is_avoidable_foul): when, by whom, where, under which
  /// command; which match and moment to look at.
  struct AvoidableFoul {
    double at = 0;  // s since the first referee sample
    referee::GameEventType type = referee::GameEventType::kUnknown;
    referee::Team team = referee::Team::kUnknown;  // the team that committed it
    std::optional<std::uint32_t> by_bot;
    std::optional<geom::Vec2> location;  // m, the referee's frame
    referee::Command command = referee::Command::kHalt;  // the referee's command at the sample
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
  struct RobotId {
    TeamColor team = TeamColor::kBlue;
    std::uint32_t id = 0;
  };
  struct ClosestRobots {
    double distance = 0;  // m, centre to centre
    double at = 0;        // s since the first referee sample (0 before it)
    RobotId first;
    RobotId second;
  };
  struct ContactEpisode {
    RobotId first;
    RobotId second;
    double from = 0;     // s since the first referee sample (0 before it)
    double seconds = 0;  // from the first to the last frame in contact
    std::uint64_t frames = 0;
    double closest = 0;  // m, centre to centre
    std::optional<referee::Command> command;  // the referee's command at the start; nullopt before one
    std::optional<double> ball_distance;      // m from the ball to the nearer robot at the closest frame
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
  std::uint64_t robot_frames = 0;  // frames with at least one robot (on_frame, on_robots)
  double duration = 0;  // s from the first to the last referee sample
  TeamLine yellow;
  TeamLine blue;
  std::vector<Goal> goals;
  double in_play = 0;  // s
  double stopped = 0;  // s
  double halted = 0;   // s
  std::optional<double> in_play_vision;         // s, the ball seen inside the field; nullopt: no field size
  std::optional<ClosestRobots> closest_robots;  // nullopt before a frame with two robots
  std::uint64_t contact_frames = 0;             // frames with two robot centres closer than kContactDistance
  std::vector<ContactEpisode> contacts;         // in the order they began
  std::map<referee::Command, std::uint32_t> commands;  // how often each command was issued
  std::vector<EventCount> events;                       // by type, then team
  std::vector<AvoidableFoul> avoidable_fouls;           // in the order the referee raised them
  std::optional<Stall> longest_stall;                   // nullopt without ball samples
  std::vector<StageChange> stages;
  std::vector<SideChange> sides;
  referee::Stage final_stage = referee::Stage::kNormalFirstHalfPre;
  bool final_whistle = false;  // POST_GAME was reached
  std::uint64_t malformed = 0;  // packets that did not decode (set by the reader, not the builder)
};

class MatchReportBuilder {
 public:
  static constexpr double kStallDistance = 0.05;   // m: the ball moved (rules: in play after 0.05 m)
  static constexpr double kBallUnseenAfter = 0.2;  // s between ball observations: longer, the ball was not seen
  /// m between two robot centres: closer is a contact (two robots of the rules' largest radius, plus 1 cm).
  static constexpr double kContactDistance = 2 * FieldGeometry{}.max_robot_radius + 0.01;
  /// s between two frames with a pair in contact: longer apart, the second begins a new episode.
  static constexpr double kContactEpisodeGap = 0.25;

  /// One referee sample at `t` (samples before the previous one are ignored).
  void on_referee(const referee::RefereeState& state, time::Timestamp t);
  /// One ball observation at `t`, metres in any fixed frame.
  void on_ball(const geom::Vec2& ball, time::Timestamp t);
  /// The ball and every robot seen at `t` (the same frame): on_ball, on_robots, and the play account's
  /// passes, shots and possession.
  void on_frame(const geom::Vec2& ball, std::span<const PlayAccount::Robot> robots, time::Timestamp t,
                std::optional<PlayAccount::Camera> camera = std::nullopt);
  /// Every robot of a frame at `t` without the ball: the closest robots and contact frames (frames before the
  /// previous one are ignored).
  void on_robots(std::span<const PlayAccount::Robot> robots, time::Timestamp t);
  /// The field's size (its length, width, goal width and ball radius are read): shots, in play from vision.
  void set_field(const FieldGeometry& field);
  bool final_whistle() const { return report_.final_whistle; }
  /// Counts a packet that did not decode.
  void on_malformed() { ++report_.malformed; }

  /// The report so far (the open interval and stall up to the last sample included).
  MatchReport report() const;

 private:
  enum class Activity { kInPlay, kStopped, kHalted };
  static Activity activity_of(referee::Command command);
  double since_start(time::Timestamp t) const;
  /// The ball not yet wholly over a field line; false without the field's size.
  bool inside_field(const geom::Vec2& ball) const;
  void close_stall(time::Timestamp t);
  /// Two robots `distance` apart (under kContactDistance) in the frame at `t`: extends or begins their episode.
  void on_contact(const PlayAccount::Robot& a, const PlayAccount::Robot& b, double distance, time::Timestamp t);

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
  bool ball_in_play_ = false;  // at the last ball observation: in play, and the ball inside the field
  double in_play_vision_ = 0;  // s
  std::optional<time::Timestamp> last_robots_time_;
  std::optional<geom::Vec2> last_ball_;
  // Per pair (the two robots ordered by team, then id): the index of its latest episode in report_.contacts
  // and the time of its latest frame in contact.
  std::map<std::pair<std::pair<int, std::uint32_t>, std::pair<int, std::uint32_t>>,
           std::pair<std::size_t, time::Timestamp>>
      open_contacts_;
  std::optional<FieldGeometry> field_;
  PlayAccount play_;
};

/// Human-readable, one fact per line.
std::string to_text(const MatchReport& report);
/// The same as one JSON object (names: the league's for commands, stages and event types).
std::string to_json(const MatchReport& report);

}  // namespace ssl::sslctl
