// The rules' keep-out zones as libs/geometry shapes, each for a robot's CENTRE: the rules measure from a
// robot's nearest side, so every zone is the rule distance grown by the robot radius. A robot breaks the
// rule when its centre is strictly inside (geom::signed_distance(centre, zone) < 0). Metres; the frame is
// whichever the positions are given in (the referee's vision frame, the planner's team frame).
//
//   geom::Stadium corridor = placement_keep_out(ball, target, field.max_robot_radius);
//   bool interferes = geom::signed_distance(robot, corridor) < 0;
#pragma once

#include "libs/domain/field.h"
#include "libs/domain/rules.h"
#include "libs/geometry/circle.h"
#include "libs/geometry/rectangle.h"
#include "libs/geometry/stadium.h"

namespace ssl {

/// STOP, and the other team's kickoff or free kick: the disc around the ball.
inline geom::Circle ball_keep_out(const geom::Vec2& ball, double robot_radius,
                                  double distance = rules::kStopBallDistance) {
  return {ball, distance + robot_radius};
}

/// The other team during a ball placement: the stadium around the segment ball -> designated position.
inline geom::Stadium placement_keep_out(const geom::Vec2& ball, const geom::Vec2& target, double robot_radius,
                                        double distance = rules::kPlacementKeepOutDistance) {
  return {{ball, target}, distance + robot_radius};
}

/// The defense area of the goal at goal_x_sign (+1 / -1) grown by `margin` towards the field and sideways
/// (square corners: a little more than the rules' rounded ones) and reaching `behind` beyond the goal
/// line, so that a centre inside the goal or behind it counts as inside too.
geom::Rectangle defense_area_keep_out(const FieldGeometry& field, double goal_x_sign, double margin,
                                      double behind);

}  // namespace ssl
