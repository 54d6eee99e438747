// TeamFrame: THE one place where the SSL-Vision global frame becomes the team frame (our goal at
// negative x, angle 0 towards the opponent goal, CCW positive). When we defend the positive half, the
// team frame is the vision frame turned by pi about the field centre: points and vectors are negated and
// pi is added to angles; otherwise it is the identity. Derived from the referee's
// blue_team_on_positive_half and our colour (default when the referee never said: blue on the negative
// half, as the Game Controller starts).
//
//   TeamFrame frame = TeamFrame::make(TeamColor::kYellow, /*blue_on_positive_half=*/false);
//   Vec2 p_team = frame.point(p_vision);   // (x, y) -> (-x, -y): yellow defends +x
#pragma once

#include "libs/common/team.h"
#include "libs/geometry/angle.h"
#include "libs/geometry/vec2.h"

namespace ssl::wm {

class TeamFrame {
 public:
  TeamFrame() = default;

  static TeamFrame make(TeamColor us, bool blue_on_positive_half) {
    TeamFrame frame;
    // We defend the positive half (and must turn the field) when our colour is on the positive half.
    frame.flipped_ = (us == TeamColor::kBlue) == blue_on_positive_half;
    return frame;
  }

  /// The frame a world state was published in (WorldState::flipped), for its consumers.
  static TeamFrame with_flip(bool flipped) {
    TeamFrame frame;
    frame.flipped_ = flipped;
    return frame;
  }

  bool flipped() const { return flipped_; }

  /// Vision -> team (the rotation by pi is its own inverse, so the same functions go back).
  geom::Vec2 point(const geom::Vec2& p) const { return flipped_ ? geom::Vec2(-p) : p; }
  geom::Vec2 vector(const geom::Vec2& v) const { return flipped_ ? geom::Vec2(-v) : v; }
  double angle(double radians) const {
    return geom::Angle::from_radians(flipped_ ? radians + geom::Angle::half_turn().radians() : radians)
        .radians();
  }
  /// Angular velocities and heights do not change under a rotation about the vertical axis.

  /// Team -> vision.
  geom::Vec2 to_vision_point(const geom::Vec2& p) const { return point(p); }
  double to_vision_angle(double radians) const { return angle(radians); }

 private:
  bool flipped_ = false;
};

}  // namespace ssl::wm
