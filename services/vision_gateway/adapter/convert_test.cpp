// The gateway's wire <-> core <-> IDL conversions: millimetres become metres once for every length
// (detections, field sizes, lines, arcs, calibrations), Unix seconds become nanoseconds, optional fields
// keep their presence, and mm -> m -> mm round trips are exact.
#include "services/vision_gateway/adapter/convert.h"

#include <google/protobuf/util/message_differencer.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "libs/league/decode.h"
#include "services/vision_gateway/testing/builders.h"

namespace ssl::vision_gateway {
namespace {

using google::protobuf::util::MessageDifferencer;

/// A wire detection frame with every field set, in millimetres, written as ssl-vision would.
SSL_WrapperPacket wire_detection() {
  SSL_WrapperPacket packet;
  packet.set_source(SSL_SOURCE_SSL_VISION);
  SSL_DetectionFrame* frame = packet.mutable_detection();
  frame->set_frame_number(123456);
  frame->set_t_capture(1780000000.125);
  frame->set_t_sent(1780000000.1295);
  frame->set_t_capture_camera(98765.4321);
  frame->set_camera_id(3);
  SSL_DetectionBall* ball = frame->add_balls();
  ball->set_confidence(0.875f);
  ball->set_area(142);
  ball->set_x(-1234.5f);
  ball->set_y(2750.25f);
  ball->set_z(43.0f);
  ball->set_pixel_x(640.5f);
  ball->set_pixel_y(480.25f);
  SSL_DetectionRobot* yellow = frame->add_robots_yellow();
  yellow->set_confidence(0.9375f);
  yellow->set_robot_id(7);
  yellow->set_x(4500.0f);
  yellow->set_y(-3000.5f);
  yellow->set_orientation(-2.5f);
  yellow->set_pixel_x(10.0f);
  yellow->set_pixel_y(20.0f);
  yellow->set_height(150.0f);
  SSL_DetectionRobot* blue = frame->add_robots_blue();  // only the required fields
  blue->set_confidence(0.5f);
  blue->set_x(0.5f);
  blue->set_y(-0.25f);
  blue->set_pixel_x(1.0f);
  blue->set_pixel_y(2.0f);
  return packet;
}

/// A wire geometry with every field set (millimetres).
SSL_WrapperPacket wire_geometry() {
  VisionPacket packet;
  packet.geometry = testing::full_geometry();
  SSL_WrapperPacket wire = to_proto(packet);
  wire.mutable_geometry()->mutable_field()->mutable_field_lines(0)->mutable_p1()->set_x(-6000.5f);
  return wire;
}

TEST(VisionGatewayConvert, DetectionLengthsBecomeMetresAndTimesNanoseconds) {
  auto packet = from_proto(wire_detection());
  ASSERT_TRUE(packet) << packet.error().message;
  EXPECT_EQ(packet->source, VisionSource::kSslVision);
  ASSERT_TRUE(packet->detection);
  const DetectionFrame& f = *packet->detection;
  EXPECT_EQ(f.camera_id, 3u);
  EXPECT_EQ(f.frame_number, 123456u);
  EXPECT_EQ(f.capture_vision.nanoseconds(), 1780000000'125000000);
  EXPECT_EQ(f.sent_vision, time::Timestamp::from_seconds(1780000000.1295));
  ASSERT_TRUE(f.capture_camera);
  EXPECT_EQ(*f.capture_camera, time::Timestamp::from_seconds(98765.4321));
  ASSERT_EQ(f.balls.size(), 1u);
  EXPECT_DOUBLE_EQ(f.balls[0].position.x(), -1.2345);
  EXPECT_DOUBLE_EQ(f.balls[0].position.y(), 2.75025);
  EXPECT_EQ(f.balls[0].z, 0.043);
  EXPECT_EQ(f.balls[0].area, 142u);
  EXPECT_EQ(f.balls[0].pixel_x, 640.5f);  // pixels stay pixels
  ASSERT_EQ(f.robots_yellow.size(), 1u);
  EXPECT_EQ(f.robots_yellow[0].robot_id, 7u);
  EXPECT_DOUBLE_EQ(f.robots_yellow[0].position.x(), 4.5);
  EXPECT_DOUBLE_EQ(f.robots_yellow[0].position.y(), -3.0005);
  EXPECT_EQ(f.robots_yellow[0].orientation, -2.5);  // radians stay radians
  EXPECT_EQ(f.robots_yellow[0].height, 0.15);
  ASSERT_EQ(f.robots_blue.size(), 1u);
  EXPECT_FALSE(f.robots_blue[0].robot_id);
  EXPECT_FALSE(f.robots_blue[0].orientation);
  EXPECT_FALSE(f.robots_blue[0].height);
  EXPECT_DOUBLE_EQ(f.robots_blue[0].position.x(), 0.0005);
  EXPECT_FALSE(packet->geometry);
}

TEST(VisionGatewayConvert, GeometryLengthsBecomeMetres) {
  auto packet = from_proto(wire_geometry());
  ASSERT_TRUE(packet) << packet.error().message;
  ASSERT_TRUE(packet->geometry);
  const GeometryInput& g = *packet->geometry;
  EXPECT_EQ(g.field.field_length, 12.0);
  EXPECT_EQ(g.field.field_width, 9.0);
  EXPECT_EQ(g.field.goal_width, 1.8);
  EXPECT_EQ(g.field.goal_depth, 0.18);
  EXPECT_EQ(g.field.boundary_width, 0.3);
  EXPECT_EQ(g.field.boundary_width_goal_line, 0.6);
  EXPECT_EQ(g.field.penalty_area_depth, 1.8);
  EXPECT_EQ(g.field.penalty_area_width, 3.6);
  EXPECT_EQ(g.field.center_circle_radius, 0.5);
  EXPECT_EQ(g.field.line_thickness, 0.01);
  EXPECT_EQ(g.field.goal_center_to_penalty_mark, 8.0);
  EXPECT_EQ(g.field.goal_height, 0.155);
  EXPECT_EQ(g.field.ball_radius, 0.0215);
  EXPECT_EQ(g.field.max_robot_radius, 0.09);
  EXPECT_EQ(g.field.goal_substitution_area_width, 0.3);
  ASSERT_EQ(g.field.lines.size(), 12u);
  EXPECT_EQ(g.field.lines[0].name, "TopTouchLine");
  EXPECT_DOUBLE_EQ(g.field.lines[0].p1.x(), -6.0005);
  EXPECT_EQ(g.field.lines[0].p1.y(), 4.5);
  EXPECT_EQ(g.field.lines[0].p2.x(), 6.0);
  EXPECT_EQ(g.field.lines[0].thickness, 0.01);
  EXPECT_EQ(g.field.lines[0].type, FieldShapeType::kTopTouchLine);
  ASSERT_EQ(g.field.arcs.size(), 1u);
  EXPECT_EQ(g.field.arcs[0].radius, 0.5);
  EXPECT_EQ(g.field.arcs[0].center, Vec2(0.0, 0.0));
  EXPECT_NEAR(g.field.arcs[0].a2, 2 * M_PI, 1e-6);  // radians unchanged
  EXPECT_EQ(g.field.arcs[0].thickness, 0.01);
  ASSERT_EQ(g.calibrations.size(), 4u);
  const CameraCalibration& c = g.calibrations[1];
  EXPECT_EQ(c.camera_id, 1u);
  EXPECT_EQ(c.focal_length, 1292.5);  // pixels unchanged
  EXPECT_EQ(c.distortion, 0.125);
  EXPECT_EQ(c.tx, -3.0);
  EXPECT_EQ(c.ty, -2.25);
  EXPECT_EQ(c.tz, 4.0);
  ASSERT_TRUE(c.derived_world);
  EXPECT_EQ(*c.derived_world, (Vec3{3.0, -2.25, 4.0}));
  EXPECT_EQ(c.pixel_image_width, 2448u);
  ASSERT_TRUE(g.straight_two_phase);
  EXPECT_EQ(g.straight_two_phase->acc_slide, -3.0);  // m/s^2 on the wire already
  ASSERT_TRUE(g.chip_fixed_loss);
  EXPECT_EQ(g.chip_fixed_loss->damping_z, 0.5);
}

TEST(VisionGatewayConvert, WireToCoreToWireIsExactForEveryField) {
  for (const SSL_WrapperPacket& wire : {wire_detection(), wire_geometry()}) {
    auto core = from_proto(wire);
    ASSERT_TRUE(core) << core.error().message;
    const SSL_WrapperPacket back = to_proto(*core);
    std::string differences;
    MessageDifferencer differencer;
    differencer.ReportDifferencesToString(&differences);
    EXPECT_TRUE(differencer.Compare(wire, back)) << differences;
  }
}

TEST(VisionGatewayConvert, CoreToWireToCoreIsExactForTheTestFixtures) {
  VisionPacket packet;
  packet.detection = testing::simple_frame(2, 77, 3);
  packet.geometry = testing::full_geometry();
  packet.source = VisionSource::kErforceSim;
  auto back = from_proto(to_proto(packet));
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(*back, packet);
}

TEST(VisionGatewayConvert, FourCameraFrameSurvivesTheWireWithinFloatPrecision) {
  for (const DetectionFrame& frame : testing::four_camera_frame(9)) {
    VisionPacket packet;
    packet.detection = frame;
    auto back = from_proto(to_proto(packet));
    ASSERT_TRUE(back);
    ASSERT_EQ(back->detection->robots_blue.size(), frame.robots_blue.size());
    for (std::size_t i = 0; i < frame.robots_blue.size(); ++i) {
      EXPECT_NEAR(back->detection->robots_blue[i].position.x(), frame.robots_blue[i].position.x(), 1e-6);
      EXPECT_NEAR(back->detection->robots_blue[i].position.y(), frame.robots_blue[i].position.y(), 1e-6);
    }
  }
}

TEST(VisionGatewayConvert, LineWithoutTypeGetsTheTypeOfItsName) {
  SSL_WrapperPacket wire = wire_geometry();
  wire.mutable_geometry()->mutable_field()->mutable_field_lines(3)->clear_type();
  wire.mutable_geometry()->mutable_field()->mutable_field_arcs(0)->clear_type();
  auto packet = from_proto(wire);
  ASSERT_TRUE(packet);
  EXPECT_EQ(packet->geometry->field.lines[3].type, FieldShapeType::kRightGoalLine);
  EXPECT_EQ(packet->geometry->field.arcs[0].type, FieldShapeType::kCenterCircle);
}

TEST(VisionGatewayConvert, MissingOptionalFieldsStayAbsent) {
  SSL_WrapperPacket wire = wire_geometry();
  SSL_GeometryFieldSize* field = wire.mutable_geometry()->mutable_field();
  field->clear_goal_height();
  field->clear_ball_radius();
  field->clear_boundary_width_goal_line();
  wire.mutable_geometry()->mutable_calib(0)->clear_derived_camera_world_tz();
  wire.mutable_geometry()->clear_models();
  auto packet = from_proto(wire);
  ASSERT_TRUE(packet);
  EXPECT_FALSE(packet->geometry->field.goal_height);
  EXPECT_FALSE(packet->geometry->field.ball_radius);
  EXPECT_FALSE(packet->geometry->field.boundary_width_goal_line);
  EXPECT_TRUE(packet->geometry->field.penalty_area_depth);
  EXPECT_FALSE(packet->geometry->calibrations[0].derived_world);  // only with all three coordinates
  EXPECT_FALSE(packet->geometry->straight_two_phase);
  EXPECT_FALSE(packet->geometry->chip_fixed_loss);
}

TEST(VisionGatewayConvert, NonFiniteNumbersAreRejectedNamingTheField) {
  SSL_WrapperPacket wire = wire_detection();
  wire.mutable_detection()->mutable_robots_yellow(0)->set_y(std::numeric_limits<float>::quiet_NaN());
  auto packet = from_proto(wire);
  ASSERT_FALSE(packet);
  EXPECT_NE(packet.error().message.find("detection.robots_yellow[0].y is not a finite number"),
            std::string::npos)
      << packet.error().message;

  wire = wire_detection();
  wire.mutable_detection()->set_t_capture(std::numeric_limits<double>::infinity());
  packet = from_proto(wire);
  ASSERT_FALSE(packet);
  EXPECT_NE(packet.error().message.find("detection.t_capture"), std::string::npos) << packet.error().message;

  wire = wire_geometry();
  wire.mutable_geometry()->mutable_field()->mutable_field_arcs(0)->set_radius(
      -std::numeric_limits<float>::infinity());
  packet = from_proto(wire);
  ASSERT_FALSE(packet);
  EXPECT_NE(packet.error().message.find("geometry.field.field_arcs[0].radius"), std::string::npos)
      << packet.error().message;
}

TEST(VisionGatewayConvert, NonPositiveFieldLengthIsRejected) {
  SSL_WrapperPacket wire = wire_geometry();
  wire.mutable_geometry()->mutable_field()->set_field_length(0);
  auto packet = from_proto(wire);
  ASSERT_FALSE(packet);
  EXPECT_NE(packet.error().message.find("field_length must be positive"), std::string::npos);
}

TEST(VisionGatewayConvert, DetectionToIdlCarriesMetresTimesAndPresenceFlags) {
  auto packet = from_proto(wire_detection());
  ASSERT_TRUE(packet);
  const PublishedFrame published{*packet->detection, VisionSource::kSslVision,
                                 time::Timestamp::from_nanoseconds(1780000000'200000001)};
  idl::vision::DetectionFrame idl;
  idl.robots_blue().resize(5);  // a reused sample: stale entries must go
  to_idl(published, idl);
  EXPECT_EQ(idl.camera_id(), 3u);
  EXPECT_EQ(idl.frame_number(), 123456u);
  EXPECT_EQ(idl.capture_unix_ns(), 1780000000'125000000);
  EXPECT_EQ(idl.sent_unix_ns(), time::Timestamp::from_seconds(1780000000.1295).nanoseconds());
  EXPECT_TRUE(idl.has_capture_camera());
  EXPECT_EQ(idl.capture_camera_ns(), time::Timestamp::from_seconds(98765.4321).nanoseconds());
  EXPECT_EQ(idl.receive_unix_ns(), 1780000000'200000001);
  EXPECT_EQ(idl.source(), idl::vision::VISION_SOURCE_SSL_VISION);
  ASSERT_EQ(idl.balls().size(), 1u);
  EXPECT_DOUBLE_EQ(idl.balls()[0].x(), -1.2345);
  EXPECT_TRUE(idl.balls()[0].has_z());
  EXPECT_DOUBLE_EQ(idl.balls()[0].z(), 0.043);
  EXPECT_EQ(idl.balls()[0].area(), 142u);
  ASSERT_EQ(idl.robots_yellow().size(), 1u);
  EXPECT_EQ(idl.robots_yellow()[0].robot_id(), 7u);
  EXPECT_DOUBLE_EQ(idl.robots_yellow()[0].x(), 4.5);
  EXPECT_TRUE(idl.robots_yellow()[0].has_orientation());
  EXPECT_DOUBLE_EQ(idl.robots_yellow()[0].orientation(), -2.5);
  EXPECT_DOUBLE_EQ(idl.robots_yellow()[0].height(), 0.15);
  ASSERT_EQ(idl.robots_blue().size(), 1u);
  EXPECT_FALSE(idl.robots_blue()[0].has_orientation());
  EXPECT_EQ(idl.robots_blue()[0].height(), 0.0);

  // Without t_capture_camera and z.
  packet->detection->capture_camera.reset();
  packet->detection->balls[0].z.reset();
  to_idl(PublishedFrame{*packet->detection, VisionSource::kUnknown, {}}, idl);
  EXPECT_FALSE(idl.has_capture_camera());
  EXPECT_EQ(idl.capture_camera_ns(), 0);
  EXPECT_FALSE(idl.balls()[0].has_z());
  EXPECT_EQ(idl.source(), idl::vision::VISION_SOURCE_UNKNOWN);
}

TEST(VisionGatewayConvert, GeometryToIdlCarriesEveryFieldLineArcCalibrationAndDefaults) {
  GeometryInput input = testing::full_geometry();
  input.field.goal_height.reset();
  const PublishedGeometry published{resolve_geometry(input, DivisionChoice::kAuto), VisionSource::kGrsim,
                                    time::Timestamp::from_nanoseconds(42)};
  idl::vision::Geometry idl;
  to_idl(published, idl);
  const auto& f = idl.field();
  EXPECT_EQ(f.field_length(), 12.0);
  EXPECT_EQ(f.field_width(), 9.0);
  EXPECT_EQ(f.goal_width(), 1.8);
  EXPECT_EQ(f.goal_depth(), 0.18);
  EXPECT_EQ(f.boundary_width(), 0.3);
  EXPECT_EQ(f.boundary_width_goal_line(), 0.6);
  EXPECT_EQ(f.penalty_area_depth(), 1.8);
  EXPECT_EQ(f.penalty_area_width(), 3.6);
  EXPECT_EQ(f.center_circle_radius(), 0.5);
  EXPECT_EQ(f.line_thickness(), 0.01);
  EXPECT_EQ(f.goal_center_to_penalty_mark(), 8.0);
  EXPECT_EQ(f.goal_height(), 0.16);  // defaulted (Division A rulebook)
  EXPECT_EQ(f.ball_radius(), 0.0215);
  EXPECT_EQ(f.max_robot_radius(), 0.09);
  EXPECT_EQ(f.goal_substitution_area_width(), 0.3);
  EXPECT_EQ(f.defaulted_fields(), std::vector<std::string>{"goal_height"});
  ASSERT_EQ(f.lines().size(), 12u);
  EXPECT_EQ(f.lines()[6].name(), "LeftPenaltyStretch");
  EXPECT_EQ(f.lines()[6].p1().x(), -4.2);
  EXPECT_EQ(f.lines()[6].p2().y(), 1.8);
  EXPECT_EQ(f.lines()[6].thickness(), 0.01);
  EXPECT_EQ(f.lines()[6].type(), idl::vision::FIELD_SHAPE_LEFT_PENALTY_STRETCH);
  ASSERT_EQ(f.arcs().size(), 1u);
  EXPECT_EQ(f.arcs()[0].type(), idl::vision::FIELD_SHAPE_CENTER_CIRCLE);
  EXPECT_EQ(f.arcs()[0].radius(), 0.5);
  ASSERT_EQ(idl.calibrations().size(), 4u);
  const auto& c = idl.calibrations()[3];
  EXPECT_EQ(c.camera_id(), 3u);
  EXPECT_EQ(c.tx(), -3.0);
  EXPECT_EQ(c.ty(), 2.25);
  EXPECT_TRUE(c.has_derived_world());
  EXPECT_EQ(c.derived_world().x(), 3.0);
  EXPECT_EQ(c.derived_world().z(), 4.0);
  EXPECT_EQ(c.pixel_image_height(), 2048u);
  EXPECT_TRUE(idl.straight_two_phase().present());
  EXPECT_EQ(idl.straight_two_phase().acc_roll(), -0.4);
  EXPECT_TRUE(idl.chip_fixed_loss().present());
  EXPECT_EQ(idl.chip_fixed_loss().damping_xy_other_hops(), 0.95);
  EXPECT_EQ(idl.receive_unix_ns(), 42);
  EXPECT_EQ(idl.source(), idl::vision::VISION_SOURCE_GRSIM);
}

TEST(VisionGatewayConvert, TrackerPacketIsSummarised) {
  TrackerWrapperPacket wire;
  wire.set_uuid("0f1e");
  wire.set_source_name("TIGERs AutoRef");
  TrackedFrame* frame = wire.mutable_tracked_frame();
  frame->set_frame_number(99);
  frame->set_timestamp(1780000000.5);
  auto* ball = frame->add_balls();
  ball->mutable_pos()->set_x(1);
  ball->mutable_pos()->set_y(2);
  ball->mutable_pos()->set_z(0);
  auto bytes = league::encode_datagram(wire);
  ASSERT_TRUE(bytes) << bytes.error().message;
  auto packet = decode_tracker_packet(league::byte_span(*bytes));
  ASSERT_TRUE(packet) << packet.error().message;
  EXPECT_EQ(packet->uuid, "0f1e");
  EXPECT_EQ(packet->source_name, "TIGERs AutoRef");
  EXPECT_EQ(packet->frame_number, 99u);
  EXPECT_EQ(packet->timestamp, time::Timestamp::from_seconds(1780000000.5));
  EXPECT_EQ(packet->balls, 1u);
  EXPECT_FALSE(decode_tracker_packet(league::byte_span("\x0a\x05zz")));
}

}  // namespace
}  // namespace ssl::vision_gateway
