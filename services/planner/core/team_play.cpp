#include "services/planner/core/team_play.h"

#include <algorithm>
#include <cmath>

#include "libs/geometry/vec2.h"
#include "services/planner/core/skills.h"
#include "services/planner/core/trajectory.h"

namespace ssl::planner {
namespace {

constexpr double kRollingDeceleration = 0.35;  // m/s^2 of a rolling ball on the carpet
constexpr double kKickedSpeed = 1.0;           // m/s: a ball this fast away from the passer was kicked
constexpr double kKickContact = 0.05;          // m beyond touching: the ball is at the passer's dribbler
constexpr double kKickRecent = 0.15;           // s since the ball was at the dribbler: the passer kicked it
constexpr double kKickAngle = 0.35;            // rad between the ball's run and the pass line
constexpr double kTaken = 0.05;                // m beyond touching, receiver to ball: the pass arrived
constexpr double kLostSpeed = 0.3;             // m/s: a pass this slow far from its receiver is dead
constexpr double kLostDistance = 0.8;          // m
constexpr double kDeflectedAngle = 0.6;        // rad between the ball's run and the way to the pass's point
constexpr double kDeflectReach = 0.05;         // m beyond touching: a robot this near the ball could deflect it
constexpr double kDeflectRecent = 0.3;         // s since a robot could have deflected the ball
constexpr double kAttackerLead = 0.2;          // s the attacker race looks ahead along the ball's motion
constexpr double kDefenderMisfit = 0.5;        // s added for a defender slot to a robot ahead of the ball
constexpr double kPassAreaClearance = 0.5;     // m: passes are received at least this far from their area
constexpr double kBackPassAreaClearance = 1.0;  // m: passes back are received at least this far from ours
constexpr std::uint32_t kRoleKeyBase = 100;    // StableAssigner keys of the styles' formations
constexpr double kStrategyGap = 0.1;           // s without a strategy tick: play was stopped in between
constexpr double kHoldApproachSpeed = 0.5;     // m/s faster than the ball the holder takes it with
constexpr double kKickFacing = 0.1;            // rad: a holder facing its kick this well kicks (behind_ball_facing)
constexpr double kTurnAreaClearance = 0.15;    // m: a ball this near their defense area is not turned with
// What a shot is worth by its distance from their goal centre (shot_quality): in full up to kShotFullUpTo,
// nothing from kShotWorthlessFrom. bench/match_series --robots 11 (base against base, seeds 51-90, two 120 s
// halves, realistic), with shots valued up to 7 m: of the shots from under 3 m 41 % went in (at once or after
// the keeper touched them), from 3-5 m 12 %, from 5-7 m none, from farther 1 in 335; valued up to 4.5 m,
// 1.68 goals a match instead of 1.35 (up to 4 m: 1.60, up to 5.5 m: 1.74).
constexpr double kShotFullUpTo = 2.0;         // m
constexpr double kShotWorthlessFrom = 4.5;    // m
constexpr double kRedirectGrid = 0.25;         // m between the points it rates
constexpr double kRedirectBack = 0.25;         // m behind the ball a point may lie, at most
constexpr double kRedirectRange = 1.8;         // m from their goal centre beyond their defense area's depth
constexpr double kRedirectReachCost = 0.05;    // shot quality a second of the receiver's way costs
constexpr double kRedirectInPlace = 0.08;      // m: the receiver is at its spot ...
constexpr double kRedirectStill = 0.2;         // m/s ... and standing
constexpr double kRedirectStaging = 0.1;       // m beyond dribbling distance the kicker waits behind the ball

double sign_or_one(double v) { return v < 0 ? -1.0 : 1.0; }

double time_to_reach(const Situation& s, const wm::RobotState& robot, const Vec2& target) {
  const TrajectoryLimits limits{.max_speed = s.config->limits.max_speed,
                                .max_acceleration = s.config->limits.max_acceleration};
  return Trajectory2D::plan(robot.position, robot.velocity, target, limits).duration();
}

/// Seconds a robot standing needs to cover `distance` at `acceleration` up to `speed`.
double time_to_cover(double distance, double speed, double acceleration) {
  const double ramp = speed * speed / (2 * acceleration);
  if (distance <= ramp) return std::sqrt(2 * distance / acceleration);
  return speed / acceleration + (distance - ramp) / speed;
}

/// Seconds a pass kicked to arrive at `arrival` m/s over `length` takes to roll `x` metres.
double ball_time(double length, double x, double arrival) {
  const double v0 = std::sqrt(arrival * arrival + 2 * kRollingDeceleration * length);
  const double under = std::max(0.0, v0 * v0 - 2 * kRollingDeceleration * x);
  return (v0 - std::sqrt(under)) / kRollingDeceleration;
}

Vec2 inside_field(const Situation& s, const Vec2& p, double margin) {
  const double x = s.field.half_length() - margin;
  const double y = s.field.width() / 2 - margin;
  return {std::clamp(p.x(), -x, x), std::clamp(p.y(), -y, y)};
}

MotionIntent as_role(MotionIntent intent, Role role, std::string_view tactic) {
  intent.role = to_string(role);
  intent.tactic = tactic;
  return intent;
}

/// A role instance of the formation: where it stands (or whom it marks).
struct Slot {
  Role role = Role::kMidfieldSupport;
  Vec2 anchor = Vec2::Zero();
  std::optional<std::uint32_t> opponent;
};

/// The two shooting lanes from the ball to each half of our goal, blocked just outside our defense area.
std::array<Vec2, 2> lane_blocks(const Situation& s) {
  const Vec2 goal = s.field.our_goal_center();
  const double quarter = s.field.size().goal_width / 4;
  const double margin = s.config->robot_radius + 0.1;
  std::array<Vec2, 2> out{};
  for (int k = 0; k < 2; ++k) {
    const Vec2 aim = goal + Vec2(0, k == 0 ? quarter : -quarter);
    const Vec2 towards = s.ball - aim;
    const double length = std::max(towards.norm(), 1e-6);
    Vec2 spot = aim;
    for (double t = 0; t <= length; t += 0.05) {
      spot = aim + towards / length * t;
      if (!s.field.in_our_defense_area(spot, margin)) break;
    }
    out[static_cast<std::size_t>(k)] = spot;
  }
  // Shoulder to shoulder at least: two robots never stand in each other.
  const Vec2 gap = out[0] - out[1];
  const double need = 2 * s.config->robot_radius + 0.04;
  if (gap.norm() < need) {
    const Vec2 across = geom::normalized_or(geom::perpendicular(Vec2(s.ball - goal)), Vec2(0, 1));
    const Vec2 middle = (out[0] + out[1]) / 2;
    out[0] = middle + across * (need / 2);
    out[1] = middle - across * (need / 2);
  }
  return out;
}

/// Opponents worth marking, most dangerous (nearest our goal) first: not in their own defense area (their
/// keeper), not the one `pressed` by our attacker.
std::vector<const wm::RobotState*> dangerous_opponents(const Situation& s, std::optional<std::uint32_t> pressed) {
  std::vector<const wm::RobotState*> out;
  for (const wm::RobotState& enemy : s.enemies) {
    if (s.field.in_their_defense_area(enemy.position, 0.0)) continue;
    if (pressed && enemy.id == *pressed) continue;
    out.push_back(&enemy);
  }
  const Vec2 goal = s.field.our_goal_center();
  std::sort(out.begin(), out.end(), [&](const wm::RobotState* a, const wm::RobotState* b) {
    const double da = (a->position - goal).norm();
    const double db = (b->position - goal).norm();
    return da != db ? da < db : a->id < b->id;
  });
  return out;
}

/// The opponent nearest the ball (the carrier when they have it); nullptr when none is seen.
const wm::RobotState* opponent_at_ball(const Situation& s) {
  const wm::RobotState* best = nullptr;
  double best_distance = 0;
  for (const wm::RobotState& enemy : s.enemies) {
    const double d = (enemy.position - s.ball).norm();
    if (!best || d < best_distance) {
      best = &enemy;
      best_distance = d;
    }
  }
  return best;
}

/// The style's roles (but the first) for `count` field players. While the keeper clears a ball at our defense
/// area, nobody blocks the lanes: the defenders would stand between the keeper and the ball it kicks.
std::vector<Slot> formation_slots(const Situation& s, Style style, std::size_t count, bool pressing,
                                  bool keeper_clears) {
  std::vector<Slot> slots;
  const std::span<const Role> roles = roles_of(style);
  const double depth = s.field.size().penalty_area_depth;
  const double front_x = s.field.half_length() - depth - 0.4;
  const double back_x = -s.field.half_length() + depth + 0.5;
  const std::array<Vec2, 2> lanes = lane_blocks(s);
  const wm::RobotState* carrier = pressing ? opponent_at_ball(s) : nullptr;
  const std::vector<const wm::RobotState*> dangerous =
      dangerous_opponents(s, carrier ? std::optional(carrier->id) : std::nullopt);
  int wingers = 0, supports = 0, defenders = 0;
  std::size_t marked = 0;
  for (std::size_t i = 0; i < count; ++i) {
    Role role = roles[std::min(i + 1, roles.size() - 1)];  // roles[0]: the attacker / presser, chosen apart
    if (role == Role::kDefender && (defenders >= 2 || keeper_clears)) role = Role::kMarker;
    if (role == Role::kMarker && marked >= dangerous.size()) role = Role::kMidfieldSupport;
    Slot slot{.role = role};
    switch (role) {
      case Role::kWinger: {
        const double side = (wingers++ % 2 == 0 ? -1.0 : 1.0) * sign_or_one(s.ball.y());
        slot.anchor = {std::clamp(s.ball.x() + 1.5, back_x, front_x), side * 0.3 * s.field.width()};
        break;
      }
      case Role::kMidfieldSupport: {
        const double side = (supports++ % 2 == 0 ? 1.0 : -1.0) * -sign_or_one(s.ball.y());
        slot.anchor = inside_field(s, {std::clamp(s.ball.x() - 0.8, back_x, front_x), s.ball.y() + side * 1.5}, 0.3);
        break;
      }
      case Role::kDefender:
        slot.anchor = lanes[static_cast<std::size_t>(defenders++)];
        break;
      case Role::kMarker:
        slot.opponent = dangerous[marked]->id;
        slot.anchor = dangerous[marked]->position;
        ++marked;
        break;
      case Role::kGoalie:
      case Role::kAttacker:
      case Role::kReceiver:
      case Role::kPresser:
        slot.anchor = s.ball;
        break;
    }
    slots.push_back(slot);
  }
  return slots;
}

MotionIntent role_default(const Situation& s, const wm::RobotState& robot, const Slot& slot) {
  switch (slot.role) {
    case Role::kWinger:
      return as_role(open_space(s, robot, {.anchor = slot.anchor, .radius = 0.8}), slot.role, "support_attack");
    case Role::kDefender:
      return as_role(go_to_point(s, robot, {.point = slot.anchor}), slot.role, "block_lanes");
    case Role::kMarker:
      return as_role(man_mark(s, robot, {.opponent = *slot.opponent}), slot.role, "mark");
    case Role::kMidfieldSupport:
    case Role::kGoalie:
    case Role::kAttacker:
    case Role::kReceiver:
    case Role::kPresser:
      break;
  }
  return as_role(open_space(s, robot, {.anchor = slot.anchor, .radius = 0.8}), Role::kMidfieldSupport, "support");
}

/// The ball lies within kTurnAreaClearance of their defense area: turning with it would drag it in (a robot
/// touching a ball inside is a foul).
bool ball_near_their_area(const Situation& s) { return s.field.in_their_defense_area(s.ball, kTurnAreaClearance); }

/// `kick` (a pass, shot or clearance along `u`) by a robot that holds the ball: it first turns with the ball
/// on its dribbler until it faces `u` (going round the ball would hand it to a nearby opponent).
MotionIntent kick_from_dribbler(const Situation& s, const wm::RobotState& robot, const Vec2& u, MotionIntent kick) {
  const Vec2 heading = geom::Angle::from_radians(robot.orientation).to_unit_vector();
  if (!holds_ball(s, robot) || heading.dot(u) > std::cos(kKickFacing) || ball_near_their_area(s)) return kick;
  MotionIntent turn = turn_with_ball(s, robot, {.orientation = geom::angle_of(u).radians()});
  turn.role = kick.role;
  turn.tactic = kick.tactic;
  return turn;
}

/// m/s the pass arrives with: faster for a one-touch redirect (the keeper has less time to move across).
double arrival_speed(const TeamPlayMemory& m) {
  return m.pass && m.pass->one_touch ? m.params.redirect_arrival_speed : m.params.arrival_speed;
}

/// m, passer centre to ball centre within which the ball is at the passer's dribbler.
double passer_contact(const Situation& s) { return s.config->robot_radius + s.field.size().ball_radius + kKickContact; }

/// Notes when the ball of the pass being set up was last at its passer's dribbler (pass_in_progress tells a
/// kick by the passer from a ball somebody else played that way).
void note_ball_at_passer(const Situation& s, PassIntent& pass, const wm::RobotState& passer) {
  if ((s.ball - passer.position).norm() < passer_contact(s)) pass.ball_at_passer = s.now;
}

/// How the pass being set up is re-rated every tick: kept while it is still possible at all (hysteresis), called
/// off once an opponent could reach its line first or stands in the ball's path.
TeamPlayParams still_possible(const TeamPlayMemory& m) {
  TeamPlayParams keep = m.params;
  keep.arrival_speed = arrival_speed(m);
  keep.min_margin = m.params.keep_margin;
  keep.min_open_angle = 0;
  keep.min_lane_clearance = 0;  // called off once an opponent stands in the ball's path
  keep.min_pass = 0;  // the ball moves at the passer's feet: the pass's length is not the question now
  keep.max_pass = (m.pass && m.pass->one_touch ? m.params.redirect_max_pass : m.params.max_pass) + 1.0;
  return keep;
}

/// The pass's receiver shooting it on at the first touch: at the point, facing the open part of their goal.
MotionIntent redirect_at(const Situation& s, const TeamPlayMemory& m, const wm::RobotState& receiver) {
  const Vec2 point = m.pass->point;
  return redirect(s, receiver, {.point = point, .aim = goal_opening(s, point, receiver.id).target,
                                .max_angle = m.params.redirect_max_angle});
}

}  // namespace

double shot_quality(const Situation& s, const Vec2& from, std::optional<std::uint32_t> shooter) {
  const double distance = (s.field.their_goal_center() - from).norm();
  const double open = std::min(1.0, goal_opening(s, from, shooter).width / 0.25);
  return open * std::clamp((kShotWorthlessFrom - distance) / (kShotWorthlessFrom - kShotFullUpTo), 0.0, 1.0);
}

std::optional<PassOption> rate_pass(const Situation& s, std::uint32_t receiver, const Vec2& point,
                                    const TeamPlayParams& params) {
  const double reach = s.config->robot_radius + s.field.size().ball_radius;
  PassOption option{.receiver = receiver, .point = point};
  const Vec2 line = point - s.ball;
  const double length = line.norm();
  if (length < params.min_pass || length > params.max_pass) return std::nullopt;
  // Never back to the front of our defense area: a pass lost there is a chance for them in front of our goal.
  if (line.x() < 0 && s.field.in_our_defense_area(point, kBackPassAreaClearance)) return std::nullopt;
  const Vec2 u = line / length;
  double margin = 1e9;
  double open = M_PI;
  double lane = 1e9;  // m between the nearest opponent body and the ball's path
  for (const wm::RobotState& enemy : s.enemies) {
    // Where it is once it reacts (it keeps going meanwhile), then from standing to the line's nearest point.
    const Vec2 start = enemy.position + enemy.velocity * params.opponent_reaction;
    const Vec2 to_enemy = start - s.ball;
    const double along = std::clamp(to_enemy.dot(u), 0.0, length);
    const Vec2 closest = s.ball + u * along;
    const double enemy_time = time_to_cover(std::max(0.0, (start - closest).norm() - reach), params.opponent_speed,
                                            params.opponent_acceleration) +
                              params.opponent_reaction;
    margin = std::min(margin, enemy_time - ball_time(length, along, params.arrival_speed));
    if (to_enemy.dot(u) > 0 && to_enemy.norm() < length + 0.3) {
      open = std::min(open, std::abs(std::atan2(geom::cross(u, to_enemy), u.dot(to_enemy))));
    }
    const Vec2 from_ball = enemy.position - s.ball;
    const Vec2 on_path = s.ball + u * std::clamp(from_ball.dot(u), 0.0, length);
    lane = std::min(lane, (enemy.position - on_path).norm() - reach);
  }
  if (margin < params.min_margin || open < params.min_open_angle || lane < params.min_lane_clearance) {
    return std::nullopt;
  }
  option.margin = margin;
  option.open_angle = open;
  option.progress = line.x();
  option.receiver_shot = shot_quality(s, point, receiver);
  option.score = option.receiver_shot + 0.6 * std::clamp(option.progress / 3.0, -1.0, 1.0) + 0.3 * std::min(margin, 1.0);
  return option;
}

std::vector<PassOption> rate_passes(const Situation& s, std::uint32_t passer, const TeamPlayParams& params) {
  std::vector<PassOption> options;
  for (const wm::RobotState& mate : s.robots) {
    if (mate.id == passer || (s.keeper && mate.id == *s.keeper)) continue;
    // The ball goes where the receiver can stand still to take it: at the dribbler of a running teammate
    // stopped (it cannot turn round in time to meet a ball played to where it was; a ball played to its
    // centre's stopping point makes it run on into the ball). A receiver next to their defense area takes the
    // ball a step back from it: a ball it does not stop at once would roll into the area, where nobody of ours
    // may play it.
    const Vec2 stop = mate.position + mate.velocity * (mate.velocity.norm() / (2 * s.config->limits.max_acceleration));
    Vec2 point = stop + geom::normalized_or(s.ball - stop, Vec2(1, 0)) * dribbler_distance(s);
    const double front = s.field.half_length() - s.field.size().penalty_area_depth - kPassAreaClearance;
    if (s.field.in_their_defense_area(point, kPassAreaClearance)) point.x() = std::min(point.x(), front);
    if (auto option = rate_pass(s, mate.id, point, params)) options.push_back(*option);
  }
  std::sort(options.begin(), options.end(), [](const PassOption& a, const PassOption& b) {
    return a.score != b.score ? a.score > b.score : a.receiver < b.receiver;
  });
  return options;
}

void read_game(const Situation& s, TeamPlayMemory& m) {
  // A pass does not outlive a stoppage: the strategy was not ticked in between.
  if (m.last_tick && s.now - *m.last_tick > kStrategyGap) m.pass.reset();
  m.last_tick = s.now;
  m.reading = m.coach.read(s);
  m.style = m.coach.decide(m.reading, s.now);
}

std::optional<std::uint32_t> assign_roles(const Situation& s, TeamPlayMemory& m, TeamIntents& out) {
  out.play = "base_strategy";
  for (MotionIntent& intent : out.robots) intent = MotionIntent{};
  m.role_of.fill(std::nullopt);
  m.marked.fill(std::nullopt);
  const bool keeper_clears = strategy_goalkeeper(s, out);
  if (s.keeper) m.role_of[*s.keeper] = Role::kGoalie;

  std::array<std::uint32_t, kMaxSlots> free_ids{};
  std::size_t free_count = 0;
  std::optional<std::uint32_t> attacker;
  std::optional<std::uint32_t> receiver;
  if (m.pass) {
    receiver = m.pass->receiver;
    if (m.pass->phase == PassIntent::Phase::kSetUp) attacker = m.pass->passer;
  } else if (!keeper_clears && s.ball_known) {
    std::array<std::uint32_t, kMaxSlots> ids{};
    std::array<double, kMaxSlots> scores{};
    std::size_t n = 0;
    const Vec2 ball_ahead = s.ball + s.ball_velocity * kAttackerLead;
    for (const wm::RobotState& robot : s.robots) {
      if (s.keeper && robot.id == *s.keeper) continue;
      if (s.restart_kicker && robot.id == *s.restart_kicker) continue;  // no double touch
      ids[n] = robot.id;
      scores[n++] = time_to_reach(s, robot, ball_ahead);
    }
    attacker = m.attacker.choose({ids.data(), n}, {scores.data(), n});
  }
  for (const wm::RobotState& robot : s.robots) {
    if ((s.keeper && robot.id == *s.keeper) || robot.id == attacker || robot.id == receiver) continue;
    free_ids[free_count++] = robot.id;
  }
  if (attacker) m.role_of[*attacker] = mode_of(m.style) == TeamMode::kDefending ? Role::kPresser : Role::kAttacker;
  if (receiver) m.role_of[*receiver] = Role::kReceiver;

  const bool pressing = attacker && mode_of(m.style) == TeamMode::kDefending;
  const std::vector<Slot> slots = formation_slots(s, m.style, free_count, pressing, keeper_clears);
  CostMatrix cost{};
  for (std::size_t r = 0; r < free_count; ++r) {
    const wm::RobotState& robot = *find_robot(s, free_ids[r]);
    for (std::size_t c = 0; c < slots.size(); ++c) {
      double t = time_to_reach(s, robot, slots[c].anchor);
      if (slots[c].role == Role::kDefender && robot.position.x() > s.ball.x()) t += kDefenderMisfit;
      cost[r][c] = t;
    }
  }
  const std::span<const int> slot_of = m.roles.assign_costs(
      kRoleKeyBase + static_cast<std::uint32_t>(m.style), {free_ids.data(), free_count},
      cost, slots.size());
  for (std::size_t r = 0; r < free_count; ++r) {
    if (slot_of[r] < 0) continue;
    const Slot& slot = slots[static_cast<std::size_t>(slot_of[r])];
    const std::uint32_t id = free_ids[r];
    m.role_of[id] = slot.role;
    m.formation[id] = slot.anchor;
    m.marked[id] = slot.opponent;
    write_intent(s, out, id, role_default(s, *find_robot(s, id), slot));
  }
  return attacker;
}

bool pass_in_progress(const Situation& s, TeamPlayMemory& m) {
  if (!m.pass) return false;
  PassIntent& pass = *m.pass;
  const TeamPlayParams& params = m.params;
  const wm::RobotState* passer = find_robot(s, pass.passer);
  const wm::RobotState* receiver = find_robot(s, pass.receiver);
  const auto end = [&] {
    m.pass.reset();
    return false;
  };
  if (!passer || !receiver || !s.ball_known) return end();
  const double speed = s.ball_velocity.norm();
  if (pass.phase == PassIntent::Phase::kSetUp) {
    // Kicked by the passer: the ball was at its dribbler a moment ago and now runs along the pass (not a ball
    // somebody else played that way).
    note_ball_at_passer(s, pass, *passer);
    const Vec2 along = geom::normalized_or(pass.point - passer->position, Vec2(1, 0));
    const bool leaving = speed > kKickedSpeed && (s.ball - passer->position).norm() >= passer_contact(s);
    const bool from_passer = pass.ball_at_passer && s.now - *pass.ball_at_passer < kKickRecent;
    const bool on_line = s.ball_velocity.dot(along) > speed * std::cos(kKickAngle);
    if (leaving && from_passer && on_line) {
      pass.phase = PassIntent::Phase::kInFlight;
      pass.since = s.now;
    } else if (s.now - pass.since > params.set_up_timeout || s.possession == wm::Possession::kEnemy) {
      return end();
    } else {
      // Still a good pass? Opponents move while the passer lines up: re-rated every tick, it is called off
      // (and the attacker decides again) once an opponent could reach its line first.
      if (!rate_pass(s, pass.receiver, pass.point, still_possible(m))) return end();
    }
  }
  if (pass.phase == PassIntent::Phase::kInFlight) {
    const double to_receiver = (s.ball - receiver->position).norm();
    // Taken: the receiver, now nearest the ball, is the next attacker. A one-touch pass is taken by its kick
    // (the ball then runs off the pass's line: deflected, below), or by the receiver once it stopped there.
    if (to_receiver < kTaken + dribbler_distance(s) && (!pass.one_touch || speed < kKickedSpeed)) return end();
    const bool dead = speed < kLostSpeed && to_receiver > kLostDistance;
    // Deflected (off a robot of either team): a robot reached the ball a moment ago and the ball no longer
    // runs towards the pass's point. Without the robot, a turn of the estimated velocity is noise (the
    // estimate jumps where two cameras' views meet), not a deflection.
    const double reach = s.config->robot_radius + s.field.size().ball_radius + kDeflectReach;
    const auto within_reach = [&](const wm::RobotState& robot) { return (robot.position - s.ball).norm() < reach; };
    if (std::any_of(s.robots.begin(), s.robots.end(), within_reach) ||
        std::any_of(s.enemies.begin(), s.enemies.end(), within_reach)) {
      pass.ball_at_robot = s.now;
    }
    const bool touched = pass.ball_at_robot && s.now - *pass.ball_at_robot < kDeflectRecent;
    const Vec2 to_point = pass.point - s.ball;
    const bool deflected = touched && speed > kLostSpeed && to_point.norm() > kLostDistance &&
                           s.ball_velocity.dot(to_point) < speed * to_point.norm() * std::cos(kDeflectedAngle);
    const bool late = s.now - pass.since > params.flight_timeout;
    const double touch = s.config->robot_radius + s.field.size().ball_radius + 0.01;
    const bool intercepted = std::any_of(s.enemies.begin(), s.enemies.end(), [&](const wm::RobotState& enemy) {
      return (enemy.position - s.ball).norm() < touch;
    });
    if (dead || late || intercepted || deflected) return end();
  }
  return true;
}

void pass_ball(const Situation& s, TeamPlayMemory& m, TeamIntents& out) {
  if (!m.pass || m.pass->phase != PassIntent::Phase::kSetUp) return;
  const wm::RobotState* passer = find_robot(s, m.pass->passer);
  if (!passer) return;
  const MotionIntent kick =
      as_role(pass(s, *passer, {.receiver = m.pass->point, .arrival_speed = arrival_speed(m)}), Role::kAttacker, "pass");
  write_intent(s, out, passer->id,
               kick_from_dribbler(s, *passer, geom::normalized_or(m.pass->point - s.ball, Vec2(1, 0)), kick));
}

void receive_pass(const Situation& s, TeamPlayMemory& m, TeamIntents& out) {
  if (!m.pass) return;
  const wm::RobotState* receiver = find_robot(s, m.pass->receiver);
  if (!receiver) return;
  if (m.pass->one_touch) {
    write_intent(s, out, receiver->id, as_role(redirect_at(s, m, *receiver), Role::kReceiver, "pass"));
    return;
  }
  write_intent(s, out, receiver->id,
               as_role(receive(s, *receiver, {.point = m.pass->point}), Role::kReceiver, "pass"));
}

namespace {

/// m, centre to their defense area, our robots keep before a free kick is in play (the rule's distance).
double free_kick_area_margin(const Situation& s) {
  return s.config->defense_area_keep_away + s.config->robot_radius + s.config->keep_away_margin;
}

}  // namespace

std::optional<PassOption> rate_free_kick_pass(const Situation& s, std::uint32_t passer, const TeamPlayParams& params) {
  const double straight = shot_quality(s, s.ball, passer);
  if (straight >= params.shoot_quality) return std::nullopt;
  // Before the kick our robots keep the free kick's distance from their defense area: so does the receiver.
  const double area_margin = free_kick_area_margin(s);
  for (const PassOption& option : rate_passes(s, passer, params)) {
    if (option.score <= straight + params.pass_advantage) break;  // best first
    if (!s.field.in_their_defense_area(option.point, area_margin)) return option;
  }
  return std::nullopt;
}

std::optional<PassOption> rate_redirect(const Situation& s, std::uint32_t passer, const TeamPlayParams& params) {
  TeamPlayParams rating = params;
  rating.arrival_speed = params.redirect_arrival_speed;
  rating.min_pass = params.redirect_min_pass;
  rating.max_pass = params.redirect_max_pass;
  const double dd = dribbler_distance(s);
  // Before the kick our robots keep the free kick's distance from their defense area.
  const double area_margin = free_kick_area_margin(s);
  const Vec2 goal = s.field.their_goal_center();
  const double straight = shot_quality(s, s.ball, passer);
  std::optional<PassOption> best;
  double best_score = std::max(straight + params.redirect_advantage, params.redirect_min_shot);
  const double range = s.field.size().penalty_area_depth + kRedirectRange;  // 2.8 m in division B, 3.6 m in A
  // A grid anchored on their goal line, from the far end towards the goal.
  for (int column = static_cast<int>(range / kRedirectGrid); column >= 1; --column) {
    const double x = goal.x() - column * kRedirectGrid;
    for (double y = -s.field.half_width() + kRedirectGrid; y < s.field.half_width(); y += kRedirectGrid) {
      const Vec2 point(x, y);
      // Forward or across, near their goal: a pass back from the restart leaves the ball in midfield when the
      // shot fails.
      if (point.x() < s.ball.x() - kRedirectBack || (point - goal).norm() > range) continue;
      const double length = (point - s.ball).norm();
      if (length < rating.min_pass || length > rating.max_pass) continue;
      const GoalOpening opening = goal_opening(s, point);
      const Vec2 back = geom::normalized_or(s.ball - point, Vec2(1, 0));
      const Vec2 on = geom::normalized_or(opening.target - point, Vec2(1, 0));
      if (std::acos(std::clamp(back.dot(on), -1.0, 1.0)) > params.redirect_max_angle) continue;
      // The receiver stands behind the point, facing the shot.
      if (s.field.in_their_defense_area(point - on * dd, area_margin)) continue;
      const wm::RobotState* receiver = nullptr;
      double reach = params.redirect_max_reach;
      for (const wm::RobotState& mate : s.robots) {
        if (mate.id == passer || (s.keeper && mate.id == *s.keeper)) continue;
        const double t = time_to_reach(s, mate, point - on * dd);
        if (t <= reach) {
          reach = t;
          receiver = &mate;
        }
      }
      if (!receiver) continue;
      std::optional<PassOption> option = rate_pass(s, receiver->id, point, rating);
      if (!option) continue;
      const double score = option->receiver_shot - kRedirectReachCost * reach;
      if (score > best_score) {
        best_score = score;
        best = option;
      }
    }
  }
  return best;
}

namespace {

/// The restart being played: a new one after a gap in the restart's ticks (play stopped in between).
RestartPlay& restart_play(const Situation& s, TeamPlayMemory& m) {
  if (!m.restart || s.now - m.restart->last_tick > kStrategyGap) {
    m.restart = RestartPlay{.since = s.now, .last_tick = s.now};
    m.pass.reset();
  }
  m.restart->last_tick = s.now;
  m.last_tick = s.now;  // the strategy takes the pass over once the ball is in play
  return *m.restart;
}

struct PassEnds {
  const wm::RobotState* passer = nullptr;
  const wm::RobotState* receiver = nullptr;
};

/// One tick of our restart's set play up to the kick (the restart's kicker named, the ball seen): on the
/// restart's first tick `choose()` gives the pass (nullopt: no set play); every tick the pass is re-checked:
/// its passer (still the kicker) and receiver on the field, set up within `set_up_timeout` of the restart's
/// first tick and still possible. Returns its ends while the set play is on; otherwise the kicker's straight
/// shot stands (RestartPlay::shoot, for the rest of the restart). Keeps the pass's set-up clock at the
/// restart's last tick (once the ball is in play the dynamic pass's own timeout counts from there).
template <typename Choose>
std::optional<PassEnds> set_play_pass(const Situation& s, TeamPlayMemory& m, double set_up_timeout,
                                      Choose choose) {
  if (!s.restart_kicker || !s.ball_known) return std::nullopt;
  const std::uint32_t kicker = *s.restart_kicker;
  RestartPlay& restart = restart_play(s, m);
  if (restart.shoot) return std::nullopt;
  const auto give_up = [&]() -> std::optional<PassEnds> {
    restart.shoot = true;
    m.pass.reset();
    return std::nullopt;
  };
  if (!m.pass) {
    m.pass = choose(kicker);
    if (!m.pass) return give_up();
  }
  PassIntent& pass = *m.pass;
  const PassEnds ends{find_robot(s, pass.passer), find_robot(s, pass.receiver)};
  if (!ends.passer || !ends.receiver || pass.passer != kicker || s.now - restart.since > set_up_timeout ||
      !rate_pass(s, pass.receiver, pass.point, still_possible(m))) {
    return give_up();
  }
  pass.since = s.now;
  note_ball_at_passer(s, pass, *ends.passer);
  return ends;
}

/// The set play's pass to a teammate where it stands (rate_passes): the receiver takes it there, the kicker
/// plays it at once.
void pass_where_it_stands(const Situation& s, const TeamPlayMemory& m, const PassEnds& ends,
                          std::string_view receive_tactic, std::string_view pass_tactic, TeamIntents& out) {
  const Vec2& point = m.pass->point;
  write_intent(s, out, ends.receiver->id,
               as_role(receive(s, *ends.receiver, {.point = point}), Role::kReceiver, receive_tactic));
  write_intent(s, out, ends.passer->id,
               as_role(planner::pass(s, *ends.passer, {.receiver = point, .arrival_speed = arrival_speed(m)}),
                       Role::kAttacker, pass_tactic));
}

}  // namespace

void free_kick_set_play(const Situation& s, TeamPlayMemory& m, TeamIntents& out) {
  const TeamPlayParams& params = m.params;
  const std::optional<PassEnds> ends =
      set_play_pass(s, m, params.redirect_set_up_timeout, [&](std::uint32_t kicker) -> std::optional<PassIntent> {
        if (const std::optional<PassOption> option = rate_redirect(s, kicker, params)) {
          return PassIntent{.passer = kicker, .receiver = option->receiver, .point = option->point, .since = s.now,
                            .one_touch = true};
        }
        if (s.config->free_kick != FreeKickPlay::kPass) return std::nullopt;
        const std::optional<PassOption> option = rate_free_kick_pass(s, kicker, params);
        if (!option) return std::nullopt;
        return PassIntent{.passer = kicker, .receiver = option->receiver, .point = option->point, .since = s.now};
      });
  if (!ends) return;
  const PassIntent& pass = *m.pass;
  const wm::RobotState& passer = *ends->passer;
  const wm::RobotState& receiver = *ends->receiver;
  if (!pass.one_touch) {
    pass_where_it_stands(s, m, *ends, "free_kick_receive", "free_kick_pass", out);
    return;
  }
  const MotionIntent wait = redirect_at(s, m, receiver);
  write_intent(s, out, receiver.id, as_role(wait, Role::kReceiver, "free_kick_redirect"));
  // The kicker passes once the receiver stands still at its spot; until then it waits behind the ball,
  // facing the pass, clear of it (a touch now puts the ball in play).
  const bool ready = (receiver.position - wait.target).norm() < kRedirectInPlace &&
                     receiver.velocity.norm() < kRedirectStill;
  const Vec2 u = geom::normalized_or(pass.point - s.ball, Vec2(1, 0));
  MotionIntent kick = ready ? planner::pass(s, passer, {.receiver = pass.point, .arrival_speed = arrival_speed(m)})
                            : go_to_point(s, passer, {.point = s.ball - u * (dribbler_distance(s) + kRedirectStaging),
                                                      .orientation = geom::angle_of(u).radians()});
  kick.avoid_ball_radius = ready ? 0.0 : dribbler_distance(s) + kRedirectStaging / 2;
  write_intent(s, out, passer.id, as_role(kick, Role::kAttacker, "free_kick_pass"));
}

void kickoff_set_play(const Situation& s, TeamPlayMemory& m, TeamIntents& out) {
  const std::optional<PassEnds> ends =
      set_play_pass(s, m, m.params.kickoff_set_up_timeout, [&](std::uint32_t kicker) -> std::optional<PassIntent> {
        // Until the ball is in play the receiver, as every robot but the kicker, stays where the kickoff allows.
        const std::vector<PassOption> options = rate_passes(s, kicker, m.params);
        const auto best = std::find_if(options.begin(), options.end(), [&](const PassOption& option) {
          return legal_before_our_kickoff(s, option.point);
        });
        if (best == options.end()) return std::nullopt;
        return PassIntent{.passer = kicker, .receiver = best->receiver, .point = best->point, .since = s.now};
      });
  if (!ends) return;
  pass_where_it_stands(s, m, *ends, "kickoff_receive", "kickoff_pass", out);
}

namespace {

void start_pass(const Situation& s, TeamPlayMemory& m, std::uint32_t passer, const PassOption& option,
                TeamIntents& out) {
  m.pass = PassIntent{.passer = passer,
                      .receiver = option.receiver,
                      .point = option.point,
                      .phase = PassIntent::Phase::kSetUp,
                      .since = s.now};
  m.role_of[option.receiver] = Role::kReceiver;
  pass_ball(s, m, out);
  receive_pass(s, m, out);
}

}  // namespace

void hold_ball(const Situation& s, TeamPlayMemory& m, const wm::RobotState& robot, TeamIntents& out) {
  if (!holds_ball(s, robot)) {
    // Gently onto a lying ball; a rolling one is caught up with.
    MotionIntent intent = go_to_ball(s, robot, {.final_speed = kHoldApproachSpeed + s.ball_velocity.norm()});
    write_intent(s, out, robot.id, as_role(intent, Role::kAttacker, "hold"));
    return;
  }
  const Vec2 heading = geom::Angle::from_radians(robot.orientation).to_unit_vector();
  const auto off_heading = [&](const Vec2& point) {
    const Vec2 u = geom::normalized_or(point - s.ball, heading);
    return std::acos(std::clamp(u.dot(heading), -1.0, 1.0));
  };
  // A pass that rates now goes once the holder faces it; the one it faces best (the quickest to play) is
  // turned towards meanwhile.
  const std::vector<PassOption> open = rate_passes(s, robot.id, m.params);
  const PassOption* best = nullptr;
  for (const PassOption& option : open) {
    if (!best || off_heading(option.point) < off_heading(best->point)) best = &option;
  }
  if (best && off_heading(best->point) <= m.params.hold_pass_turn) {
    start_pass(s, m, robot.id, *best, out);
    return;
  }
  // Nothing open: turn towards the teammate nearest to being open (the pass rated with every safety margin
  // relaxed), or else the robot's back to the nearest opponent, shielding the ball.
  Vec2 face = heading;
  if (best) {
    face = best->point - s.ball;
  } else {
    TeamPlayParams relaxed = m.params;
    relaxed.min_margin = -1e9;
    relaxed.min_open_angle = 0;
    relaxed.min_lane_clearance = -1e9;
    const std::vector<PassOption> near_open = rate_passes(s, robot.id, relaxed);
    if (!near_open.empty()) {
      const auto safest = std::max_element(near_open.begin(), near_open.end(), [](const PassOption& a, const PassOption& b) {
        return a.margin < b.margin;
      });
      face = safest->point - s.ball;
    } else if (const wm::RobotState* nearest = opponent_at_ball(s)) {
      face = s.ball - nearest->position;
    }
  }
  const MotionIntent intent = turn_with_ball(s, robot, {.orientation = geom::angle_of(face).radians()});
  write_intent(s, out, robot.id, as_role(intent, Role::kAttacker, "hold"));
}

namespace {

/// Whether a field player of ours other than `attacker` stands within a pass's length of the ball.
bool teammate_in_passing_range(const Situation& s, std::uint32_t attacker, const TeamPlayParams& params) {
  return std::any_of(s.robots.begin(), s.robots.end(), [&](const wm::RobotState& mate) {
    const double length = (mate.position - s.ball).norm();
    return mate.id != attacker && (!s.keeper || mate.id != *s.keeper) && length >= params.min_pass &&
           length <= params.max_pass;
  });
}

}  // namespace

void attack(const Situation& s, TeamPlayMemory& m, std::uint32_t attacker, TeamIntents& out) {
  const wm::RobotState* robot = find_robot(s, attacker);
  if (!robot) return;
  const TeamPlayParams& params = m.params;
  const bool opponent_at_it = std::any_of(s.enemies.begin(), s.enemies.end(), [&](const wm::RobotState& enemy) {
    return (enemy.position - s.ball).norm() < params.contested_distance;
  });
  const bool coming_forward = (s.ball - robot->position).x() > 0;
  if (mode_of(m.style) != TeamMode::kAttacking && opponent_at_it && coming_forward) {
    write_intent(s, out, attacker, as_role(challenge(s, *robot, {}), m.role_of[attacker].value_or(Role::kPresser),
                                           "challenge"));
    return;
  }
  if (mode_of(m.style) == TeamMode::kDefending) {
    write_intent(s, out, attacker, as_role(shoot(s, *robot, {}), Role::kPresser, "press"));
    return;
  }
  const double quality = shot_quality(s, s.ball, attacker);
  if (m.style == Style::kClearance && quality < params.shoot_quality) {
    write_intent(s, out, attacker, as_role(clear_ball(s, *robot, {}), Role::kAttacker, "clear"));
    return;
  }
  const bool at_ball = (robot->position - s.ball).norm() < 0.5;
  // A shot that would give the ball away (below hold_below) is not taken while a teammate is there to pass
  // to: the attacker keeps the ball. Building up it keeps it at once (turning towards the pass, no going
  // round the ball); otherwise only when no pass rates better now.
  bool keep = at_ball && quality < params.hold_below && s.possession != wm::Possession::kEnemy &&
              !ball_near_their_area(s) && teammate_in_passing_range(s, attacker, params);
  if (keep) {
    if (!m.keeping || m.keeping->first != attacker) m.keeping = std::pair(attacker, s.now);
    keep = s.now - m.keeping->second <= params.max_hold;
  } else {
    m.keeping.reset();
  }
  const bool building_up = m.style == Style::kBuildUpAttack || m.style == Style::kHoldPossession;
  if (keep && building_up) {
    hold_ball(s, m, *robot, out);
    return;
  }
  if (at_ball && quality < params.shoot_quality && s.possession != wm::Possession::kEnemy) {
    std::vector<PassOption> options = rate_passes(s, attacker, params);
    // Turning round the ball takes the time opponents need to close the line: passes the way the attacker
    // already comes at the ball are worth more.
    const Vec2 coming = geom::normalized_or(s.ball - robot->position, Vec2(1, 0));
    for (PassOption& option : options) {
      const Vec2 u = geom::normalized_or(option.point - s.ball, coming);
      option.score -= params.turn_cost * std::acos(std::clamp(u.dot(coming), -1.0, 1.0)) / M_PI;
    }
    std::sort(options.begin(), options.end(), [](const PassOption& a, const PassOption& b) {
      return a.score != b.score ? a.score > b.score : a.receiver < b.receiver;
    });
    if (!options.empty() && options.front().score > quality + params.pass_advantage) {
      start_pass(s, m, attacker, options.front(), out);
      return;
    }
  }
  if (keep) {
    hold_ball(s, m, *robot, out);
    return;
  }
  const Vec2 aim = geom::normalized_or(shot_target(s, attacker) - s.ball, Vec2(1, 0));
  write_intent(s, out, attacker,
               kick_from_dribbler(s, *robot, aim, as_role(shoot(s, *robot, {}), Role::kAttacker, "attack")));
}

}  // namespace ssl::planner
