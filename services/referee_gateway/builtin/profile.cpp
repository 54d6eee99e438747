// The schema of a referee profile (one Fields list per section) and the name-or-path lookup. Every key is
// required: a profile file states all its rules, so nothing changes behind the reader's back.
#include "services/referee_gateway/builtin/profile.h"

#include <algorithm>
#include <string>

#include "libs/common/deploy_files.h"
#include "libs/config/config.h"

namespace ssl::referee {
namespace {

using config::field;
using config::Fields;
using config::nested;

constexpr std::string_view kBuiltinProfiles = "arcade, strict_ai, simulation";

/// A per-division time limit, keys a and b (seconds).
Fields<DivisionSeconds> division_seconds_fields(double min, double max) {
  return {
      field("a", &DivisionSeconds::a).unit("s").range(min, max).doc("division A"),
      field("b", &DivisionSeconds::b).unit("s").range(min, max).doc("division B"),
  };
}

Fields<GoalDetectionRule> goal_detection_fields() {
  return {
      field("enabled", &GoalDetectionRule::enabled),
      field("cooldown", &GoalDetectionRule::cooldown)
          .unit("s")
          .range(0, 60)
          .doc("after a counted goal, further goals are ignored this long"),
  };
}

Fields<OutOfBoundsRule> out_of_bounds_fields() {
  return {
      field("enabled", &OutOfBoundsRule::enabled),
      field("ball_placement", &OutOfBoundsRule::ball_placement)
          .doc("the free-kick team places the ball (false: STOP, the operator places it)"),
      field("line_distance", &OutOfBoundsRule::line_distance)
          .unit("m")
          .range(0, 1)
          .doc("placement point inside the touch line, and inside the goal line for a corner kick"),
      field("goal_kick_distance", &OutOfBoundsRule::goal_kick_distance)
          .unit("m")
          .range(0, 3)
          .doc("placement point inside the goal line for a goal kick"),
  };
}

Fields<DefenseAreaRule> defense_area_fields() {
  return {
      field("enabled", &DefenseAreaRule::enabled),
      field("max_defenders", &DefenseAreaRule::max_defenders)
          .range(0, 11)
          .doc("robots of a team, goalkeeper included, allowed entirely inside their own defense area"),
      field("attacker_infringement", &DefenseAreaRule::attacker_infringement)
          .doc("an attacker entirely inside, or touching the ball partly inside, the opponent's area: free "
               "kick for the defenders"),
  };
}

Fields<KeepOutRule> keep_out_fields() {
  return {
      field("enabled", &KeepOutRule::enabled),
      field("radius", &KeepOutRule::radius)
          .unit("m")
          .range(0, 3)
          .doc("distance from the ball to a robot's nearest side during STOP and opponent restarts"),
      field("violation_persistence", &KeepOutRule::violation_persistence)
          .unit("s")
          .range(0, 60)
          .doc("a robot must stay too close this long before it is a foul"),
  };
}

Fields<NoProgressRule> no_progress_fields() {
  return {
      field("enabled", &NoProgressRule::enabled),
      nested("timeout", &NoProgressRule::timeout, division_seconds_fields(1, 600))
          .doc("the ball not moved 0.05 m this long while running: STOP, then FORCE_START"),
  };
}

Fields<PlacementInterferenceRule> placement_interference_fields() {
  return {
      field("enabled", &PlacementInterferenceRule::enabled),
      field("radius", &PlacementInterferenceRule::radius).unit("m").range(0, 3)
          .doc("the other team's robots keep this from the stadium ball -> target"),
      field("violation_persistence", &PlacementInterferenceRule::violation_persistence).unit("s").range(0, 60),
      field("extra_time", &PlacementInterferenceRule::extra_time).unit("s").range(0, 60)
          .doc("added to the placing team's time per foul"),
  };
}

Fields<CrashRule> crash_fields() {
  return {
      field("enabled", &CrashRule::enabled),
      field("speed", &CrashRule::speed).unit("m/s").range(0.1, 10)
          .doc("relative speed along the line between the centres above which a contact is a crash"),
      field("drawn_speed_difference", &CrashRule::drawn_speed_difference).unit("m/s").range(0, 10)
          .doc("both robots foul when their speeds differ by less"),
  };
}

Fields<StopSpeedRule> stop_speed_fields() {
  return {
      field("enabled", &StopSpeedRule::enabled),
      field("max_speed", &StopSpeedRule::max_speed).unit("m/s").range(0.1, 10),
      field("grace", &StopSpeedRule::grace).unit("s").range(0, 60).doc("after the STOP command"),
  };
}

Fields<DoubleTouchRule> double_touch_fields() {
  return {
      field("enabled", &DoubleTouchRule::enabled),
      field("distance", &DoubleTouchRule::distance).unit("m").range(0.01, 1)
          .doc("the kicker may stay in contact while the ball travels this far"),
  };
}

Fields<BallSpeedRule> ball_speed_fields() {
  return {
      field("enabled", &BallSpeedRule::enabled),
      field("max_speed", &BallSpeedRule::max_speed).unit("m/s").range(1, 20),
  };
}

Fields<BoundaryCrossingRule> boundary_crossing_fields() {
  return {
      field("enabled", &BoundaryCrossingRule::enabled).doc("the walls: the field geometry's boundary widths"),
  };
}

Fields<DribblingRule> dribbling_fields() {
  return {
      field("enabled", &DribblingRule::enabled),
      field("max_distance", &DribblingRule::max_distance).unit("m").range(0.1, 20),
  };
}

Fields<AttackerDefenseAreaDistanceRule> attacker_defense_area_distance_fields() {
  return {
      field("enabled", &AttackerDefenseAreaDistanceRule::enabled),
      field("distance", &AttackerDefenseAreaDistanceRule::distance).unit("m").range(0, 2)
          .doc("from the opponent's defense area to a robot's nearest side"),
      field("violation_persistence", &AttackerDefenseAreaDistanceRule::violation_persistence).unit("s").range(0, 60),
  };
}

Fields<KeeperHeldBallRule> keeper_held_ball_fields() {
  return {
      field("enabled", &KeeperHeldBallRule::enabled),
      nested("time", &KeeperHeldBallRule::time, division_seconds_fields(1, 600))
          .doc("the ball may lie in a team's own defense area this long while running"),
  };
}

Fields<RobotCountRule> robot_count_fields() {
  return {
      field("enabled", &RobotCountRule::enabled),
      field("grace", &RobotCountRule::grace).unit("s").range(0, 600).doc("to take a robot off"),
  };
}

Fields<CardRule> card_fields() {
  return {
      field("enabled", &CardRule::enabled),
      field("fouls_per_card", &CardRule::fouls_per_card).range(1, 100),
      field("yellow_card_duration", &CardRule::yellow_card_duration).unit("s").range(1, 3600)
          .doc("of playing time"),
  };
}

Fields<RefereeRules> rules_fields() {
  return {
      nested("goal_detection", &RefereeRules::goal_detection, goal_detection_fields()),
      nested("out_of_bounds", &RefereeRules::out_of_bounds, out_of_bounds_fields()),
      nested("defense_area", &RefereeRules::defense_area, defense_area_fields()),
      nested("keep_out", &RefereeRules::keep_out, keep_out_fields()),
      nested("no_progress", &RefereeRules::no_progress, no_progress_fields()),
      nested("placement_interference", &RefereeRules::placement_interference, placement_interference_fields()),
      nested("crash", &RefereeRules::crash, crash_fields()),
      nested("stop_speed", &RefereeRules::stop_speed, stop_speed_fields()),
      nested("double_touch", &RefereeRules::double_touch, double_touch_fields()),
      nested("ball_speed", &RefereeRules::ball_speed, ball_speed_fields()),
      nested("boundary_crossing", &RefereeRules::boundary_crossing, boundary_crossing_fields()),
      nested("dribbling", &RefereeRules::dribbling, dribbling_fields()),
      nested("attacker_defense_area_distance", &RefereeRules::attacker_defense_area_distance,
             attacker_defense_area_distance_fields()),
      nested("keeper_held_ball", &RefereeRules::keeper_held_ball, keeper_held_ball_fields()),
      nested("robot_count", &RefereeRules::robot_count, robot_count_fields()),
      nested("cards", &RefereeRules::cards, card_fields()),
  };
}

Fields<ExtraTimeSettings> extra_time_fields() {
  return {
      field("enabled", &ExtraTimeSettings::enabled)
          .doc("a draw after the second half goes to extra time, then to a shoot-out (elimination matches)"),
      field("break", &ExtraTimeSettings::break_duration).unit("s").range(0, 3600),
      field("half_duration", &ExtraTimeSettings::half_duration).unit("s").range(1, 3600)
          .doc("playing time per extra half"),
      field("half_time", &ExtraTimeSettings::half_time).unit("s").range(0, 3600),
      field("shootout_break", &ExtraTimeSettings::shootout_break).unit("s").range(0, 3600),
      field("shootout_penalties", &ExtraTimeSettings::shootout_penalties).range(1, 20)
          .doc("penalties per team before sudden death"),
  };
}

Fields<GameSettings> game_fields() {
  return {
      field("half_duration", &GameSettings::half_duration)
          .unit("s")
          .range(1, 3600)
          .doc("playing time per half (the clock runs only while the game runs)"),
      field("half_time", &GameSettings::half_time).unit("s").range(0, 3600),
      field("kickoff_team", &GameSettings::kickoff_team)
          .values({{"yellow", TeamColor::kYellow}, {"blue", TeamColor::kBlue}})
          .doc("kicks off the first half; the other team kicks off the second"),
      field("force_start_after_goal", &GameSettings::force_start_after_goal)
          .doc("after a goal: STOP, then FORCE_START after stop_duration (false: wait for the kickoff)"),
      field("auto_continue", &GameSettings::auto_continue)
          .doc("pending kickoffs and penalties, and their NORMAL_START, follow after stop_duration"),
      field("stop_duration", &GameSettings::stop_duration)
          .unit("s")
          .range(0, 60)
          .doc("time in STOP or preparation before an automatic continuation"),
      field("prepare_timeout", &GameSettings::prepare_timeout)
          .unit("s")
          .range(0, 600)
          .doc("with auto_continue: NORMAL_START once the robots are in position, at the latest after this"),
      field("kickoff_timeout", &GameSettings::kickoff_timeout)
          .unit("s")
          .range(1, 600)
          .doc("after NORMAL_START a kickoff ball is in play this late even if nobody kicked it"),
      nested("free_kick_timeout", &GameSettings::free_kick_timeout, division_seconds_fields(1, 600))
          .doc("after a free kick its ball is in play this late even if nobody kicked it"),
      field("penalty_timeout", &GameSettings::penalty_timeout)
          .unit("s")
          .range(1, 600)
          .doc("a penalty not decided this long after NORMAL_START fails: goal kick for the defenders"),
      field("ball_placement", &GameSettings::ball_placement)
          .doc("a team places the ball for a kickoff, penalty or FORCE_START whose ball is not where the "
               "restart needs it (false: STOP until it is placed by hand)"),
      field("placement_timeout", &GameSettings::placement_timeout).unit("s").range(1, 300),
      field("placement_tolerance", &GameSettings::placement_tolerance)
          .unit("m")
          .range(0.01, 1)
          .doc("ball within this distance of the target, at rest, for a successful placement"),
      field("early_end_goals", &GameSettings::early_end_goals)
          .range(0, 1000)
          .doc("a team with this many goals and a lead of at least 2 ends the match (0: never)"),
      nested("extra_time", &GameSettings::extra_time, extra_time_fields()),
  };
}

Fields<RefereeProfile> profile_fields() {
  return Fields<RefereeProfile>{
      field("name", &RefereeProfile::name).doc("shown to the operator"),
      nested("rules", &RefereeProfile::rules, rules_fields()),
      nested("game", &RefereeProfile::game, game_fields()),
  }
      .check([](const RefereeProfile& profile) -> Status {
        if (profile.name.empty()) return Error{"key 'name' must not be empty"};
        return Status::success();
      });
}

bool looks_like_path(std::string_view text) {
  return text.find('/') != std::string_view::npos || text.ends_with(".yaml") || text.ends_with(".yml");
}

bool is_profile_name(std::string_view text) {
  return !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
}

}  // namespace

Result<RefereeProfile> load_referee_profile(std::string_view name_or_path) {
  if (looks_like_path(name_or_path)) return config::load_file(std::string(name_or_path), profile_fields());
  if (!is_profile_name(name_or_path)) {
    return Error{"referee profile '" + std::string(name_or_path) +
                 "' is neither a profile name (letters, digits, _ and -) nor a .yaml path"};
  }
  Result<std::string> file =
      find_deploy_file("config/referee_profiles/" + std::string(name_or_path) + ".yaml");
  if (!file) {
    return Error{"unknown referee profile '" + std::string(name_or_path) +
                 "' (built-in: " + std::string(kBuiltinProfiles) +
                 "; or give the path of a .yaml file): " + file.error().message};
  }
  return config::load_file(*file, profile_fields());
}

Result<RefereeProfile> load_referee_profile_from_string(std::string_view yaml, std::string_view source) {
  return config::load_string(yaml, profile_fields(), source);
}

std::string referee_profile_yaml(const RefereeProfile& profile) {
  return config::to_yaml(profile, profile_fields());
}

}  // namespace ssl::referee
