#include "services/planner/core/plays.h"

#include "services/planner/core/skills.h"

#include <algorithm>
#include <cmath>

#include "libs/geometry/angle.h"
#include "libs/geometry/project.h"
#include "libs/geometry/segment.h"
#include "libs/geometry/vec2.h"

namespace ssl::planner {
namespace {

using wm::RefereeCommand;

// Formation keys for the stable assigner (one per formation shape).
enum FormationKey : std::uint32_t {
  kDefensiveKey = 1,
  kAttackKey,
  kOurKickoffKey,
  kTheirKickoffKey,
  kOurPenaltyKey,
  kTheirPenaltyKey,
  kParkKey,
};

struct Slot {
  Vec2 position = Vec2::Zero();
  std::string_view role;
};

struct Formation {
  std::array<Slot, kMaxSlots> slots{};
  std::size_t count = 0;
  void add(const Vec2& position, std::string_view role) {
    if (count < slots.size()) slots[count++] = {position, role};
  }
};

struct Ids {
  std::array<std::uint32_t, kMaxSlots> ids{};
  std::size_t count = 0;
  void add(std::uint32_t id) {
    if (count < ids.size()) ids[count++] = id;
  }
  bool contains(std::uint32_t id) const {
    return std::find(ids.begin(), ids.begin() + count, id) != ids.begin() + count;
  }
  std::span<const std::uint32_t> view() const { return {ids.data(), count}; }
};

double radius(const Situation& s) { return s.config->robot_radius; }
/// Robot-centre distance to the ball that keeps the rule's 0.5 m plus our margin.
double ball_clearance(const Situation& s) {
  return s.config->ball_keep_away + s.config->robot_radius + s.config->keep_away_margin;
}
double stop_speed(const Situation& s) { return s.config->stop_speed - s.config->stop_speed_margin; }
double sign_or_one(double v) { return v < 0 ? -1.0 : 1.0; }

}  // namespace

MotionIntent base_intent(const Situation& s, std::string_view tactic) {
  MotionIntent intent;
  intent.active = true;
  intent.max_speed = s.config->limits.max_speed;
  intent.tactic = tactic;
  return intent;
}

MotionIntent stop_intent(const Situation& s, std::string_view tactic) {
  MotionIntent intent = base_intent(s, tactic);
  intent.max_speed = stop_speed(s);
  intent.avoid_ball_radius = ball_clearance(s);
  return intent;
}

namespace {

void begin(const Situation& s, TeamIntents& out, std::string_view play) {
  out.play = play;
  for (MotionIntent& intent : out.robots) intent = MotionIntent{};
  (void)s;
}

void write(const Situation& s, TeamIntents& out, std::uint32_t id, MotionIntent intent) {
  if (id >= out.robots.size()) return;
  intent.target = project_out(intent.target, intent, s.zones);
  out.robots[id] = intent;
}

Ids field_players(const Situation& s) {
  Ids ids;
  for (const wm::RobotState& robot : s.robots) {
    if (!s.keeper || robot.id != *s.keeper) ids.add(robot.id);
  }
  return ids;
}

/// The field player closest to `point` (stable), or the keeper when it is our only robot.
std::optional<std::uint32_t> choose_closest(const Situation& s, StableChoice& choice, const Vec2& point) {
  const Ids ids = field_players(s);
  std::array<double, kMaxSlots> scores{};
  for (std::size_t i = 0; i < ids.count; ++i)
    scores[i] = (find_robot(s, ids.ids[i])->position - point).norm();
  if (ids.count == 0) return s.keeper;
  return choice.choose(ids.view(), {scores.data(), ids.count});
}

// ---- formations ---------------------------------------------------------------------------------------

double defender_x(const Situation& s) {
  return -s.field.half_length() + s.field.size().penalty_area_depth + radius(s) + 0.3;
}

void add_defenders(const Situation& s, Formation& f, int which) {
  const double y = std::clamp(s.ball.y() * 0.3, -0.8, 0.8);
  if (which & 1) f.add({defender_x(s), y + 0.35}, "defender");
  if (which & 2) f.add({defender_x(s), y - 0.35}, "defender");
}

void add_generic(const Situation& s, Formation& f) {
  const double L = s.field.length();
  const double W = s.field.width();
  const Vec2 spots[] = {
      {-0.25 * L, 0.25 * W}, {-0.25 * L, -0.25 * W}, {-0.05 * L, 0.35 * W},  {-0.05 * L, -0.35 * W},
      {-0.15 * L, 0.0},      {-0.38 * L, 0.38 * W},  {-0.38 * L, -0.38 * W}, {0.12 * L, 0.3 * W},
      {0.12 * L, -0.3 * W},  {0.12 * L, 0.0},        {-0.3 * L, 0.45 * W},   {-0.3 * L, -0.45 * W},
      {0.0, 0.45 * W},       {0.0, -0.45 * W},       {-0.1 * L, 0.15 * W},   {-0.1 * L, -0.15 * W}};
  for (const Vec2& p : spots) f.add(p, "support");
}

/// Between the ball and our goal: a two-robot wall, two defenders, then supporters.
Formation defensive_set(const Situation& s) {
  Formation f;
  const Vec2 u = geom::normalized_or(s.field.our_goal_center() - s.ball, Vec2(-1, 0));
  const Vec2 wall = s.ball + u * (ball_clearance(s) + 0.1);
  const Vec2 side = geom::perpendicular(u) * (radius(s) + 0.03);
  f.add(wall + side, "wall");
  add_defenders(s, f, 1);
  f.add(wall - side, "wall");
  add_defenders(s, f, 2);
  add_generic(s, f);
  return f;
}

/// Ahead of the ball for passes, and two defenders.
Formation attack_set(const Situation& s) {
  Formation f;
  const double limit_x = s.field.half_length() - s.field.size().penalty_area_depth - 0.6;
  const double min_x = -s.field.half_length() + s.field.size().penalty_area_depth + 0.5;
  const auto x_at = [&](double dx) { return std::clamp(s.ball.x() + dx, min_x, limit_x); };
  const double side = sign_or_one(s.ball.y());
  const double W = s.field.width();
  add_defenders(s, f, 1);
  f.add({x_at(1.8), -side * 0.25 * W}, "support");
  f.add({x_at(0.8), side * 0.35 * W}, "support");
  add_defenders(s, f, 2);
  f.add({x_at(-1.2), -side * 0.1 * W}, "support");
  f.add({x_at(2.5), side * 0.1 * W}, "support");
  add_generic(s, f);
  return f;
}

Formation our_kickoff_set(const Situation& s) {
  Formation f;
  const double W = s.field.width();
  const double L = s.field.length();
  f.add({-0.35, 1.2}, "wing");
  f.add({-0.35, -1.2}, "wing");
  add_defenders(s, f, 3);
  f.add({-1.5, 0.0}, "midfield");
  f.add({-0.35, 0.36 * W}, "wing");
  f.add({-0.35, -0.36 * W}, "wing");
  f.add({-0.25 * L, 0.25 * W}, "support");
  f.add({-0.25 * L, -0.25 * W}, "support");
  f.add({-0.38 * L, 0.38 * W}, "support");
  f.add({-0.38 * L, -0.38 * W}, "support");
  add_generic(s, f);
  return f;
}

Formation their_kickoff_set(const Situation& s) {
  Formation f;
  const double W = s.field.width();
  const double L = s.field.length();
  const double r = s.field.size().center_circle_radius + radius(s) + s.config->keep_away_margin + 0.1;
  f.add({-r, 0.0}, "blocker");
  f.add({-r * 0.75, r * 0.75 + 0.2}, "blocker");
  f.add({-r * 0.75, -r * 0.75 - 0.2}, "blocker");
  add_defenders(s, f, 3);
  f.add({-0.35, 0.3 * W}, "wing");
  f.add({-0.35, -0.3 * W}, "wing");
  f.add({-0.25 * L, 0.25 * W}, "support");
  f.add({-0.25 * L, -0.25 * W}, "support");
  f.add({-0.38 * L, 0.38 * W}, "support");
  add_generic(s, f);
  return f;
}

/// A line across the field at `x`, spreading from y = 0 outwards, or (`staggered`) from half a spacing
/// either side of it. Robots stand far enough apart that another can pass between two of them.
Formation line_set(const Situation& s, double x, std::string_view role, bool staggered) {
  Formation f;
  const double spacing = 2 * radius(s) + 0.8;
  const double max_y = s.field.half_width() - radius(s) - 0.1;
  for (std::size_t k = 0; k < kMaxSlots; ++k) {
    const double rank = staggered ? static_cast<double>(k / 2) + 0.5 : static_cast<double>((k + 1) / 2);
    const double y = (k % 2 == 0) ? rank * spacing : -rank * spacing;
    if (std::abs(y) > max_y) {
      f.add({x + (x < 0 ? -1.0 : 1.0) * 0.4, std::clamp(y * 0.5, -max_y, max_y)}, role);
    } else {
      f.add({x, y}, role);
    }
  }
  return f;
}

/// m from the ball to the line of the robots waiting behind a penalty kick. Both teams wait on the same
/// side of the ball, so the defending team stands one row further back and staggered: the two lines never
/// claim the same spots, and a robot of either can walk between two of the other's (an opponent's robot on
/// one of our spots still pushes that slot aside, see fill()).
constexpr double kDefendingPenaltyRow = 0.4;
double penalty_line_offset(const Situation& s, bool attacking) {
  return s.config->penalty_line_behind + radius(s) + s.config->keep_away_margin + 0.05 +
         (attacking ? 0.0 : kDefendingPenaltyRow);
}

Formation park_set(const Situation& s) {
  Formation f;
  const double y = -s.field.half_width() + radius(s) + 0.2;
  for (std::size_t k = 0; k < kMaxSlots; ++k) f.add({-0.4 - 0.35 * static_cast<double>(k), y}, "parked");
  return f;
}

/// Assigns the robots not in `reserved` to `f` (stably) and writes their intents from `tmpl`.
void fill(const Situation& s, PlayMemory& memory, std::uint32_t key, Formation f, const MotionIntent& tmpl,
          const Ids& reserved, TeamIntents& out) {
  Ids ids;
  std::array<Vec2, kMaxSlots> positions{};
  for (const wm::RobotState& robot : s.robots) {
    if (reserved.contains(robot.id) || ids.count >= kMaxSlots) continue;
    positions[ids.count] = robot.position;
    ids.add(robot.id);
  }
  if (ids.count == 0) return;
  const std::size_t n = std::min(f.count, ids.count);
  // The slots that will be used, legal first, then kept apart so that two robots do not share a spot, and
  // off the spots opponents stand on (their formation may want the same places: a penalty's lines).
  std::array<Vec2, kMaxSlots> targets{};
  for (std::size_t i = 0; i < n; ++i) targets[i] = project_out(f.slots[i].position, tmpl, s.zones);
  const double min_gap = 2 * radius(s) + 0.08;
  for (int pass = 0; pass < 3; ++pass) {
    for (std::size_t i = 0; i < n; ++i) {
      for (const wm::RobotState& enemy : s.enemies) {
        const Vec2 d = targets[i] - enemy.position;
        const double dist = d.norm();
        if (dist >= min_gap) continue;
        targets[i] = enemy.position + (dist > 1e-9 ? Vec2(d / dist) : Vec2(0, 1)) * (min_gap + 0.005);
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i + 1; j < n; ++j) {
        const Vec2 d = targets[j] - targets[i];
        const double dist = d.norm();
        if (dist >= min_gap) continue;
        const Vec2 u = dist > 1e-9 ? Vec2(d / dist) : Vec2(0, 1);
        const double push = (min_gap - dist) / 2 + 0.005;
        targets[i] -= u * push;
        targets[j] += u * push;
      }
    }
    for (std::size_t i = 0; i < n; ++i) targets[i] = project_out(targets[i], tmpl, s.zones);
  }
  const std::span<const int> slot_of =
      memory.assigner.assign(key, ids.view(), {positions.data(), ids.count}, {targets.data(), n});
  for (std::size_t r = 0; r < ids.count; ++r) {
    MotionIntent intent = tmpl;
    const int slot = slot_of[r];
    if (slot >= 0) {
      intent.target = targets[static_cast<std::size_t>(slot)];
      intent.role = f.slots[static_cast<std::size_t>(slot)].role;
    } else {
      intent.target = positions[r];
      intent.role = "spare";
    }
    intent.orientation = heading_to(intent.target, s.ball);
    write(s, out, ids.ids[r], intent);
  }
}

// ---- single roles -------------------------------------------------------------------------------------

/// The goalkeeper: the defend_goal skill under the play's limits (`tmpl`: speed, tactic).
/// `touch_line`: centre so close to the line that the robot touches it (their penalty).
MotionIntent keeper_intent(const Situation& s, const MotionIntent& tmpl, bool touch_line) {
  const wm::RobotState* keeper = s.keeper ? find_robot(s, *s.keeper) : nullptr;
  MotionIntent intent = tmpl;
  if (!keeper) return intent;
  const MotionIntent skill = defend_goal(s, *keeper, {.touch_line = touch_line});
  intent.avoid_our_defense_area = skill.avoid_our_defense_area;
  intent.contests_ball = skill.contests_ball;
  intent.target = skill.target;
  intent.orientation = skill.orientation;
  intent.skill = skill.skill;
  intent.role = "goalkeeper";
  return intent;
}

void write_keeper(const Situation& s, const MotionIntent& tmpl, bool touch_line, Ids& reserved,
                  TeamIntents& out) {
  if (!s.keeper) return;
  reserved.add(*s.keeper);
  write(s, out, *s.keeper, keeper_intent(s, tmpl, touch_line));
}

/// The kicker of a restart before it may touch the ball: behind the ball towards `aim`, `distance` from it.
MotionIntent staging_intent(const Situation& s, const MotionIntent& tmpl, const Vec2& aim, double distance) {
  MotionIntent intent = tmpl;
  const Vec2 u = geom::normalized_or(aim - s.ball, Vec2(1, 0));
  intent.target = s.ball - u * distance;
  intent.orientation = geom::angle_of(u).radians();
  intent.avoid_ball_radius =
      std::min(tmpl.avoid_ball_radius > 0 ? tmpl.avoid_ball_radius : distance, distance - 0.02);
  intent.role = "kicker";
  intent.skill = "approach_ball";
  return intent;
}

/// Pre-positions for the announced next command under the STOP limits (or the default stop formation).
void stop_with_next(const Situation& s, PlayMemory& memory, TeamIntents& out, const MotionIntent& tmpl) {
  Ids reserved;
  const auto next = s.next_command;
  const bool blue = s.we_are_blue;
  const auto is = [&](RefereeCommand ours_blue, RefereeCommand ours_yellow) {
    return next && *next == (blue ? ours_blue : ours_yellow);
  };
  using C = RefereeCommand;
  const bool our_kickoff = is(C::kPrepareKickoffBlue, C::kPrepareKickoffYellow);
  const bool their_kickoff = is(C::kPrepareKickoffYellow, C::kPrepareKickoffBlue);
  const bool our_penalty = is(C::kPreparePenaltyBlue, C::kPreparePenaltyYellow);
  const bool their_penalty = is(C::kPreparePenaltyYellow, C::kPreparePenaltyBlue);
  const bool our_free =
      is(C::kDirectFreeBlue, C::kDirectFreeYellow) || is(C::kIndirectFreeBlue, C::kIndirectFreeYellow);
  write_keeper(s, tmpl, false, reserved, out);
  const double staging = ball_clearance(s) + 0.05;
  if (our_kickoff || our_penalty || our_free) {
    const Vec2 aim = our_free ? shot_target(s) : s.field.their_goal_center();
    if (auto kicker = choose_closest(s, memory.kicker, s.ball)) {
      if (!reserved.contains(*kicker)) {
        reserved.add(*kicker);
        write(s, out, *kicker, staging_intent(s, tmpl, aim, staging));
      }
    }
  }
  if (our_kickoff) {
    fill(s, memory, kOurKickoffKey, our_kickoff_set(s), tmpl, reserved, out);
  } else if (their_kickoff) {
    fill(s, memory, kTheirKickoffKey, their_kickoff_set(s), tmpl, reserved, out);
  } else if (our_penalty) {
    fill(s, memory, kOurPenaltyKey, line_set(s, s.ball.x() - penalty_line_offset(s, true), "penalty_line", false), tmpl,
         reserved, out);
  } else if (their_penalty) {
    fill(s, memory, kTheirPenaltyKey, line_set(s, s.ball.x() + penalty_line_offset(s, false), "penalty_line", true), tmpl,
         reserved, out);
  } else if (our_free) {
    fill(s, memory, kAttackKey, attack_set(s), tmpl, reserved, out);
  } else {
    fill(s, memory, kDefensiveKey, defensive_set(s), tmpl, reserved, out);
  }
}

/// m beyond our half and the centre circle a robot's centre keeps before a kickoff is in play.
double kickoff_margin(const Situation& s) { return radius(s) + s.config->keep_away_margin; }

/// Kickoff: every robot but the kicker in our half and outside the centre circle (targets).
void keep_kickoff_legal(const Situation& s, TeamIntents& out, std::optional<std::uint32_t> kicker) {
  const double margin = kickoff_margin(s);
  const double circle = s.field.size().center_circle_radius + margin;
  for (const wm::RobotState& robot : s.robots) {
    if (kicker && robot.id == *kicker) continue;
    MotionIntent& intent = out.robots[robot.id];
    if (!intent.active) continue;
    Vec2& p = intent.target;
    p.x() = std::min(p.x(), -margin);
    if (p.norm() < circle) p = geom::normalized_or(p, Vec2(-1, 0)) * circle;
  }
}

/// m/s of a penalty shot: as hard as the rules allow (less a margin for the kicker's spread), so that the
/// keeper has the least time.
constexpr double kPenaltyKickSpeed = rules::kMaxBallSpeed - 0.5;
/// The base strategy's penalty (penalty_attack).
constexpr double kPenaltyShotBeyondArea = 0.8;     // m, ball to their goal centre less the area's depth
constexpr double kPenaltyAdvanceBeyondArea = 0.4;  // m in front of their defense area, on the goal's axis
// m/s the ball still rolls at there, as planned: the kicker's own run adds 0.3-0.5 m/s to the pass. Planned at
// 0.8 the ball still rolled at 1 m/s into their area, the kicker trailing it 0.15 m, and it lay there until
// the penalty's time ran out: 38 of 48 scored (division A, realistic, seeds 1-12 each side and colour),
// 47 of 48 at 0.4 (and 48 of 48 in division B).
constexpr double kPenaltyAdvanceArrival = 0.4;
constexpr double kPenaltyRollingOn = 0.4;          // m/s towards that spot: the kicker runs with it

/// Our restart's kick once it may be taken: a shot, a penalty as hard as the rules allow; the base strategy's
/// penalty (PenaltyPlay::kAdvance) is penalty_attack. (A pass instead of a poor shot lost more balls than it
/// kept: bench/match_series measured base 1.9 : 6.1 ball_chaser with it.)
void set_piece_kick(const Situation& s, std::uint32_t kicker, std::string_view tactic, TeamIntents& out) {
  const wm::RobotState* robot = find_robot(s, kicker);
  if (!robot) return;
  MotionIntent intent = shoot(s, *robot, {});
  if (tactic == "penalty") {
    const bool advance = s.config->strategy == Strategy::kBase && s.config->penalty == PenaltyPlay::kAdvance;
    intent = advance ? penalty_attack(s, *robot) : shoot(s, *robot, {.speed = kPenaltyKickSpeed});
  }
  intent.role = "kicker";
  intent.tactic = tactic;
  write(s, out, kicker, intent);
}

/// Our kicker of a prepared restart (kickoff, penalty): the robot closest to the ball (stable). Before
/// NORMAL_START it waits behind the ball facing their goal, `staging_gap` m beyond dribbling distance, never
/// touching it; once the restart is ready it approaches and kicks. `one_touch`: it may not touch the ball
/// again before another robot did (kickoffs; a penalty's attacker may). Returns the kicker (reserved).
std::optional<std::uint32_t> take_prepared_kick(const Situation& s, PlayMemory& memory, std::string_view tactic,
                                                double staging_gap, bool one_touch, Ids& reserved, TeamIntents& out) {
  const std::optional<std::uint32_t> kicker = choose_closest(s, memory.kicker, s.ball);
  if (!kicker || reserved.contains(*kicker)) return kicker;
  reserved.add(*kicker);
  if (s.game->is_ready()) {
    if (one_touch) memory.restart_kicker = *kicker;
    set_piece_kick(s, *kicker, tactic, out);
    return kicker;
  }
  MotionIntent kick_tmpl = base_intent(s, tactic);
  kick_tmpl.avoid_ball_radius = dribbler_distance(s) + 0.08;
  write(s, out, *kicker,
        staging_intent(s, kick_tmpl, s.field.their_goal_center(), dribbler_distance(s) + staging_gap));
  return kicker;
}

}  // namespace

bool legal_before_our_kickoff(const Situation& s, const Vec2& p) {
  const double margin = kickoff_margin(s);
  return p.x() <= -margin && p.norm() >= s.field.size().center_circle_radius + margin;
}

MotionIntent penalty_attack(const Situation& s, const wm::RobotState& kicker) {
  const Vec2 goal = s.field.their_goal_center();
  const double depth = s.field.size().penalty_area_depth;
  const double range = depth + kPenaltyShotBeyondArea;
  const Vec2 spot = goal - Vec2(depth + kPenaltyAdvanceBeyondArea, 0);
  const Vec2 on = geom::normalized_or(spot - s.ball, Vec2(1, 0));
  const bool rolling_on = s.ball_known && s.ball_velocity.dot(on) > kPenaltyRollingOn;
  if ((goal - s.ball).norm() > range && !rolling_on) {
    return pass(s, kicker, {.receiver = spot, .arrival_speed = kPenaltyAdvanceArrival});
  }
  return shoot(s, kicker, {.speed = kPenaltyKickSpeed, .max_distance = range});
}

const wm::RobotState* find_robot(const Situation& s, std::uint32_t id) {
  for (const wm::RobotState& robot : s.robots) {
    if (robot.id == id) return &robot;
  }
  return nullptr;
}

void play_wander(const Situation& s, PlayMemory& memory, TeamIntents& out) {
  begin(s, out, "wander");
  constexpr double kArrived = 0.15;  // m: the waypoint is reached, take the next
  const double half_length = s.field.size().field_length / 2 - s.field.size().penalty_area_depth - 0.4;
  const double half_width = s.field.size().field_width / 2 - 0.3;
  // Waypoint `leg` of robot `id`: a fixed sequence (a multiplicative hash), the same in every run.
  const auto waypoint = [&](std::uint32_t id, std::uint32_t leg) {
    const std::uint32_t h = (id * 2654435761U) ^ (leg * 2246822519U);
    const double u = static_cast<double>(h & 0xFFFF) / 0xFFFF;
    const double v = static_cast<double>((h >> 16) & 0xFFFF) / 0xFFFF;
    return Vec2((2 * u - 1) * half_length, (2 * v - 1) * half_width);
  };
  for (const wm::RobotState& robot : s.robots) {
    if (robot.id >= memory.wander_leg.size()) continue;
    std::uint32_t& leg = memory.wander_leg[robot.id];
    if ((waypoint(robot.id, leg) - robot.position).norm() < kArrived) ++leg;
    MotionIntent intent;
    intent.active = true;
    intent.target = waypoint(robot.id, leg);
    intent.orientation = std::atan2(intent.target.y() - robot.position.y(), intent.target.x() - robot.position.x());
    intent.max_speed = s.config->limits.max_speed;
    intent.role = "wanderer";
    intent.tactic = "wander";
    intent.skill = "move_to";
    write(s, out, robot.id, intent);
  }
}

void play_halt(const Situation& s, TeamIntents& out) {
  begin(s, out, "halt");
  for (const wm::RobotState& robot : s.robots) {
    MotionIntent intent;
    intent.active = true;
    intent.halt = true;
    intent.target = robot.position;
    intent.orientation = robot.orientation;
    intent.max_speed = 0;
    intent.role = s.keeper && robot.id == *s.keeper ? "goalkeeper" : "halted";
    intent.tactic = "halt";
    intent.skill = "halt";
    if (robot.id < out.robots.size()) out.robots[robot.id] = intent;
  }
}

void play_stop(const Situation& s, PlayMemory& memory, TeamIntents& out, std::string_view play) {
  begin(s, out, play);
  stop_with_next(s, memory, out, stop_intent(s, "stop_formation"));
}

void play_timeout(const Situation& s, PlayMemory& memory, TeamIntents& out) {
  begin(s, out, "timeout");
  const MotionIntent tmpl = stop_intent(s, "park");
  Ids reserved;
  write_keeper(s, tmpl, false, reserved, out);
  fill(s, memory, kParkKey, park_set(s), tmpl, reserved, out);
}

/// The pull-back of a ball lying too near a wall to be approached from behind (placement).
struct PullBackParams {
  double speed = 0.3;            // m/s backwards with the ball on the dribbler
  double approach_margin = 0.12;  // m beyond the dribbler the placer waits behind a ball before taking it
  double clear_of_wall = 0.05;   // m more than that approach point needs before the ball is released
};

/// Whether the placer can stand behind `ball` (seen from the target along `u`) at the approach distance,
/// inside the walls (the placer may enter the boundary).
bool approachable_from_behind(const Situation& s, const Vec2& ball, const Vec2& u, double extra) {
  const PullBackParams params;
  const Vec2 behind = ball - u * (dribbler_distance(s) + params.approach_margin + extra);
  const double reach_x = s.field.size().wall_half_length() - s.zones.wall_margin;
  const double reach_y = s.field.size().wall_half_width() - s.zones.wall_margin;
  return std::abs(behind.x()) <= reach_x && std::abs(behind.y()) <= reach_y;
}

/// m/s under which the placer (and the ball it carries) counts as at rest: it lets the ball go only then.
constexpr double kReleaseSpeed = 0.1;

void play_our_ball_placement(const Situation& s, PlayMemory& memory, TeamIntents& out) {
  if (!s.placement_target) {
    play_stop(s, memory, out, "our_ball_placement_no_target");
    return;
  }
  begin(s, out, "our_ball_placement");
  MotionIntent tmpl = stop_intent(s, "clear_placement");
  tmpl.avoid_placement_corridor = true;
  Ids reserved;
  write_keeper(s, tmpl, false, reserved, out);
  const std::optional<std::uint32_t> placer_id = choose_closest(s, memory.placer, s.ball);
  const wm::RobotState* placer = placer_id ? find_robot(s, *placer_id) : nullptr;
  if (placer) {
    if (memory.current_placer != placer->id) memory.place_phase = PlayMemory::PlacePhase::kApproach;
    memory.current_placer = placer->id;
    reserved.add(placer->id);
    const Vec2 target = *s.placement_target;
    const double dd = dribbler_distance(s);
    const Vec2 heading = geom::Angle::from_radians(placer->orientation).to_unit_vector();
    const Vec2 rel = placer->position - s.ball;
    const bool held = holds_ball(s, *placer);
    const double ball_error = (s.ball - target).norm();
    const PullBackParams pull;
    const Vec2 u = geom::normalized_or(target - s.ball, heading);
    const bool from_behind = approachable_from_behind(s, s.ball, u, 0);
    using P = PlayMemory::PlacePhase;
    switch (memory.place_phase) {
      case P::kApproach:
        // A ball already on the target (placed by the simulator, or left there) is not touched again.
        if (ball_error < s.config->placement_tolerance * 0.5) {
          memory.place_phase = P::kRelease;
        } else if (held && from_behind) {
          memory.place_phase = P::kCarry;
        } else if (!from_behind && rel.norm() < dd - 0.005 && (-rel).normalized().dot(heading) > std::cos(0.35)) {
          memory.place_phase = P::kPullBack;  // pressed against the ball: the dribbler holds it
        }
        break;
      case P::kPullBack:
        if (approachable_from_behind(s, s.ball, u, pull.clear_of_wall)) {
          memory.place_phase = P::kRelease;
        } else if (rel.norm() > dd + 0.1) {
          memory.place_phase = P::kApproach;  // lost the ball: take it again
        }
        break;
      case P::kCarry:
        // Released at rest only: a placer still rolling pushes the ball on as the dribbler lets go.
        if (ball_error < 0.04 && placer->velocity.norm() < kReleaseSpeed && s.ball_velocity.norm() < kReleaseSpeed) {
          memory.place_phase = P::kRelease;
        } else if (!held && rel.norm() > dd + 0.1) {
          memory.place_phase = P::kApproach;
        }
        break;
      case P::kRelease:
        if (ball_error > s.config->placement_tolerance * 0.8) memory.place_phase = P::kApproach;
        break;
    }
    MotionIntent intent = base_intent(s, "place_ball");
    intent.max_speed = std::min(stop_speed(s), s.config->ball_placement_speed);
    intent.role = "placer";
    intent.may_enter_boundary = true;  // the ball may lie between the lines and the walls
    switch (memory.place_phase) {
      case P::kApproach: {
        if (!from_behind) {
          // Too near a wall to get behind it: take it from the field side, facing the wall.
          const double along = rel.dot(u);  // > 0: the placer is on the target side of the ball
          const double lateral = std::abs(geom::cross(u, rel));
          intent.orientation = geom::angle_of(Vec2(-u)).radians();
          if (along > 0.05 && lateral < 0.04) {
            intent.target = s.ball + u * (dd - 0.02);
            intent.dribble = true;
            intent.max_speed = 0.5;
            intent.skill = "get_ball_from_the_field_side";
          } else {
            intent.target = s.ball + u * (dd + pull.approach_margin);
            intent.avoid_ball_radius = dd + 0.06;
            intent.skill = "approach_ball";
          }
          break;
        }
        const double along = rel.dot(u);
        const double lateral = std::abs(geom::cross(u, rel));
        const double heading_error = std::acos(std::clamp(heading.dot(u), -1.0, 1.0));
        intent.orientation = geom::angle_of(u).radians();
        if (along < -0.05 && lateral < 0.04 && heading_error < 0.2) {
          intent.target = s.ball - u * (dd - 0.02);
          intent.dribble = true;
          intent.max_speed = 0.5;
          intent.skill = "get_ball";
        } else {
          intent.target = s.ball - u * (dd + 0.12);
          intent.avoid_ball_radius = dd + 0.06;
          intent.skill = "approach_ball";
        }
        break;
      }
      case P::kCarry: {
        const Vec2 to_target = target - placer->position;
        const Vec2 dir = to_target.norm() > 0.25 ? geom::normalized_or(to_target, heading) : heading;
        intent.target = target - dir * dd;
        intent.orientation = geom::angle_of(dir).radians();
        intent.dribble = true;
        intent.max_speed = std::min(intent.max_speed, 0.3 + 1.5 * ball_error);
        intent.skill = "dribble_to";
        break;
      }
      case P::kPullBack:
        // Backwards towards the target, the ball held by the dribbler, until it can be taken from behind.
        intent.target = placer->position + u * 0.3;
        intent.orientation = geom::angle_of(Vec2(-u)).radians();
        intent.dribble = true;
        intent.max_speed = pull.speed;
        intent.skill = "pull_back";
        break;
      case P::kRelease:
        // Straight away from the ball (behind the dribbler after a carry).
        intent.target = s.ball + geom::normalized_or(rel, -heading) * (ball_clearance(s) + 0.05);
        intent.orientation = placer->orientation;
        intent.max_speed = 0.5;
        intent.skill = "release_ball";
        break;
    }
    intent.avoid_our_defense_area = false;  // rules 13.4: entering defense areas is allowed when placing
    intent.avoid_their_defense_area = false;
    write(s, out, placer->id, intent);
  }
  fill(s, memory, kDefensiveKey, defensive_set(s), tmpl, reserved, out);
}

void play_their_ball_placement(const Situation& s, PlayMemory& memory, TeamIntents& out) {
  begin(s, out, "their_ball_placement");
  MotionIntent tmpl = stop_intent(s, "clear_placement");
  tmpl.avoid_placement_corridor = true;
  Ids reserved;
  write_keeper(s, tmpl, false, reserved, out);
  fill(s, memory, kDefensiveKey, defensive_set(s), tmpl, reserved, out);
}

void play_our_kickoff(const Situation& s, PlayMemory& memory, TeamIntents& out) {
  begin(s, out, "our_kickoff");
  MotionIntent tmpl = base_intent(s, "kickoff_formation");
  tmpl.avoid_ball_radius = s.field.size().center_circle_radius + radius(s) + s.config->keep_away_margin;
  Ids reserved;
  write_keeper(s, tmpl, false, reserved, out);
  const std::optional<std::uint32_t> kicker = take_prepared_kick(s, memory, "kickoff", 0.1, /*one_touch=*/true, reserved, out);
  fill(s, memory, kOurKickoffKey, our_kickoff_set(s), tmpl, reserved, out);
  keep_kickoff_legal(s, out, kicker);
}

void play_their_kickoff(const Situation& s, PlayMemory& memory, TeamIntents& out) {
  begin(s, out, "their_kickoff");
  MotionIntent tmpl = base_intent(s, "kickoff_defense");
  tmpl.avoid_ball_radius = std::max(s.field.size().center_circle_radius, s.config->ball_keep_away) +
                           radius(s) + s.config->keep_away_margin;
  Ids reserved;
  write_keeper(s, tmpl, false, reserved, out);
  fill(s, memory, kTheirKickoffKey, their_kickoff_set(s), tmpl, reserved, out);
  keep_kickoff_legal(s, out, std::nullopt);
}

void play_our_penalty(const Situation& s, PlayMemory& memory, TeamIntents& out) {
  begin(s, out, "our_penalty");
  MotionIntent tmpl = base_intent(s, "penalty_line");
  Ids reserved;
  write_keeper(s, tmpl, false, reserved, out);
  take_prepared_kick(s, memory, "penalty", 0.12, /*one_touch=*/false, reserved, out);
  fill(s, memory, kOurPenaltyKey, line_set(s, s.ball.x() - penalty_line_offset(s, true), "penalty_line", false), tmpl,
       reserved, out);
}

void play_their_penalty(const Situation& s, PlayMemory& memory, TeamIntents& out) {
  begin(s, out, "their_penalty");
  MotionIntent tmpl = base_intent(s, "penalty_line");
  tmpl.avoid_ball_radius = ball_clearance(s);
  Ids reserved;
  // The keeper touches its goal line until the ball is in play; after NORMAL_START it may slide along it.
  MotionIntent keeper_tmpl = base_intent(s, "penalty_defense");
  write_keeper(s, keeper_tmpl, true, reserved, out);
  if (s.keeper && !s.game->is_ready()) {
    MotionIntent& keeper = out.robots[*s.keeper];
    keeper.target.y() = 0;
  }
  fill(s, memory, kTheirPenaltyKey, line_set(s, s.ball.x() + penalty_line_offset(s, false), "penalty_line", true), tmpl,
       reserved, out);
}

void play_our_free_kick(const Situation& s, PlayMemory& memory, TeamIntents& out) {
  begin(s, out, "our_free_kick");
  MotionIntent tmpl = base_intent(s, "free_kick_support");
  tmpl.avoid_ball_radius = s.config->ball_keep_away;  // room for the kicker
  Ids reserved;
  write_keeper(s, tmpl, false, reserved, out);
  const std::optional<std::uint32_t> kicker = choose_closest(s, memory.kicker, s.ball);
  if (kicker && !reserved.contains(*kicker)) {
    reserved.add(*kicker);
    memory.restart_kicker = *kicker;
    set_piece_kick(s, *kicker, "free_kick", out);
  }
  fill(s, memory, kAttackKey, attack_set(s), tmpl, reserved, out);
}

void play_their_free_kick(const Situation& s, PlayMemory& memory, TeamIntents& out) {
  begin(s, out, "their_free_kick");
  MotionIntent tmpl = base_intent(s, "free_kick_defense");
  tmpl.avoid_ball_radius = ball_clearance(s);
  Ids reserved;
  write_keeper(s, tmpl, false, reserved, out);
  fill(s, memory, kDefensiveKey, defensive_set(s), tmpl, reserved, out);
}

// ---- base strategy --------------------------------------------------------------------------------------

/// In normal play the keeper clears a slow ball lying in our defense area or within kKeeperClearMargin of
/// it: no field player may fetch it there (robots keep out of our area, and an attacker behind the ball
/// would stand inside it), so without the keeper such a ball lies until the no-progress restart. Outside the
/// area only when it is there kKeeperClearLead before any opponent: else an opponent shoots into the goal
/// the keeper left.
constexpr double kKeeperClearMargin = 0.3;    // m around our defense area
constexpr double kKeeperClearMaxSpeed = 0.8;  // m/s: a faster ball is guarded, not chased
constexpr double kKeeperClearLead = 0.3;      // m the keeper must be nearer a ball outside the area
// s a ball may lie at rest there before the keeper clears it whoever is nearer: an opponent beside a ball on
// our area's edge may not get behind it either (on grSim, with no autoRef to call no progress, such a ball
// lay for 174 s).
constexpr double kKeeperClearAfterRest = 2.0;

bool keeper_should_clear(const Situation& s) {
  if (!s.keeper || !s.ball_known || s.ball_velocity.norm() > kKeeperClearMaxSpeed ||
      !s.field.in_our_defense_area(s.ball, kKeeperClearMargin) || !s.field.ball_in_field(s.ball)) {
    return false;
  }
  if (s.field.in_our_defense_area(s.ball, 0.0) || s.ball_at_rest_for >= kKeeperClearAfterRest) return true;
  const wm::RobotState* keeper = find_robot(s, *s.keeper);
  if (!keeper) return false;
  const double keeper_distance = (keeper->position - s.ball).norm();
  return std::none_of(s.enemies.begin(), s.enemies.end(), [&](const wm::RobotState& enemy) {
    return (enemy.position - s.ball).norm() < keeper_distance + kKeeperClearLead;
  });
}

/// The keeper clears the ball: the clear_ball skill, allowed in our defense area.
void write_keeper_clearing(const Situation& s, Ids& reserved, TeamIntents& out) {
  const wm::RobotState* keeper = find_robot(s, *s.keeper);
  if (!keeper) return;
  reserved.add(*s.keeper);
  MotionIntent intent = clear_ball(s, *keeper, {});
  intent.tactic = "clear_ball";
  intent.avoid_our_defense_area = false;
  intent.role = "goalkeeper";
  write(s, out, *s.keeper, intent);
}

bool strategy_goalkeeper(const Situation& s, TeamIntents& out) {
  Ids reserved;
  if (keeper_should_clear(s)) {
    write_keeper_clearing(s, reserved, out);
    return true;
  }
  write_keeper(s, base_intent(s, "defend"), false, reserved, out);
  return false;
}

void write_intent(const Situation& s, TeamIntents& out, std::uint32_t id, const MotionIntent& intent) {
  write(s, out, id, intent);
}

void strategy_approach(const Situation& s, std::uint32_t attacker, TeamIntents& out) {
  const wm::RobotState* robot = find_robot(s, attacker);
  if (!robot) return;
  MotionIntent intent = shoot(s, *robot, {});
  intent.tactic = "attack";
  intent.role = "attacker";
  write(s, out, attacker, intent);
}

/// m (centre to ball) where a chaser that is not the shooter stops: as near as two of them fit beside the
/// shooter, so that they crowd the ball without pushing each other into it.
constexpr double kChaserDistance = 0.35;

void play_ball_chaser(const Situation& s, PlayMemory& memory, TeamIntents& out) {
  begin(s, out, "ball_chaser");
  Ids reserved;
  write_keeper(s, base_intent(s, "defend"), false, reserved, out);
  if (!s.ball_known) return;
  const std::optional<std::uint32_t> shooter = choose_closest(s, memory.kicker, s.ball);
  if (shooter && !reserved.contains(*shooter)) {
    strategy_approach(s, *shooter, out);
    out.robots[*shooter].tactic = "chase";
    reserved.add(*shooter);
  }
  for (const wm::RobotState& robot : s.robots) {
    if (reserved.contains(robot.id)) continue;
    const Vec2 from_ball = geom::normalized_or(robot.position - s.ball, Vec2(-1, 0));
    MotionIntent intent = go_to_point(s, robot, {.point = s.ball + from_ball * kChaserDistance});
    intent.tactic = "chase";
    intent.role = "chaser";
    write(s, out, robot.id, intent);
  }
}

}  // namespace ssl::planner
