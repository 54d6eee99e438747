#include "services/vision_gateway/adapter/convert.h"

#include <cmath>
#include <initializer_list>
#include <string>

#include "libs/league/decode.h"

namespace ssl::vision_gateway {
namespace {

/// A named number of a wire message, for validation.
struct Named {
  const char* name;
  double value;
};

/// Collects the first validation problem of a packet. Paths ("detection.robots_blue[3].x") are only built
/// when something is wrong, so valid packets cost no string work.
class Checker {
 public:
  /// Records an error when one of `values` is NaN or infinite; `index` < 0 means "not a list element".
  void finite(std::initializer_list<Named> values, const char* where, int index = -1) {
    if (!error_.empty()) return;
    for (const Named& named : values) {
      if (std::isfinite(named.value)) continue;
      error_ = where;
      if (index >= 0) error_ += "[" + std::to_string(index) + "]";
      error_ += std::string(".") + named.name + " is not a finite number";
      return;
    }
  }
  time::Timestamp time(double unix_seconds, const char* path) {
    std::optional<time::Timestamp> t = time::Timestamp::try_from_seconds(unix_seconds);
    if (t) return *t;
    fail(std::string(path) + " is not a representable time in seconds");
    return {};
  }
  void fail(std::string message) {
    if (error_.empty()) error_ = std::move(message);
  }
  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }

 private:
  std::string error_;
};

BallDetection ball_from_proto(const SSL_DetectionBall& in, int index, Checker& check) {
  check.finite({{"x", in.x()},
                {"y", in.y()},
                {"z", in.z()},
                {"confidence", in.confidence()},
                {"pixel_x", in.pixel_x()},
                {"pixel_y", in.pixel_y()}},
               "detection.balls", index);
  BallDetection ball;
  ball.position = {metres_from_mm(in.x()), metres_from_mm(in.y())};
  if (in.has_z()) ball.z = metres_from_mm(in.z());
  ball.confidence = in.confidence();
  if (in.has_area()) ball.area = in.area();
  ball.pixel_x = in.pixel_x();
  ball.pixel_y = in.pixel_y();
  return ball;
}

RobotDetection robot_from_proto(const SSL_DetectionRobot& in, const char* where, int index, Checker& check) {
  check.finite({{"x", in.x()},
                {"y", in.y()},
                {"orientation", in.orientation()},
                {"height", in.height()},
                {"confidence", in.confidence()},
                {"pixel_x", in.pixel_x()},
                {"pixel_y", in.pixel_y()}},
               where, index);
  RobotDetection robot;
  if (in.has_robot_id()) robot.robot_id = in.robot_id();
  robot.position = {metres_from_mm(in.x()), metres_from_mm(in.y())};
  if (in.has_orientation()) robot.orientation = in.orientation();
  if (in.has_height()) robot.height = metres_from_mm(in.height());
  robot.confidence = in.confidence();
  robot.pixel_x = in.pixel_x();
  robot.pixel_y = in.pixel_y();
  return robot;
}

DetectionFrame frame_from_proto(const SSL_DetectionFrame& in, Checker& check) {
  DetectionFrame frame;
  frame.camera_id = in.camera_id();
  frame.frame_number = in.frame_number();
  frame.capture_vision = check.time(in.t_capture(), "detection.t_capture");
  frame.sent_vision = check.time(in.t_sent(), "detection.t_sent");
  if (in.has_t_capture_camera())
    frame.capture_camera = check.time(in.t_capture_camera(), "detection.t_capture_camera");
  frame.balls.reserve(static_cast<std::size_t>(in.balls_size()));
  for (int i = 0; i < in.balls_size(); ++i) frame.balls.push_back(ball_from_proto(in.balls(i), i, check));
  frame.robots_yellow.reserve(static_cast<std::size_t>(in.robots_yellow_size()));
  for (int i = 0; i < in.robots_yellow_size(); ++i) {
    frame.robots_yellow.push_back(robot_from_proto(in.robots_yellow(i), "detection.robots_yellow", i, check));
  }
  frame.robots_blue.reserve(static_cast<std::size_t>(in.robots_blue_size()));
  for (int i = 0; i < in.robots_blue_size(); ++i) {
    frame.robots_blue.push_back(robot_from_proto(in.robots_blue(i), "detection.robots_blue", i, check));
  }
  return frame;
}

Vec2 point_from_proto(const Vector2f& in) { return {metres_from_mm(in.x()), metres_from_mm(in.y())}; }

FieldShapeType shape_from_proto(bool has_type, SSL_FieldShapeType type, const std::string& name) {
  if (has_type) return static_cast<FieldShapeType>(type);
  return shape_type_from_name(name);
}

GeometryInput geometry_from_proto(const SSL_GeometryData& in, Checker& check) {
  GeometryInput geometry;
  const SSL_GeometryFieldSize& f = in.field();
  FieldSizeInput& field = geometry.field;
  field.field_length = metres_from_mm(f.field_length());
  field.field_width = metres_from_mm(f.field_width());
  field.goal_width = metres_from_mm(f.goal_width());
  field.goal_depth = metres_from_mm(f.goal_depth());
  field.boundary_width = metres_from_mm(f.boundary_width());
  if (f.field_length() <= 0) check.fail("geometry.field.field_length must be positive");
  if (f.field_width() <= 0) check.fail("geometry.field.field_width must be positive");
  check.finite({{"ball_radius", f.ball_radius()}, {"max_robot_radius", f.max_robot_radius()}},
               "geometry.field");
  if (f.has_boundary_width_goal_line())
    field.boundary_width_goal_line = metres_from_mm(f.boundary_width_goal_line());
  if (f.has_penalty_area_depth()) field.penalty_area_depth = metres_from_mm(f.penalty_area_depth());
  if (f.has_penalty_area_width()) field.penalty_area_width = metres_from_mm(f.penalty_area_width());
  if (f.has_center_circle_radius()) field.center_circle_radius = metres_from_mm(f.center_circle_radius());
  if (f.has_line_thickness()) field.line_thickness = metres_from_mm(f.line_thickness());
  if (f.has_goal_center_to_penalty_mark()) {
    field.goal_center_to_penalty_mark = metres_from_mm(f.goal_center_to_penalty_mark());
  }
  if (f.has_goal_height()) field.goal_height = metres_from_mm(f.goal_height());
  if (f.has_ball_radius()) field.ball_radius = metres_from_mm(f.ball_radius());
  if (f.has_max_robot_radius()) field.max_robot_radius = metres_from_mm(f.max_robot_radius());
  if (f.has_goal_substitution_area_width()) {
    field.goal_substitution_area_width = metres_from_mm(f.goal_substitution_area_width());
  }
  field.lines.reserve(static_cast<std::size_t>(f.field_lines_size()));
  for (int i = 0; i < f.field_lines_size(); ++i) {
    const SSL_FieldLineSegment& l = f.field_lines(i);
    check.finite({{"p1.x", l.p1().x()},
                  {"p1.y", l.p1().y()},
                  {"p2.x", l.p2().x()},
                  {"p2.y", l.p2().y()},
                  {"thickness", l.thickness()}},
                 "geometry.field.field_lines", i);
    FieldLine line;
    line.name = l.name();
    line.p1 = point_from_proto(l.p1());
    line.p2 = point_from_proto(l.p2());
    line.thickness = metres_from_mm(l.thickness());
    line.type = shape_from_proto(l.has_type(), l.type(), l.name());
    field.lines.push_back(std::move(line));
  }
  field.arcs.reserve(static_cast<std::size_t>(f.field_arcs_size()));
  for (int i = 0; i < f.field_arcs_size(); ++i) {
    const SSL_FieldCircularArc& a = f.field_arcs(i);
    check.finite({{"center.x", a.center().x()},
                  {"center.y", a.center().y()},
                  {"radius", a.radius()},
                  {"a1", a.a1()},
                  {"a2", a.a2()},
                  {"thickness", a.thickness()}},
                 "geometry.field.field_arcs", i);
    FieldArc arc;
    arc.name = a.name();
    arc.center = point_from_proto(a.center());
    arc.radius = metres_from_mm(a.radius());
    arc.a1 = a.a1();
    arc.a2 = a.a2();
    arc.thickness = metres_from_mm(a.thickness());
    arc.type = shape_from_proto(a.has_type(), a.type(), a.name());
    field.arcs.push_back(std::move(arc));
  }
  geometry.calibrations.reserve(static_cast<std::size_t>(in.calib_size()));
  for (int i = 0; i < in.calib_size(); ++i) {
    const SSL_GeometryCameraCalibration& c = in.calib(i);
    check.finite({{"focal_length", c.focal_length()},
                  {"principal_point_x", c.principal_point_x()},
                  {"principal_point_y", c.principal_point_y()},
                  {"distortion", c.distortion()},
                  {"q0", c.q0()},
                  {"q1", c.q1()},
                  {"q2", c.q2()},
                  {"q3", c.q3()},
                  {"tx", c.tx()},
                  {"ty", c.ty()},
                  {"tz", c.tz()},
                  {"derived_camera_world_tx", c.derived_camera_world_tx()},
                  {"derived_camera_world_ty", c.derived_camera_world_ty()},
                  {"derived_camera_world_tz", c.derived_camera_world_tz()}},
                 "geometry.calib", i);
    CameraCalibration calibration;
    calibration.camera_id = c.camera_id();
    calibration.focal_length = c.focal_length();
    calibration.principal_point_x = c.principal_point_x();
    calibration.principal_point_y = c.principal_point_y();
    calibration.distortion = c.distortion();
    calibration.q0 = c.q0();
    calibration.q1 = c.q1();
    calibration.q2 = c.q2();
    calibration.q3 = c.q3();
    calibration.tx = metres_from_mm(c.tx());
    calibration.ty = metres_from_mm(c.ty());
    calibration.tz = metres_from_mm(c.tz());
    if (c.has_derived_camera_world_tx() && c.has_derived_camera_world_ty() &&
        c.has_derived_camera_world_tz()) {
      calibration.derived_world =
          Vec3{metres_from_mm(c.derived_camera_world_tx()), metres_from_mm(c.derived_camera_world_ty()),
               metres_from_mm(c.derived_camera_world_tz())};
    }
    if (c.has_pixel_image_width()) calibration.pixel_image_width = c.pixel_image_width();
    if (c.has_pixel_image_height()) calibration.pixel_image_height = c.pixel_image_height();
    geometry.calibrations.push_back(calibration);
  }
  if (in.has_models()) {
    const SSL_GeometryModels& m = in.models();
    if (m.has_straight_two_phase()) {
      const auto& s = m.straight_two_phase();
      check.finite({{"acc_slide", s.acc_slide()}, {"acc_roll", s.acc_roll()}, {"k_switch", s.k_switch()}},
                   "geometry.models.straight_two_phase");
      geometry.straight_two_phase = BallModelStraightTwoPhase{s.acc_slide(), s.acc_roll(), s.k_switch()};
    }
    if (m.has_chip_fixed_loss()) {
      const auto& c = m.chip_fixed_loss();
      check.finite({{"damping_xy_first_hop", c.damping_xy_first_hop()},
                    {"damping_xy_other_hops", c.damping_xy_other_hops()},
                    {"damping_z", c.damping_z()}},
                   "geometry.models.chip_fixed_loss");
      geometry.chip_fixed_loss =
          BallModelChipFixedLoss{c.damping_xy_first_hop(), c.damping_xy_other_hops(), c.damping_z()};
    }
  }
  return geometry;
}

// ---- core -> wire

float mmf(double metres) { return static_cast<float>(mm_from_metres(metres)); }
std::int32_t mmi(double metres) { return static_cast<std::int32_t>(std::lround(mm_from_metres(metres))); }

void robot_to_proto(const RobotDetection& in, SSL_DetectionRobot& out) {
  out.set_confidence(in.confidence);
  if (in.robot_id) out.set_robot_id(*in.robot_id);
  out.set_x(mmf(in.position.x()));
  out.set_y(mmf(in.position.y()));
  if (in.orientation) out.set_orientation(static_cast<float>(*in.orientation));
  out.set_pixel_x(in.pixel_x);
  out.set_pixel_y(in.pixel_y);
  if (in.height) out.set_height(mmf(*in.height));
}

void frame_to_proto(const DetectionFrame& in, SSL_DetectionFrame& out) {
  out.set_frame_number(in.frame_number);
  out.set_t_capture(in.capture_vision.to_seconds());
  out.set_t_sent(in.sent_vision.to_seconds());
  if (in.capture_camera) out.set_t_capture_camera(in.capture_camera->to_seconds());
  out.set_camera_id(in.camera_id);
  for (const BallDetection& ball : in.balls) {
    SSL_DetectionBall* b = out.add_balls();
    b->set_confidence(ball.confidence);
    if (ball.area) b->set_area(*ball.area);
    b->set_x(mmf(ball.position.x()));
    b->set_y(mmf(ball.position.y()));
    if (ball.z) b->set_z(mmf(*ball.z));
    b->set_pixel_x(ball.pixel_x);
    b->set_pixel_y(ball.pixel_y);
  }
  for (const RobotDetection& robot : in.robots_yellow) robot_to_proto(robot, *out.add_robots_yellow());
  for (const RobotDetection& robot : in.robots_blue) robot_to_proto(robot, *out.add_robots_blue());
}

void point_to_proto(const Vec2& in, Vector2f& out) {
  out.set_x(mmf(in.x()));
  out.set_y(mmf(in.y()));
}

void geometry_to_proto(const GeometryInput& in, SSL_GeometryData& out) {
  const FieldSizeInput& f = in.field;
  SSL_GeometryFieldSize& field = *out.mutable_field();
  field.set_field_length(mmi(f.field_length));
  field.set_field_width(mmi(f.field_width));
  field.set_goal_width(mmi(f.goal_width));
  field.set_goal_depth(mmi(f.goal_depth));
  field.set_boundary_width(mmi(f.boundary_width));
  if (f.boundary_width_goal_line) field.set_boundary_width_goal_line(mmi(*f.boundary_width_goal_line));
  if (f.penalty_area_depth) field.set_penalty_area_depth(mmi(*f.penalty_area_depth));
  if (f.penalty_area_width) field.set_penalty_area_width(mmi(*f.penalty_area_width));
  if (f.center_circle_radius) field.set_center_circle_radius(mmi(*f.center_circle_radius));
  if (f.line_thickness) field.set_line_thickness(mmi(*f.line_thickness));
  if (f.goal_center_to_penalty_mark)
    field.set_goal_center_to_penalty_mark(mmi(*f.goal_center_to_penalty_mark));
  if (f.goal_height) field.set_goal_height(mmi(*f.goal_height));
  if (f.ball_radius) field.set_ball_radius(mmf(*f.ball_radius));
  if (f.max_robot_radius) field.set_max_robot_radius(mmf(*f.max_robot_radius));
  if (f.goal_substitution_area_width)
    field.set_goal_substitution_area_width(mmi(*f.goal_substitution_area_width));
  for (const FieldLine& line : f.lines) {
    SSL_FieldLineSegment* l = field.add_field_lines();
    l->set_name(line.name);
    point_to_proto(line.p1, *l->mutable_p1());
    point_to_proto(line.p2, *l->mutable_p2());
    l->set_thickness(mmf(line.thickness));
    l->set_type(static_cast<SSL_FieldShapeType>(line.type));
  }
  for (const FieldArc& arc : f.arcs) {
    SSL_FieldCircularArc* a = field.add_field_arcs();
    a->set_name(arc.name);
    point_to_proto(arc.center, *a->mutable_center());
    a->set_radius(mmf(arc.radius));
    a->set_a1(static_cast<float>(arc.a1));
    a->set_a2(static_cast<float>(arc.a2));
    a->set_thickness(mmf(arc.thickness));
    a->set_type(static_cast<SSL_FieldShapeType>(arc.type));
  }
  for (const CameraCalibration& c : in.calibrations) {
    SSL_GeometryCameraCalibration* out_c = out.add_calib();
    out_c->set_camera_id(c.camera_id);
    out_c->set_focal_length(static_cast<float>(c.focal_length));
    out_c->set_principal_point_x(static_cast<float>(c.principal_point_x));
    out_c->set_principal_point_y(static_cast<float>(c.principal_point_y));
    out_c->set_distortion(static_cast<float>(c.distortion));
    out_c->set_q0(static_cast<float>(c.q0));
    out_c->set_q1(static_cast<float>(c.q1));
    out_c->set_q2(static_cast<float>(c.q2));
    out_c->set_q3(static_cast<float>(c.q3));
    out_c->set_tx(mmf(c.tx));
    out_c->set_ty(mmf(c.ty));
    out_c->set_tz(mmf(c.tz));
    if (c.derived_world) {
      out_c->set_derived_camera_world_tx(mmf(c.derived_world->x));
      out_c->set_derived_camera_world_ty(mmf(c.derived_world->y));
      out_c->set_derived_camera_world_tz(mmf(c.derived_world->z));
    }
    if (c.pixel_image_width) out_c->set_pixel_image_width(*c.pixel_image_width);
    if (c.pixel_image_height) out_c->set_pixel_image_height(*c.pixel_image_height);
  }
  if (in.straight_two_phase) {
    auto* s = out.mutable_models()->mutable_straight_two_phase();
    s->set_acc_slide(in.straight_two_phase->acc_slide);
    s->set_acc_roll(in.straight_two_phase->acc_roll);
    s->set_k_switch(in.straight_two_phase->k_switch);
  }
  if (in.chip_fixed_loss) {
    auto* c = out.mutable_models()->mutable_chip_fixed_loss();
    c->set_damping_xy_first_hop(in.chip_fixed_loss->damping_xy_first_hop);
    c->set_damping_xy_other_hops(in.chip_fixed_loss->damping_xy_other_hops);
    c->set_damping_z(in.chip_fixed_loss->damping_z);
  }
}

// ---- core -> IDL

idl::vision::VisionSource source_to_idl(VisionSource source) {
  return static_cast<idl::vision::VisionSource>(static_cast<std::uint32_t>(source));
}

idl::vision::FieldShapeType shape_to_idl(FieldShapeType type) {
  return static_cast<idl::vision::FieldShapeType>(static_cast<std::uint32_t>(type));
}

idl::common::Vec2 vec2_to_idl(const Vec2& v) {
  idl::common::Vec2 out;
  out.x(v.x());
  out.y(v.y());
  return out;
}

void robots_to_idl(const std::vector<RobotDetection>& in, std::vector<idl::vision::RobotDetection>& out) {
  out.resize(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    const RobotDetection& r = in[i];
    idl::vision::RobotDetection& o = out[i];
    o.robot_id(r.robot_id.value_or(0));
    o.x(r.position.x());
    o.y(r.position.y());
    o.orientation(r.orientation.value_or(0.0));
    o.has_orientation(r.orientation.has_value());
    o.height(r.height.value_or(0.0));
    o.confidence(r.confidence);
    o.pixel_x(r.pixel_x);
    o.pixel_y(r.pixel_y);
  }
}

}  // namespace

Result<VisionPacket> from_proto(const SSL_WrapperPacket& packet) {
  Checker check;
  VisionPacket out;
  if (packet.has_source()) out.source = static_cast<VisionSource>(packet.source());
  if (packet.has_detection()) out.detection = frame_from_proto(packet.detection(), check);
  if (packet.has_geometry()) out.geometry = geometry_from_proto(packet.geometry(), check);
  if (!check.ok()) return Error{"SSL_WrapperPacket: " + check.error()};
  return out;
}

SSL_WrapperPacket to_proto(const VisionPacket& packet) {
  SSL_WrapperPacket out;
  if (packet.detection) frame_to_proto(*packet.detection, *out.mutable_detection());
  if (packet.geometry) geometry_to_proto(*packet.geometry, *out.mutable_geometry());
  if (packet.source != VisionSource::kUnknown) out.set_source(static_cast<SSL_Source>(packet.source));
  return out;
}

Result<VisionPacket> VisionDecoder::decode(std::span<const std::uint8_t> bytes) {
  if (Status decoded = league::decode_into(bytes, message_); !decoded) return decoded.error();
  return from_proto(message_);
}

TrackerPacket from_proto(const TrackerWrapperPacket& packet) {
  TrackerPacket out;
  out.uuid = packet.uuid();
  if (packet.has_source_name()) out.source_name = packet.source_name();
  if (packet.has_tracked_frame()) {
    const TrackedFrame& frame = packet.tracked_frame();
    out.frame_number = frame.frame_number();
    out.timestamp = time::Timestamp::try_from_seconds(frame.timestamp());
    out.balls = static_cast<std::size_t>(frame.balls_size());
    out.robots = static_cast<std::size_t>(frame.robots_size());
  }
  return out;
}

Result<TrackerPacket> decode_tracker_packet(std::span<const std::uint8_t> bytes) {
  auto decoded = league::decode_tracker_wrapper(bytes);
  if (!decoded) return decoded.error();
  return from_proto(*decoded);
}

void to_idl(const PublishedFrame& published, idl::vision::DetectionFrame& out) {
  const DetectionFrame& frame = published.frame;
  out.camera_id(frame.camera_id);
  out.frame_number(frame.frame_number);
  out.capture_unix_ns(frame.capture_vision.nanoseconds());
  out.sent_unix_ns(frame.sent_vision.nanoseconds());
  out.capture_camera_ns(frame.capture_camera ? frame.capture_camera->nanoseconds() : 0);
  out.has_capture_camera(frame.capture_camera.has_value());
  out.receive_unix_ns(published.receive_wall.nanoseconds());
  out.source(source_to_idl(published.source));
  out.balls().resize(frame.balls.size());
  for (std::size_t i = 0; i < frame.balls.size(); ++i) {
    const BallDetection& b = frame.balls[i];
    idl::vision::BallDetection& o = out.balls()[i];
    o.x(b.position.x());
    o.y(b.position.y());
    o.z(b.z.value_or(0.0));
    o.has_z(b.z.has_value());
    o.confidence(b.confidence);
    o.area(b.area.value_or(0));
    o.pixel_x(b.pixel_x);
    o.pixel_y(b.pixel_y);
  }
  robots_to_idl(frame.robots_yellow, out.robots_yellow());
  robots_to_idl(frame.robots_blue, out.robots_blue());
}

void to_idl(const PublishedGeometry& published, idl::vision::Geometry& out) {
  const FieldGeometry& geometry = published.geometry;
  const FieldSize& f = geometry.field;
  idl::vision::FieldSize& field = out.field();
  field.field_length(f.field_length);
  field.field_width(f.field_width);
  field.goal_width(f.goal_width);
  field.goal_depth(f.goal_depth);
  field.boundary_width(f.boundary_width);
  field.boundary_width_goal_line(f.boundary_width_goal_line);
  field.penalty_area_depth(f.penalty_area_depth);
  field.penalty_area_width(f.penalty_area_width);
  field.center_circle_radius(f.center_circle_radius);
  field.line_thickness(f.line_thickness);
  field.goal_center_to_penalty_mark(f.goal_center_to_penalty_mark);
  field.goal_height(f.goal_height);
  field.ball_radius(f.ball_radius);
  field.max_robot_radius(f.max_robot_radius);
  field.goal_substitution_area_width(f.goal_substitution_area_width);
  field.lines().clear();
  for (const FieldLine& line : f.lines) {
    idl::vision::FieldLine l;
    l.name(line.name);
    l.p1(vec2_to_idl(line.p1));
    l.p2(vec2_to_idl(line.p2));
    l.thickness(line.thickness);
    l.type(shape_to_idl(line.type));
    field.lines().push_back(std::move(l));
  }
  field.arcs().clear();
  for (const FieldArc& arc : f.arcs) {
    idl::vision::FieldArc a;
    a.name(arc.name);
    a.center(vec2_to_idl(arc.center));
    a.radius(arc.radius);
    a.a1(arc.a1);
    a.a2(arc.a2);
    a.thickness(arc.thickness);
    a.type(shape_to_idl(arc.type));
    field.arcs().push_back(std::move(a));
  }
  field.defaulted_fields(geometry.defaulted_fields);
  out.calibrations().clear();
  for (const CameraCalibration& c : geometry.calibrations) {
    idl::vision::CameraCalibration o;
    o.camera_id(c.camera_id);
    o.focal_length(c.focal_length);
    o.principal_point_x(c.principal_point_x);
    o.principal_point_y(c.principal_point_y);
    o.distortion(c.distortion);
    o.q0(c.q0);
    o.q1(c.q1);
    o.q2(c.q2);
    o.q3(c.q3);
    o.tx(c.tx);
    o.ty(c.ty);
    o.tz(c.tz);
    o.has_derived_world(c.derived_world.has_value());
    idl::common::Vec3 world;
    if (c.derived_world) {
      world.x(c.derived_world->x);
      world.y(c.derived_world->y);
      world.z(c.derived_world->z);
    }
    o.derived_world(world);
    o.pixel_image_width(c.pixel_image_width.value_or(0));
    o.pixel_image_height(c.pixel_image_height.value_or(0));
    out.calibrations().push_back(std::move(o));
  }
  idl::vision::BallModelStraightTwoPhase straight;
  straight.present(geometry.straight_two_phase.has_value());
  if (geometry.straight_two_phase) {
    straight.acc_slide(geometry.straight_two_phase->acc_slide);
    straight.acc_roll(geometry.straight_two_phase->acc_roll);
    straight.k_switch(geometry.straight_two_phase->k_switch);
  }
  out.straight_two_phase(straight);
  idl::vision::BallModelChipFixedLoss chip;
  chip.present(geometry.chip_fixed_loss.has_value());
  if (geometry.chip_fixed_loss) {
    chip.damping_xy_first_hop(geometry.chip_fixed_loss->damping_xy_first_hop);
    chip.damping_xy_other_hops(geometry.chip_fixed_loss->damping_xy_other_hops);
    chip.damping_z(geometry.chip_fixed_loss->damping_z);
  }
  out.chip_fixed_loss(chip);
  out.receive_unix_ns(published.receive_wall.nanoseconds());
  out.source(source_to_idl(published.source));
}

}  // namespace ssl::vision_gateway
