#include "services/planner/core/skills.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "libs/geometry/angle.h"
#include "libs/geometry/project.h"
#include "libs/geometry/segment.h"
#include "libs/geometry/vec2.h"

namespace ssl::planner {
namespace {

/// A shot at our goal: the ball rolling towards our goal line at least this fast (m/s) and crossing it
/// within the goal mouth widened by this margin (m) on each side.
constexpr double kShotMinSpeed = 0.5;
constexpr double kShotMouthMargin = 0.1;
/// The rules' dribbling limit (1 m) less a margin: a dribble stops this far from where it started.
constexpr double kMaxDribble = rules::kMaxDribblingDistance - 0.1;
/// m/s: a ball this fast rolling our way is a pass to receive, not a ball to fetch.
constexpr double kIncomingSpeed = 0.5;
/// m: the receiver gives way (cushions) once the ball is this close.
constexpr double kCushionDistance = 0.4;
/// m beside the ball's line a receiver may be and still give way with it (else it first steps onto the line).
constexpr double kCushionOffLine = 0.03;
/// s the marker aims ahead of where its opponent is (the latency it reacts with).
constexpr double kMarkLookahead = 0.05;
/// m inside the post (beyond the ball's width) a shot at a gap beside the post aims.
constexpr double kPostAim = 0.06;
/// A gap of the goal mouth at least this fraction of the widest is as good a target (goal_opening).
constexpr double kSimilarGap = 0.8;
/// m between a robot touching the ball and their defense area (touching it partly inside is a foul).
constexpr double kAreaTouchClearance = 0.02;
/// m: a slow ball this close to the receiving point is fetched by the receiver.
constexpr double kTakeNearPoint = 1.0;
constexpr double kHoldAngle = 0.35;    // rad off the heading the held ball may lie (holds_ball)

double radius(const Situation& s) { return s.config->robot_radius; }

MotionIntent base(const Situation& s, Skill skill) {
  MotionIntent intent;
  intent.active = true;
  intent.max_speed = s.config->limits.max_speed;
  intent.skill = skill_name(skill);
  return intent;
}

const wm::RobotState* find_enemy(const Situation& s, std::uint32_t id) {
  for (const wm::RobotState& enemy : s.enemies) {
    if (enemy.id == id) return &enemy;
  }
  return nullptr;
}

/// `intent` holding the robot where it is, facing the ball (its opponent is not seen).
MotionIntent hold(const Situation& s, const wm::RobotState& robot, MotionIntent intent) {
  intent.target = robot.position;
  intent.orientation = heading_to(robot.position, s.ball);
  return intent;
}

/// m/s a robot closes on the ball it is about to touch (faster and it knocks the ball away).
constexpr double kTouchClosingSpeed = 1.0;
/// m/s: a ball rolling away along the approach this fast is followed (moving with it), not waited for.
constexpr double kFollowAwaySpeed = 0.2;
/// m from either defense area within which a rolling ball is not followed (follow_ball).
constexpr double kFollowAreaClearance = 0.4;
/// m/s a robot closes on a ball lying within kAreaEdgeClearance (m) of a defense area: closing at
/// kTouchClosingSpeed it stops 2-3 cm beyond its target, partly inside their area while it touches the ball
/// (a foul, seen in the match series on a ball lying 1 cm in front of their area).
constexpr double kAreaEdgeClosingSpeed = 0.5;
constexpr double kAreaEdgeClearance = 0.15;
/// m a ball on our goal line beside a post is pulled out by the robot clearing it (clear_ball).
constexpr double kPullOffGoalLine = 0.4;
/// m from the dribbler within which that ball is touched and the pull starts.
constexpr double kPullContact = 0.015;
/// m/s of that pull: reversing at the dribble's 1 m/s the robot lost the ball after 5-10 cm (realistic).
constexpr double kPullSpeed = 0.4;
/// m before the first field line on its way that a cleared ball or a long ball comes to rest (the straight
/// ball model's error and a bounce off a robot stay inside).
constexpr double kStopInsideField = 1.0;
/// m of field a clearing direction leaves before a line at the least; fewer only when no direction has it.
constexpr double kClearMinRoom = 3.0;
/// Room (rad to the nearest opponent) a clear gives up per radian it turns from the robot's heading: with
/// the opponents moving, the roomiest direction flipped between ticks and a keeper circled a lying ball in
/// its own defense area for 2-3 s (KEEPER_HELD_BALL about once a match per team, 11 v 11). The heading, not
/// the way the robot comes at the ball: getting behind the ball turns the robot to the chosen direction, so
/// the choice holds, while the robot's bearing to the ball drifts as it goes round.
constexpr double kClearTurnCost = 0.3;
/// rad either side of straight upfield a clear may go; kClearWideFan where no direction within kClearFan
/// has its kicking spot on the field (a ball on our goal line, the keeper inside the goal mouth: along the
/// line, away from the goal, at once, rather than round to the field side for a pull, which took the keeper
/// past the 5 s it may keep the ball in its area); every kClearStep.
constexpr double kClearFan = 0.8;
constexpr double kClearWideFan = 1.5;
constexpr double kClearStep = 0.1;
/// m a robot kicking a clear keeps from our goal's walls (a post beside the ball).
constexpr double kClearWallClearance = 0.005;

/// Whether the ball lies within `clearance` (m) of either defense area.
bool ball_near_a_defense_area(const Situation& s, double clearance) {
  return s.field.in_their_defense_area(s.ball, clearance) || s.field.in_our_defense_area(s.ball, clearance);
}

/// A ball rolling away along `u` (the approach) is moved with: the robot arrives at its target at the
/// ball's velocity instead of stopping short of a ball that has rolled on. Not near a defense area: moving
/// with the ball is steering past the path search, which keeps the robot out of them.
void follow_ball(const Situation& s, const Vec2& u, MotionIntent& intent) {
  const double away = s.ball_known ? s.ball_velocity.dot(u) : 0.0;
  if (away > kFollowAwaySpeed && !ball_near_a_defense_area(s, kFollowAreaClearance)) {
    intent.target_velocity = s.ball_velocity;
  }
}

/// Whether `robot` is our restart's kicker (Situation::restart_kicker).
bool is_restart_kicker(const Situation& s, const wm::RobotState& robot) {
  return s.restart_kicker && *s.restart_kicker == robot.id;
}

/// The last part of the approach along `u` to a ball: closing at kTouchClosingSpeed (kAreaEdgeClosingSpeed
/// on a defense area's edge) on top of the speed the ball rolls away along `u` at, moving with a ball that
/// rolls away (a cap of its own would leave the robot trailing a rolling ball, never touching it). Not the
/// kicker of our restart, which may not touch the ball again: a ball it set rolling (a push instead of its
/// kick) it lets go, slower than the ball.
void close_on_ball(const Situation& s, const wm::RobotState& robot, const Vec2& u, MotionIntent& intent) {
  const double away = s.ball_known ? std::max(0.0, s.ball_velocity.dot(u)) : 0.0;
  if (is_restart_kicker(s, robot)) {
    intent.max_speed = std::min(intent.max_speed, away > kFollowAwaySpeed ? away / 2 : kTouchClosingSpeed);
    return;
  }
  const double closing =
      ball_near_a_defense_area(s, kAreaEdgeClearance) ? kAreaEdgeClosingSpeed : kTouchClosingSpeed;
  intent.max_speed = std::min(intent.max_speed, closing + away);
  follow_ball(s, u, intent);
}

/// Drive through the ball along `u` with the kicker armed at `speed`.
void kick_through(const Situation& s, const wm::RobotState& robot, const Vec2& u, double speed, MotionIntent& intent) {
  intent.target = s.ball + u * 0.2;
  intent.orientation = geom::angle_of(u).radians();
  close_on_ball(s, robot, u, intent);
  intent.kick = KickType::kFlat;
  intent.kick_speed = std::min(speed, rules::kMaxBallSpeed - 0.3);
}

/// m beyond the dribbler distance behind the ball where approach_ball stages a robot not yet behind it.
constexpr double kStagingBehind = 0.2;

/// m short of the ball's contact point where an approach ends before the kicker is armed.
constexpr double kApproachGap = 0.01;
/// Get behind the ball on the line along `u`: align when already close behind it, else go around it.
/// Aligned, the target leaves `gap` (m) between dribbler and ball: negative goes into the ball, to take it.
void approach_ball(const Situation& s, const wm::RobotState& robot, const Vec2& u, MotionIntent& intent,
                   double gap = kApproachGap) {
  const Vec2 rel = robot.position - s.ball;
  const double dd = dribbler_distance(s);
  intent.orientation = geom::angle_of(u).radians();
  intent.contests_ball = true;
  if (rel.dot(u) < -0.06 && std::abs(geom::cross(u, rel)) < 0.08) {
    intent.target = s.ball - u * (dd + gap);
    close_on_ball(s, robot, u, intent);
  } else {
    intent.target = s.ball - u * (dd + kStagingBehind);
    intent.avoid_ball_radius = dd + 0.1;
  }
}

/// m short of the ball's contact point where a restart's kicker not yet armed stops: inside the arming
/// window, so it arms as soon as it is in line, and its overshoot (2-3 cm with a lagging robot) never pushes
/// the ball unarmed. A push sets the ball in play, and the kick after it is a double touch. In open play a
/// push costs nothing, and stopping short would delay every kick.
constexpr double kRestartUnarmedGap = 0.04;
/// Kick along `u` at `speed` once behind the ball facing that way, else get there.
MotionIntent kick_along(const Situation& s, const wm::RobotState& robot, const Vec2& u, double speed, Skill skill) {
  MotionIntent intent = base(s, skill);
  if (behind_ball_facing(s, robot, u, 0.1)) {
    kick_through(s, robot, u, speed, intent);
    // Touched from wholly outside their defense area, the ball may be driven through towards it; the robot
    // stops before it would stand wholly inside (a foul), the kick fires at the touch. Otherwise the zone
    // keeps the robot off the ball: touching it partly inside is a foul.
    const Vec2 contact = s.ball - u * dribbler_distance(s);
    if (!s.field.in_their_defense_area(contact, radius(s) + kAreaTouchClearance)) {
      intent.avoid_their_defense_area = false;
      // The robot stops wholly outside the area (with the touch clearance): a ball coming back off their
      // keeper or the goal touches a robot standing partly inside (a foul). A ball on the area's edge is
      // kicked from the contact point, never driven into.
      const double contact_through = -dribbler_distance(s);
      double through = (intent.target - s.ball).norm();
      while (through > contact_through &&
             s.field.in_their_defense_area(s.ball + u * through, radius(s) + kAreaTouchClearance)) {
        through -= 0.01;
      }
      intent.target = s.ball + u * std::max(through, contact_through);
    }
  } else {
    approach_ball(s, robot, u, intent, is_restart_kicker(s, robot) ? kRestartUnarmedGap : kApproachGap);
  }
  return intent;
}

/// The angular intervals (seen from `from`, rad) that robots other than `shooter` hide.
std::vector<std::pair<double, double>> shadows(const Situation& s, const Vec2& from,
                                               std::optional<std::uint32_t> shooter) {
  std::vector<std::pair<double, double>> out;
  const double reach = radius(s) + s.field.size().ball_radius;
  const auto add = [&](const Vec2& position) {
    const Vec2 d = position - from;
    const double distance = d.norm();
    if (distance <= reach || d.x() <= 0) return;
    const double centre = std::atan2(d.y(), d.x());
    const double half = std::asin(std::min(1.0, reach / distance));
    out.emplace_back(centre - half, centre + half);
  };
  for (const wm::RobotState& robot : s.robots) {
    if (!shooter || robot.id != *shooter) add(robot.position);
  }
  for (const wm::RobotState& enemy : s.enemies) add(enemy.position);
  return out;
}

}  // namespace

std::string_view skill_name(Skill skill) {
  switch (skill) {
    case Skill::kPass: return "pass";
    case Skill::kReceive: return "receive";
    case Skill::kGoToBall: return "go_to_ball";
    case Skill::kGoToPoint: return "go_to_point";
    case Skill::kTurnWithBall: return "turn_with_ball";
    case Skill::kClear: return "clear_ball";
    case Skill::kShoot: return "shoot";
    case Skill::kStop: return "stop";
    case Skill::kOpenSpace: return "open_space";
    case Skill::kManMark: return "man_mark";
    case Skill::kBlock: return "block";
    case Skill::kDefendGoal: return "defend_goal";
    case Skill::kChallenge: return "challenge";
    case Skill::kRedirect: return "redirect";
  }
  return "unknown";
}

Skill skill_of(const SkillCall& call) {
  // SkillCall lists its params in Skill's order.
  static_assert(std::variant_size_v<SkillCall> == static_cast<std::size_t>(Skill::kRedirect) + 1);
  static_assert(std::is_same_v<std::variant_alternative_t<static_cast<std::size_t>(Skill::kRedirect), SkillCall>,
                               RedirectParams>);
  return static_cast<Skill>(call.index());
}

double dribbler_distance(const Situation& s) { return radius(s) + s.field.size().ball_radius; }

double heading_to(const Vec2& from, const Vec2& to) { return geom::angle_of(to - from).radians(); }

bool behind_ball_facing(const Situation& s, const wm::RobotState& robot, const Vec2& u, double max_heading_error) {
  const Vec2 rel = robot.position - s.ball;
  const double along = rel.dot(u);
  const double lateral = std::abs(geom::cross(u, rel));
  const double dd = dribbler_distance(s);
  const Vec2 heading = geom::Angle::from_radians(robot.orientation).to_unit_vector();
  return along < -(dd - 0.03) && along > -(dd + 0.06) && lateral < 0.03 &&
         heading.dot(u) > std::cos(max_heading_error);
}

bool holds_ball(const Situation& s, const wm::RobotState& robot, double reach) {
  const Vec2 to_ball = s.ball - robot.position;
  const Vec2 heading = geom::Angle::from_radians(robot.orientation).to_unit_vector();
  return to_ball.norm() < dribbler_distance(s) + reach &&
         geom::normalized_or(to_ball, heading).dot(heading) > std::cos(kHoldAngle);
}

std::optional<geom::Segment> shot_path(const Situation& s) {
  const Vec2& v = s.ball_velocity;
  const double goal_line = -s.field.half_length();
  // Any direction counts (a ball rolling along the goal line too), as long as it is fast and comes our way.
  if (!s.ball_known || v.norm() < kShotMinSpeed || v.x() > -1e-3 || s.ball.x() <= goal_line) return std::nullopt;
  const double y_at_goal = s.ball.y() + v.y() * (goal_line - s.ball.x()) / v.x();
  if (std::abs(y_at_goal) > s.field.size().goal_width / 2 + kShotMouthMargin) return std::nullopt;
  return geom::Segment{s.ball, Vec2(goal_line, y_at_goal)};
}

GoalOpening goal_opening(const Situation& s, const Vec2& from, std::optional<std::uint32_t> shooter) {
  const Vec2 goal = s.field.their_goal_center();
  if (from.x() >= goal.x()) return {0, goal};
  // The mouth as seen from `from`, less a ball's width at each post.
  const double half = s.field.size().goal_width / 2 - s.field.size().ball_radius * 2;
  const double low = std::atan2(goal.y() - half - from.y(), goal.x() - from.x());
  const double high = std::atan2(goal.y() + half - from.y(), goal.x() - from.x());
  std::vector<std::pair<double, double>> hidden = shadows(s, from, shooter);
  std::sort(hidden.begin(), hidden.end());
  std::vector<std::pair<double, double>> gaps;  // (from, width), rad
  double start = low;
  for (const auto& [begin, end] : hidden) {
    if (end <= start) continue;
    if (begin >= high) break;
    if (std::min(begin, high) > start) gaps.emplace_back(start, std::min(begin, high) - start);
    start = std::max(start, end);
  }
  if (start < high) gaps.emplace_back(start, high - start);
  if (gaps.empty()) return {0, goal};
  const double reach = std::max(goal.x() - from.x(), 1e-6);
  // Against a post the shot goes kPostAim inside it, as far from the robot bounding the gap as it can: the
  // keeper has the longest way. A gap between two robots (or the whole mouth) is shot through its middle.
  const auto aim_of = [&](const std::pair<double, double>& gap) {
    const auto [gap_from, width] = gap;
    const double post_margin = std::min(std::atan(kPostAim / reach), width / 2);
    const bool at_low_post = gap_from <= low + 1e-12;
    const bool at_high_post = gap_from + width >= high - 1e-12;
    if (at_low_post && !at_high_post) return gap_from + post_margin;
    if (at_high_post && !at_low_post) return gap_from + width - post_margin;
    return gap_from + width / 2;
  };
  const auto widest = std::max_element(gaps.begin(), gaps.end(),
                                       [](const auto& a, const auto& b) { return a.second < b.second; });
  double aim = aim_of(*widest);
  // Of gaps about as wide (a keeper in the middle of the mouth leaves two), the shooter keeps to the one it
  // faces: picking by a hair's width, its aim flipped between the posts with the keeper's jitter and the
  // robot never faced either.
  if (const wm::RobotState* robot = shooter ? find_robot(s, *shooter) : nullptr) {
    double best_turn = std::abs(geom::Angle::from_radians(aim - robot->orientation).radians());
    for (const auto& gap : gaps) {
      if (gap.second < kSimilarGap * widest->second) continue;
      const double turn = std::abs(geom::Angle::from_radians(aim_of(gap) - robot->orientation).radians());
      if (turn < best_turn) {
        best_turn = turn;
        aim = aim_of(gap);
      }
    }
  }
  return {widest->second, {goal.x(), from.y() + std::tan(aim) * (goal.x() - from.x())}};
}

Vec2 shot_target(const Situation& s, std::optional<std::uint32_t> shooter) {
  return goal_opening(s, s.ball, shooter).target;
}

MotionIntent pass(const Situation& s, const wm::RobotState& robot, const PassParams& p) {
  const Vec2 to = p.receiver - s.ball;
  const double distance = to.norm();
  // Rolling at v0 (after the slide) it slows to v over d when v0^2 = v^2 + 2 a d.
  const double rolling = std::sqrt(p.arrival_speed * p.arrival_speed + 2 * p.ball_deceleration * distance);
  const double speed = rolling / p.rolling_fraction;
  return kick_along(s, robot, geom::normalized_or(to, Vec2(1, 0)), speed, Skill::kPass);
}

MotionIntent receive(const Situation& s, const wm::RobotState& robot, const ReceiveParams& p) {
  const double dd = dribbler_distance(s);
  const double speed = s.ball_velocity.norm();
  const Vec2 v = geom::normalized_or(s.ball_velocity, Vec2(1, 0));
  const bool incoming = s.ball_known && speed > kIncomingSpeed && (p.point - s.ball).dot(v) > 0;
  if (!incoming) {
    // A slow ball near the point (or one that ran past it) is ours to take, gently but catching up with it;
    // otherwise wait at the point, facing the ball.
    if (s.ball_known && (s.ball - p.point).norm() < kTakeNearPoint) {
      MotionIntent intent = go_to_ball(s, robot, {.final_speed = 0.5 + speed});
      intent.skill = skill_name(Skill::kReceive);
      return intent;
    }
    MotionIntent intent = base(s, Skill::kReceive);
    intent.dribble = true;
    intent.target = p.point;
    intent.orientation = heading_to(p.point, s.ball);
    return intent;
  }
  // Where the ball's line passes the expected point: the dribbler on the line there, facing the ball.
  MotionIntent intent = base(s, Skill::kReceive);
  intent.dribble = true;
  const Vec2 contact = s.ball + v * std::max(0.0, (p.point - s.ball).dot(v));
  intent.orientation = geom::angle_of(Vec2(-v)).radians();
  intent.target = contact + v * dd;
  if ((robot.position - s.ball).norm() < kCushionDistance + dd) {
    // The ball is near: onto its line where the robot stands across it, at full speed while beside it; once
    // on it, give way with the ball, so that the dribbler meets it at a lower relative speed and holds it.
    const Vec2 across = s.ball + v * (robot.position - s.ball).dot(v);
    intent.target = across;
    if ((robot.position - across).norm() < kCushionOffLine) {
      intent.target = across + v * (p.cushion * speed * 0.5);
      intent.max_speed = std::min(intent.max_speed, p.cushion * speed);
    }
  }
  return intent;
}

MotionIntent go_to_ball(const Situation& s, const wm::RobotState& robot, const GoToBallParams& p) {
  MotionIntent intent = base(s, Skill::kGoToBall);
  const Vec2 u = geom::normalized_or(s.ball - robot.position, Vec2(1, 0));
  const double dd = dribbler_distance(s);
  intent.orientation = geom::angle_of(u).radians();
  intent.dribble = true;
  intent.target = s.ball - u * (dd - 0.01);
  if ((robot.position - s.ball).norm() < dd + 0.3) intent.max_speed = std::min(intent.max_speed, p.final_speed);
  follow_ball(s, u, intent);
  return intent;
}

MotionIntent go_to_point(const Situation& s, const wm::RobotState& robot, const GoToPointParams& p) {
  MotionIntent intent = base(s, Skill::kGoToPoint);
  intent.max_speed = std::min(intent.max_speed, p.max_speed);
  intent.target = p.point;
  if (!p.with_ball) {
    intent.orientation = p.orientation ? *p.orientation : heading_to(p.point, s.ball);
    return intent;
  }
  intent.dribble = true;
  intent.orientation = p.orientation ? *p.orientation : robot.orientation;
  intent.max_speed = std::min(intent.max_speed, 1.0);  // faster and the ball rolls off the dribbler
  if (p.dribble_start) {
    // The ball (dribbler_distance ahead of the centre) may go at most kMaxDribble from the start.
    const Vec2 ahead = geom::Angle::from_radians(intent.orientation).to_unit_vector() * dribbler_distance(s);
    const Vec2 ball_at = p.point + ahead;
    const Vec2 from_start = ball_at - *p.dribble_start;
    if (from_start.norm() > kMaxDribble) intent.target = *p.dribble_start + from_start.normalized() * kMaxDribble - ahead;
  }
  return intent;
}

MotionIntent turn_with_ball(const Situation& s, const wm::RobotState& robot, const TurnWithBallParams& p) {
  MotionIntent intent = base(s, Skill::kTurnWithBall);
  intent.target = robot.position;
  intent.orientation = p.orientation;
  intent.dribble = true;
  intent.max_speed = std::min(intent.max_speed, 0.3);
  intent.max_angular_speed = p.max_angular_speed;
  return intent;
}

double kick_speed_to_rest_after(double distance) {
  // Sliding from v to k v at acc_slide, then rolling to rest at acc_roll:
  //   distance = v^2 (1 - k^2) / (2 |acc_slide|) + k^2 v^2 / (2 |acc_roll|).
  const wm::BallModel model;
  const double k2 = model.k_switch * model.k_switch;
  const double per_v2 = (1 - k2) / (2 * std::abs(model.acc_slide)) + k2 / (2 * std::abs(model.acc_roll));
  return std::sqrt(std::max(0.0, distance) / per_v2);
}

double kick_speed_kept_in(const Situation& s, const Vec2& u, double speed, double stop_inside) {
  return std::min(speed, kick_speed_to_rest_after(s.field.distance_inside(s.ball, u) - stop_inside));
}

MotionIntent clear_ball(const Situation& s, const wm::RobotState& robot, const ClearParams& p) {
  // Directions from straight upfield to kClearFan either side whose kicking spot behind the ball lies on the
  // field, with the robot kicking there clear of our goal's walls, and that leave kClearMinRoom of field
  // before a line (any, when none does): the one whose nearest opponent (within 3 m of the ball) is
  // angularly furthest away, less kClearTurnCost for each radian it turns from the robot's heading. None
  // within kClearFan (the ball on our goal line): along the line, within kClearWideFan, away from the goal.
  // None there either: straight away from our goal centre. The ball is kicked to come to rest inside.
  Vec2 best = geom::normalized_or(s.ball - s.field.our_goal_center(), Vec2(1, 0));
  const Vec2 heading = geom::Angle::from_radians(robot.orientation).to_unit_vector();
  double best_room = -1;
  double best_score = -1e9;
  const double dd = dribbler_distance(s);
  const double behind = dd + kStagingBehind;  // where approach_ball takes the robot
  for (const double fan : {kClearFan, kClearWideFan}) {
    for (const double min_room : {kClearMinRoom, 0.0}) {
      const int steps = static_cast<int>(std::lround(fan / kClearStep));
      for (int i = -steps; i <= steps; ++i) {
        const double angle = i * kClearStep;
        const Vec2 u(std::cos(angle), std::sin(angle));
        if (std::abs(angle) > kClearFan + 1e-9 && u.y() * s.ball.y() < 0) continue;  // across our goal mouth
        if (!s.field.in_field(s.ball - u * behind, s.zones.field_margin)) continue;
        if (s.field.distance_to_our_goal_walls(s.ball - u * dd) < radius(s) + kClearWallClearance) continue;
        if (s.field.distance_inside(s.ball, u) < min_room) continue;
        double room = M_PI;
        for (const wm::RobotState& enemy : s.enemies) {
          const Vec2 d = enemy.position - s.ball;
          if (d.norm() > 3.0 || d.norm() < 1e-6) continue;
          room = std::min(room, std::acos(std::clamp(d.normalized().dot(u), -1.0, 1.0)));
        }
        const double score = room - kClearTurnCost * std::acos(std::clamp(heading.dot(u), -1.0, 1.0));
        if (score > best_score + 1e-6) {
          best_score = score;
          best_room = room;
          best = u;
        }
      }
      if (best_room >= 0) break;
    }
    if (best_room >= 0) break;
  }
  if (best_room < 0 && std::abs(s.ball.y()) > s.field.size().goal_width / 2) {
    // On our goal line just beyond a post: no kicking spot behind the ball on the field, and along the line
    // the post stands in the way (a keeper tried for minutes; coming along the line it stuck on the post 4 cm
    // short of the ball, which holds_ball counts as held). Taken on the dribbler facing the goal line, from
    // the field side, and pulled out, then cleared from there. The pull starts at the touch: from
    // holds_ball's 4 cm the robot, 75 ms from camera to wheels, reversed before its dribbler had the ball.
    const Vec2 facing_goal_line(-1, 0);
    if (holds_ball(s, robot, kPullContact) && heading.dot(facing_goal_line) > std::cos(kHoldAngle)) {
      MotionIntent intent = go_to_point(s, robot, {.point = robot.position + Vec2(kPullOffGoalLine, 0),
                                                   .orientation = robot.orientation,
                                                   .with_ball = true,
                                                   .max_speed = kPullSpeed});
      intent.skill = skill_name(Skill::kClear);
      return intent;
    }
    MotionIntent intent = base(s, Skill::kClear);
    approach_ball(s, robot, facing_goal_line, intent, -0.01);
    intent.dribble = true;
    return intent;
  }
  return kick_along(s, robot, best, kick_speed_kept_in(s, best, p.speed, kStopInsideField), Skill::kClear);
}

MotionIntent shoot(const Situation& s, const wm::RobotState& robot, const ShootParams& p) {
  const Vec2 u = geom::normalized_or(shot_target(s, robot.id) - s.ball, Vec2(1, 0));
  if ((s.field.their_goal_center() - s.ball).norm() > p.max_distance) {
    MotionIntent intent = base(s, Skill::kShoot);
    approach_ball(s, robot, u, intent);
    return intent;
  }
  double speed = p.speed.value_or(s.config->kick_speed);
  if ((s.field.their_goal_center() - s.ball).norm() > kShotRange) {
    speed = kick_speed_kept_in(s, u, speed, kStopInsideField);
  }
  return kick_along(s, robot, u, speed, Skill::kShoot);
}

MotionIntent stop(const Situation& s, const wm::RobotState& /*robot*/, const StopParams& /*p*/) {
  MotionIntent intent = base(s, Skill::kStop);
  intent.halt = true;
  return intent;
}

MotionIntent open_space(const Situation& s, const wm::RobotState& /*robot*/, const OpenSpaceParams& p) {
  MotionIntent intent = base(s, Skill::kOpenSpace);
  intent.keep_off_ball = true;
  // A 7 x 7 grid over the square around the anchor, inside its circle and the field, off the defense areas.
  Vec2 best = p.anchor;
  double best_score = -1e9;
  for (int i = -3; i <= 3; ++i) {
    for (int j = -3; j <= 3; ++j) {
      const Vec2 candidate = p.anchor + Vec2(i, j) * (p.radius / 3);
      if ((candidate - p.anchor).norm() > p.radius + 1e-9) continue;
      if (!s.field.in_field(candidate) || s.field.in_our_defense_area(candidate, radius(s) + 0.1) ||
          s.field.in_their_defense_area(candidate, radius(s) + 0.3)) {
        continue;
      }
      double room = 1.5;  // m: more than this from every opponent counts the same
      double lane = 1.0;  // m: the pass lane from the ball is open this wide
      const geom::Segment line{s.ball, candidate};
      for (const wm::RobotState& enemy : s.enemies) {
        room = std::min(room, (enemy.position - candidate).norm());
        lane = std::min(lane, (geom::project(enemy.position, line).point - enemy.position).norm());
      }
      const double score = room + 0.5 * lane - 0.3 * (candidate - p.anchor).norm();
      if (score > best_score) {
        best_score = score;
        best = candidate;
      }
    }
  }
  intent.target = best;
  intent.orientation = heading_to(best, s.ball);
  return intent;
}

MotionIntent man_mark(const Situation& s, const wm::RobotState& robot, const ManMarkParams& p) {
  MotionIntent intent = base(s, Skill::kManMark);
  const wm::RobotState* opponent = find_enemy(s, p.opponent);
  if (!opponent) return hold(s, robot, intent);
  // On its line to our goal centre, where it will be kMarkLookahead from now, moving with it.
  const Vec2 predicted = opponent->position + opponent->velocity * kMarkLookahead;
  const Vec2 to_goal = geom::normalized_or(s.field.our_goal_center() - predicted, Vec2(-1, 0));
  intent.target = predicted + to_goal * p.distance;
  intent.target_velocity = opponent->velocity;
  intent.orientation = heading_to(intent.target, s.ball);
  return intent;
}

MotionIntent block(const Situation& s, const wm::RobotState& robot, const BlockParams& p) {
  MotionIntent intent = base(s, Skill::kBlock);
  const wm::RobotState* opponent = find_enemy(s, p.opponent);
  if (!opponent) return hold(s, robot, intent);
  const Vec2 heading = geom::Angle::from_radians(opponent->orientation).to_unit_vector();
  const Vec2 to_goal = geom::normalized_or(s.field.our_goal_center() - opponent->position, Vec2(-1, 0));
  const bool faces_goal = heading.dot(to_goal) > std::cos(p.facing_limit);
  // Phase 1: in its mouth (where a kick would go). Phase 2: on its line of sight to our goal.
  const Vec2 direction = faces_goal ? heading : to_goal;
  intent.target = opponent->position + direction * p.distance;
  intent.orientation = heading_to(intent.target, opponent->position);
  intent.avoid_ball_radius = 0;
  intent.contests_ball = true;
  return intent;
}

MotionIntent defend_goal(const Situation& s, const wm::RobotState& robot, const DefendGoalParams& p) {
  MotionIntent intent = base(s, Skill::kDefendGoal);
  intent.avoid_our_defense_area = false;
  intent.contests_ball = true;
  const double goal_line = -s.field.half_length();
  const double max_y = s.field.size().goal_width / 2 - radius(s) - 0.01;  // clear of the posts
  // The bisector of the angle the two posts make at the ball: a keeper on it covers both sides equally.
  const auto [left_post, right_post] = s.field.our_goal_posts();
  const Vec2 bisector = geom::normalized_or(Vec2(geom::normalized_or(left_post - s.ball, Vec2(-1, 0)) +
                                                 geom::normalized_or(right_post - s.ball, Vec2(-1, 0))),
                                            Vec2(-1, 0));
  const std::optional<geom::Segment> shot = shot_path(s);
  if (p.touch_line) {
    // On the line x, where the bisector (or a shot) crosses it.
    const double x = goal_line + radius(s) * 0.6;
    const auto y_at = [x](const Vec2& from, const Vec2& d) { return from.y() + d.y() * (x - from.x()) / d.x(); };
    double y = s.ball.y();
    if (s.ball.x() > x + 1e-6 && bisector.x() < -1e-6) y = y_at(s.ball, bisector);
    if (shot && shot->start.x() > x) y = y_at(shot->start, shot->direction());
    intent.target = {x, std::clamp(y, -max_y, max_y)};
    intent.orientation = heading_to(intent.target, s.ball);
    return intent;
  }
  // On the bisector, `guard` out from where it crosses the goal line: in front of the mouth for a ball ahead,
  // near the line for a ball from a wide angle (one rolling along the line meets the keeper, not the gap
  // behind it).
  constexpr double kGuardMargin = 0.05;  // m beyond the robot's radius
  const double guard = radius(s) + kGuardMargin;
  intent.target = {goal_line + guard, std::clamp(s.ball.y(), -max_y, max_y)};
  if (s.ball.x() > goal_line + 0.01 && bisector.x() < -1e-6) {
    const Vec2 crossing = s.ball + bisector * ((goal_line - s.ball.x()) / bisector.x());
    const Vec2 out = crossing - bisector * guard;
    intent.target = {std::max(out.x(), goal_line + 0.02), std::clamp(out.y(), -max_y, max_y)};
  }
  // A shot: meet it on its path, at the point nearest to where the keeper is.
  if (shot) {
    const Vec2 meet = geom::project(robot.position, *shot).point;
    intent.target = {std::max(meet.x(), goal_line + 0.02), std::clamp(meet.y(), -max_y - 0.05, max_y + 0.05)};
  }
  intent.orientation = heading_to(intent.target, s.ball);
  return intent;
}

MotionIntent challenge(const Situation& s, const wm::RobotState& robot, const ChallengeParams& p) {
  MotionIntent intent = base(s, Skill::kChallenge);
  const Vec2 coming = geom::normalized_or(s.ball - robot.position, Vec2(1, 0));
  const Vec2 to_goal = geom::normalized_or(s.field.their_goal_center() - s.ball, Vec2(1, 0));
  // The way we come at it, turned towards their goal by at most max_turn.
  const double turn = std::clamp(std::atan2(geom::cross(coming, to_goal), coming.dot(to_goal)), -p.max_turn, p.max_turn);
  const Vec2 u = geom::Angle::from_radians(geom::angle_of(coming).radians() + turn).to_unit_vector();
  intent.orientation = geom::angle_of(u).radians();
  intent.target = s.ball + u * 0.1;  // through the ball: the armed kicker fires on contact
  intent.kick = KickType::kFlat;
  intent.kick_speed = std::min(p.speed, rules::kMaxBallSpeed - 0.3);
  intent.dribble = false;
  return intent;
}

MotionIntent redirect(const Situation& s, const wm::RobotState&, const RedirectParams& p) {
  MotionIntent intent = base(s, Skill::kRedirect);
  // The way the ball comes: along its run once it rolls towards the point, else from where it lies.
  const double speed = s.ball_velocity.norm();
  const Vec2 run = geom::normalized_or(s.ball_velocity, Vec2(1, 0));
  const bool incoming = s.ball_known && speed > kIncomingSpeed && (p.point - s.ball).dot(run) > 0;
  const Vec2 coming = incoming ? run : geom::normalized_or(p.point - s.ball, Vec2(1, 0));
  // Met where its line passes the point (the line it runs on now, not the one it was meant to).
  const Vec2 contact = incoming ? Vec2(s.ball + run * (p.point - s.ball).dot(run)) : p.point;
  const Vec2 back = -coming;
  const Vec2 out = geom::normalized_or(p.aim - contact, Vec2(1, 0));
  const double turn = std::atan2(geom::cross(back, out), back.dot(out));
  const double heading = geom::angle_of(back).radians() + std::clamp(turn, -p.max_angle, p.max_angle);
  const Vec2 h = geom::Angle::from_radians(heading).to_unit_vector();
  intent.target = contact - h * dribbler_distance(s);
  intent.orientation = heading;
  intent.kick = KickType::kFlat;
  intent.kick_speed = std::min(p.speed, rules::kMaxBallSpeed - 0.3);
  intent.dribble = false;
  return intent;
}

MotionIntent run_skill(const Situation& s, const wm::RobotState& robot, const SkillCall& call) {
  return std::visit(
      [&](const auto& p) -> MotionIntent {
        using P = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<P, PassParams>) return pass(s, robot, p);
        if constexpr (std::is_same_v<P, ReceiveParams>) return receive(s, robot, p);
        if constexpr (std::is_same_v<P, GoToBallParams>) return go_to_ball(s, robot, p);
        if constexpr (std::is_same_v<P, GoToPointParams>) return go_to_point(s, robot, p);
        if constexpr (std::is_same_v<P, TurnWithBallParams>) return turn_with_ball(s, robot, p);
        if constexpr (std::is_same_v<P, ClearParams>) return clear_ball(s, robot, p);
        if constexpr (std::is_same_v<P, ShootParams>) return shoot(s, robot, p);
        if constexpr (std::is_same_v<P, StopParams>) return stop(s, robot, p);
        if constexpr (std::is_same_v<P, OpenSpaceParams>) return open_space(s, robot, p);
        if constexpr (std::is_same_v<P, ManMarkParams>) return man_mark(s, robot, p);
        if constexpr (std::is_same_v<P, BlockParams>) return block(s, robot, p);
        if constexpr (std::is_same_v<P, DefendGoalParams>) return defend_goal(s, robot, p);
        if constexpr (std::is_same_v<P, ChallengeParams>) return challenge(s, robot, p);
        if constexpr (std::is_same_v<P, RedirectParams>) return redirect(s, robot, p);
      },
      call);
}

}  // namespace ssl::planner
