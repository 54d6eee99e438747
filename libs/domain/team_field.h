// Field: the playing field's dimensions (FieldGeometry, field.h) and its named points and areas in the TEAM
// frame (our goal at negative x, see team_frame.h), for the world model and for the planner. Metres. The field is symmetric
// under the team flip, so these depend only on the dimensions (from vision.geometry).
//
//   Field field(geometry.field);
//   Vec2 aim = field.their_goal_center();            // (+L/2, 0)
//   bool keeper_zone = field.in_our_defense_area(ball);
#pragma once

#include <array>
#include <algorithm>
#include <cmath>
#include <limits>

#include "libs/domain/world.h"

namespace ssl::wm {

class Field {
 public:
  explicit Field(const FieldSize& size = {}) : size_(size) {}

  const FieldSize& size() const { return size_; }
  double length() const { return size_.field_length; }
  double width() const { return size_.field_width; }
  double half_length() const { return size_.field_length / 2; }
  double half_width() const { return size_.field_width / 2; }

  Vec2 center() const { return Vec2::Zero(); }
  Vec2 our_goal_center() const { return {-half_length(), 0}; }
  Vec2 their_goal_center() const { return {half_length(), 0}; }
  /// Goal posts (inner edge), +y first.
  std::array<Vec2, 2> our_goal_posts() const {
    return {Vec2(-half_length(), size_.goal_width / 2), Vec2(-half_length(), -size_.goal_width / 2)};
  }
  std::array<Vec2, 2> their_goal_posts() const {
    return {Vec2(half_length(), size_.goal_width / 2), Vec2(half_length(), -size_.goal_width / 2)};
  }
  /// The mark the ball is placed on for a penalty on THEIR goal (we shoot), and on ours.
  Vec2 their_penalty_mark() const { return {half_length() - size_.goal_center_to_penalty_mark, 0}; }
  Vec2 our_penalty_mark() const { return {-half_length() + size_.goal_center_to_penalty_mark, 0}; }

  /// Defense area corners on the field side: +y first, then -y. The other two are on the goal line.
  std::array<Vec2, 2> our_defense_area_front_corners() const {
    const double x = -half_length() + size_.penalty_area_depth;
    return {Vec2(x, size_.penalty_area_width / 2), Vec2(x, -size_.penalty_area_width / 2)};
  }
  std::array<Vec2, 2> their_defense_area_front_corners() const {
    const double x = half_length() - size_.penalty_area_depth;
    return {Vec2(x, size_.penalty_area_width / 2), Vec2(x, -size_.penalty_area_width / 2)};
  }
  /// All four corners, counter-clockwise starting at the goal line's -y corner.
  std::array<Vec2, 4> our_defense_area_corners() const {
    const double x0 = -half_length();
    const double x1 = x0 + size_.penalty_area_depth;
    const double h = size_.penalty_area_width / 2;
    return {Vec2(x0, -h), Vec2(x1, -h), Vec2(x1, h), Vec2(x0, h)};
  }
  std::array<Vec2, 4> their_defense_area_corners() const {
    const double x0 = half_length();
    const double x1 = x0 - size_.penalty_area_depth;
    const double h = size_.penalty_area_width / 2;
    return {Vec2(x0, h), Vec2(x1, h), Vec2(x1, -h), Vec2(x0, -h)};
  }
  /// Field corners: our left (+y), our right, their left, their right.
  Vec2 our_corner_pos() const { return {-half_length(), half_width()}; }
  Vec2 our_corner_neg() const { return {-half_length(), -half_width()}; }
  Vec2 their_corner_pos() const { return {half_length(), half_width()}; }
  Vec2 their_corner_neg() const { return {half_length(), -half_width()}; }

  bool in_field(const Vec2& p, double margin = 0) const {
    return std::abs(p.x()) <= half_length() + margin && std::abs(p.y()) <= half_width() + margin;
  }
  /// Whether a ball centred at `p` is still in the field: it leaves only once wholly beyond a line.
  bool ball_in_field(const Vec2& p) const { return in_field(p, size_.ball_radius); }
  /// m from `from` (inside the field) along the unit direction `u` until a field line is crossed: how far a
  /// ball sent that way stays in. 0 from a point on or outside a line it is moving across.
  double distance_inside(const Vec2& from, const Vec2& u) const {
    double distance = std::numeric_limits<double>::infinity();
    for (int axis = 0; axis < 2; ++axis) {
      const double limit = axis == 0 ? half_length() : half_width();
      if (std::abs(u[axis]) < 1e-12) continue;
      const double edge = u[axis] > 0 ? limit : -limit;
      distance = std::min(distance, std::max(0.0, (edge - from[axis]) / u[axis]));
    }
    return distance;
  }
  bool in_our_half(const Vec2& p) const { return p.x() < 0; }
  bool in_our_defense_area(const Vec2& p, double margin = 0) const {
    return p.x() <= -half_length() + size_.penalty_area_depth + margin && p.x() >= -half_length() - margin &&
           std::abs(p.y()) <= size_.penalty_area_width / 2 + margin;
  }
  bool in_their_defense_area(const Vec2& p, double margin = 0) const {
    return p.x() >= half_length() - size_.penalty_area_depth - margin && p.x() <= half_length() + margin &&
           std::abs(p.y()) <= size_.penalty_area_width / 2 + margin;
  }
  bool in_center_circle(const Vec2& p) const { return p.norm() <= size_.center_circle_radius; }
  /// m from `p` to the nearer side wall of our goal: the wall from its post on the goal line back by the
  /// goal's depth (its thickness is not counted).
  double distance_to_our_goal_walls(const Vec2& p) const {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Vec2& post : our_goal_posts()) {
      const double x = std::clamp(p.x(), post.x() - size_.goal_depth, post.x());
      nearest = std::min(nearest, std::hypot(p.x() - x, p.y() - post.y()));
    }
    return nearest;
  }
  /// Inside either goal: behind its goal line, between its side walls.
  bool in_goal(const Vec2& p) const {
    return std::abs(p.x()) > half_length() && std::abs(p.y()) < size_.goal_width / 2;
  }

 private:
  FieldSize size_;
};

}  // namespace ssl::wm
