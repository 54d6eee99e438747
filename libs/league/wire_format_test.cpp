// Wire compatibility of proto/*.proto with the league's field tables (shared/reference/ssl-protocols.md):
// for a representative message of every .proto file, the bytes our generated classes emit must equal
// bytes encoded by hand from the tables, and the hand bytes must decode back to the same values.
#include <gtest/gtest.h>

#include <cstdint>
#include <iterator>
#include <string>

#include "libs/league/decode.h"
#include "libs/league/testing/hand_encoder.h"
#include "proto/grsim_packet.pb.h"
#include "proto/grsim_robotstatus.pb.h"
#include "proto/ssl_gc_ci.pb.h"
#include "proto/ssl_gc_common.pb.h"
#include "proto/ssl_gc_game_event.pb.h"
#include "proto/ssl_gc_geometry.pb.h"
#include "proto/ssl_gc_rcon.pb.h"
#include "proto/ssl_gc_rcon_autoref.pb.h"
#include "proto/ssl_gc_rcon_team.pb.h"
#include "proto/ssl_gc_referee_message.pb.h"
#include "proto/ssl_simulation_config.pb.h"
#include "proto/ssl_simulation_control.pb.h"
#include "proto/ssl_simulation_custom_erforce_realism.pb.h"
#include "proto/ssl_simulation_custom_erforce_robot_specs.pb.h"
#include "proto/ssl_simulation_error.pb.h"
#include "proto/ssl_simulation_robot_control.pb.h"
#include "proto/ssl_simulation_robot_feedback.pb.h"
#include "proto/ssl_simulation_synchronous.pb.h"
#include "proto/ssl_vision_detection.pb.h"
#include "proto/ssl_vision_detection_tracked.pb.h"
#include "proto/ssl_vision_geometry.pb.h"
#include "proto/ssl_vision_geometry_legacy.pb.h"
#include "proto/ssl_vision_wrapper.pb.h"
#include "proto/ssl_vision_wrapper_legacy.pb.h"
#include "proto/ssl_vision_wrapper_tracked.pb.h"

namespace ssl::league {
namespace {

using testing::HandEncoder;
using testing::hex;

/// Checks that `built` serializes to exactly `hand`, then decodes `hand` and returns the result.
template <typename M>
M expect_wire(const M& built, const HandEncoder& hand) {
  EXPECT_EQ(hex(built.SerializeAsString()), hex(hand.str())) << M::descriptor()->full_name();
  auto decoded = decode<M>(byte_span(hand.str()));
  EXPECT_TRUE(decoded.ok()) << (decoded.ok() ? std::string() : decoded.error().message);
  return decoded.ok() ? *decoded : M{};
}

HandEncoder vec2(float x, float y) {
  HandEncoder v;
  v.f32(1, x).f32(2, y);
  return v;
}

HandEncoder vec3(float x, float y, float z) {
  HandEncoder v;
  v.f32(1, x).f32(2, y).f32(3, z);
  return v;
}

// The encoder itself, against the examples of the protobuf encoding guide.
TEST(LeagueHandEncoder, MatchesEncodingGuideExamples) {
  EXPECT_EQ(hex(HandEncoder().varint(1, 150).str()), "08 96 01");
  EXPECT_EQ(hex(HandEncoder().bytes(2, "testing").str()), "12 07 74 65 73 74 69 6e 67");
  EXPECT_EQ(hex(HandEncoder().sint(1, -1).str()), "08 01");
  EXPECT_EQ(hex(HandEncoder().sint(1, 1).str()), "08 02");
  EXPECT_EQ(hex(HandEncoder().sint(1, -2).str()), "08 03");
  EXPECT_EQ(hex(HandEncoder().int64(1, -1).str()), "08 ff ff ff ff ff ff ff ff ff 01");
  EXPECT_EQ(hex(HandEncoder().f32(1, 1.0F).str()), "0d 00 00 80 3f");
  EXPECT_EQ(hex(HandEncoder().f64(1, 1.0).str()), "09 00 00 00 00 00 00 f0 3f");
  EXPECT_EQ(hex(HandEncoder().packed_varints(4, {3, 270}).str()), "22 03 03 8e 02");
  EXPECT_EQ(hex(HandEncoder().varint(43, 0).str()), "d8 02 00");  // two-byte tag
}

// ---------------------------------------------------------------------------------------------------
// ssl_vision_detection.proto

TEST(LeagueWireFormat, VisionDetectionFrame) {
  SSL_DetectionFrame frame;
  frame.set_frame_number(42);
  frame.set_t_capture(1.5);
  frame.set_t_sent(1.75);
  frame.set_camera_id(3);
  frame.set_t_capture_camera(0.25);
  auto* ball = frame.add_balls();
  ball->set_confidence(0.9F);
  ball->set_area(120);
  ball->set_x(-1000.5F);
  ball->set_y(250.0F);
  ball->set_z(21.5F);
  ball->set_pixel_x(300.0F);
  ball->set_pixel_y(200.0F);
  auto* yellow = frame.add_robots_yellow();
  yellow->set_confidence(0.8F);
  yellow->set_robot_id(7);
  yellow->set_x(10.0F);
  yellow->set_y(-20.0F);
  yellow->set_orientation(1.25F);
  yellow->set_pixel_x(1.0F);
  yellow->set_pixel_y(2.0F);
  yellow->set_height(150.0F);
  auto* blue = frame.add_robots_blue();
  blue->set_confidence(1.0F);
  blue->set_x(0.0F);
  blue->set_y(0.0F);
  blue->set_pixel_x(0.0F);
  blue->set_pixel_y(0.0F);

  HandEncoder hand_ball;
  hand_ball.f32(1, 0.9F)
      .varint(2, 120)
      .f32(3, -1000.5F)
      .f32(4, 250.0F)
      .f32(5, 21.5F)
      .f32(6, 300.0F)
      .f32(7, 200.0F);
  HandEncoder hand_yellow;
  hand_yellow.f32(1, 0.8F)
      .varint(2, 7)
      .f32(3, 10.0F)
      .f32(4, -20.0F)
      .f32(5, 1.25F)
      .f32(6, 1.0F)
      .f32(7, 2.0F)
      .f32(8, 150.0F);
  HandEncoder hand_blue;
  hand_blue.f32(1, 1.0F).f32(3, 0.0F).f32(4, 0.0F).f32(6, 0.0F).f32(7, 0.0F);
  HandEncoder hand;
  hand.varint(1, 42).f64(2, 1.5).f64(3, 1.75).varint(4, 3);
  hand.message(5, hand_ball).message(6, hand_yellow).message(7, hand_blue).f64(8, 0.25);

  const auto decoded = expect_wire(frame, hand);
  EXPECT_EQ(decoded.frame_number(), 42U);
  EXPECT_EQ(decoded.camera_id(), 3U);
  EXPECT_DOUBLE_EQ(decoded.t_capture_camera(), 0.25);
  ASSERT_EQ(decoded.balls_size(), 1);
  EXPECT_FLOAT_EQ(decoded.balls(0).z(), 21.5F);
  EXPECT_EQ(decoded.balls(0).area(), 120U);
  ASSERT_EQ(decoded.robots_yellow_size(), 1);
  EXPECT_EQ(decoded.robots_yellow(0).robot_id(), 7U);
  EXPECT_FLOAT_EQ(decoded.robots_yellow(0).height(), 150.0F);
  ASSERT_EQ(decoded.robots_blue_size(), 1);
  EXPECT_FALSE(decoded.robots_blue(0).has_robot_id());
}

// ---------------------------------------------------------------------------------------------------
// ssl_vision_geometry.proto

SSL_GeometryFieldSize minimal_field() {
  SSL_GeometryFieldSize field;
  field.set_field_length(9000);
  field.set_field_width(6000);
  field.set_goal_width(1000);
  field.set_goal_depth(180);
  field.set_boundary_width(300);
  return field;
}

HandEncoder hand_minimal_field() {
  HandEncoder field;
  field.varint(1, 9000).varint(2, 6000).varint(3, 1000).varint(4, 180).varint(5, 300);
  return field;
}

TEST(LeagueWireFormat, VisionGeometryWithNewFieldsAndModels) {
  SSL_GeometryData data;
  auto* field = data.mutable_field();
  field->set_field_length(12000);
  field->set_field_width(9000);
  field->set_goal_width(1800);
  field->set_goal_depth(180);
  field->set_boundary_width(300);
  auto* line = field->add_field_lines();
  line->set_name("LeftGoalLine");
  line->mutable_p1()->set_x(-6000.0F);
  line->mutable_p1()->set_y(-4500.0F);
  line->mutable_p2()->set_x(-6000.0F);
  line->mutable_p2()->set_y(4500.0F);
  line->set_thickness(10.0F);
  line->set_type(LeftGoalLine);
  auto* arc = field->add_field_arcs();
  arc->set_name("CenterCircle");
  arc->mutable_center()->set_x(0.0F);
  arc->mutable_center()->set_y(0.0F);
  arc->set_radius(500.0F);
  arc->set_a1(0.0F);
  arc->set_a2(6.2831855F);
  arc->set_thickness(10.0F);
  arc->set_type(CenterCircle);
  field->set_penalty_area_depth(1800);
  field->set_penalty_area_width(3600);
  field->set_center_circle_radius(500);
  field->set_line_thickness(10);
  field->set_goal_center_to_penalty_mark(8000);
  field->set_goal_height(155);
  field->set_ball_radius(21.5F);
  field->set_max_robot_radius(90.0F);
  field->set_boundary_width_goal_line(600);
  field->set_goal_substitution_area_width(300);
  auto* calib = data.add_calib();
  calib->set_camera_id(2);
  calib->set_focal_length(390.5F);
  calib->set_principal_point_x(300.0F);
  calib->set_principal_point_y(240.0F);
  calib->set_distortion(0.25F);
  calib->set_q0(0.5F);
  calib->set_q1(-0.5F);
  calib->set_q2(0.25F);
  calib->set_q3(-0.25F);
  calib->set_tx(100.0F);
  calib->set_ty(-200.0F);
  calib->set_tz(3500.0F);
  calib->set_derived_camera_world_tx(1500.0F);
  calib->set_derived_camera_world_ty(-2250.0F);
  calib->set_derived_camera_world_tz(4000.0F);
  calib->set_pixel_image_width(2448);
  calib->set_pixel_image_height(2048);
  auto* straight = data.mutable_models()->mutable_straight_two_phase();
  straight->set_acc_slide(-3.0);
  straight->set_acc_roll(-0.4);
  straight->set_k_switch(0.69);
  auto* chip = data.mutable_models()->mutable_chip_fixed_loss();
  chip->set_damping_xy_first_hop(0.75);
  chip->set_damping_xy_other_hops(0.95);
  chip->set_damping_z(0.5);

  HandEncoder hand_line;
  hand_line.bytes(1, "LeftGoalLine").message(2, vec2(-6000.0F, -4500.0F)).message(3, vec2(-6000.0F, 4500.0F));
  hand_line.f32(4, 10.0F).varint(5, 4);
  HandEncoder hand_arc;
  hand_arc.bytes(1, "CenterCircle")
      .message(2, vec2(0.0F, 0.0F))
      .f32(3, 500.0F)
      .f32(4, 0.0F)
      .f32(5, 6.2831855F);
  hand_arc.f32(6, 10.0F).varint(7, 1);
  HandEncoder hand_field;
  hand_field.varint(1, 12000).varint(2, 9000).varint(3, 1800).varint(4, 180).varint(5, 300);
  hand_field.message(6, hand_line).message(7, hand_arc);
  hand_field.varint(8, 1800).varint(9, 3600).varint(10, 500).varint(11, 10).varint(12, 8000).varint(13, 155);
  hand_field.f32(14, 21.5F).f32(15, 90.0F).varint(16, 600).varint(17, 300);
  HandEncoder hand_calib;
  hand_calib.varint(1, 2).f32(2, 390.5F).f32(3, 300.0F).f32(4, 240.0F).f32(5, 0.25F);
  hand_calib.f32(6, 0.5F)
      .f32(7, -0.5F)
      .f32(8, 0.25F)
      .f32(9, -0.25F)
      .f32(10, 100.0F)
      .f32(11, -200.0F)
      .f32(12, 3500.0F);
  hand_calib.f32(13, 1500.0F).f32(14, -2250.0F).f32(15, 4000.0F).varint(16, 2448).varint(17, 2048);
  HandEncoder hand_straight;
  hand_straight.f64(1, -3.0).f64(2, -0.4).f64(3, 0.69);
  HandEncoder hand_chip;
  hand_chip.f64(1, 0.75).f64(2, 0.95).f64(3, 0.5);
  HandEncoder hand_models;
  hand_models.message(1, hand_straight).message(2, hand_chip);
  HandEncoder hand;
  hand.message(1, hand_field).message(2, hand_calib).message(3, hand_models);

  const auto decoded = expect_wire(data, hand);
  EXPECT_EQ(decoded.field().boundary_width_goal_line(), 600);
  EXPECT_EQ(decoded.field().goal_substitution_area_width(), 300);
  EXPECT_EQ(decoded.field().field_lines(0).type(), LeftGoalLine);
  EXPECT_EQ(decoded.field().field_arcs(0).type(), CenterCircle);
  EXPECT_FLOAT_EQ(decoded.field().max_robot_radius(), 90.0F);
  EXPECT_EQ(decoded.calib(0).pixel_image_height(), 2048U);
  EXPECT_DOUBLE_EQ(decoded.models().straight_two_phase().acc_roll(), -0.4);
  EXPECT_DOUBLE_EQ(decoded.models().chip_fixed_loss().damping_z(), 0.5);
  EXPECT_EQ(RightFieldRightPenaltyStretch, 13);
}

// ---------------------------------------------------------------------------------------------------
// ssl_vision_wrapper.proto

TEST(LeagueWireFormat, VisionWrapperWithSource) {
  SSL_WrapperPacket packet;
  auto* frame = packet.mutable_detection();
  frame->set_frame_number(1);
  frame->set_t_capture(2.0);
  frame->set_t_sent(3.0);
  frame->set_camera_id(0);
  *packet.mutable_geometry()->mutable_field() = minimal_field();
  packet.set_source(SSL_SOURCE_ERFORCE_SIM);

  HandEncoder hand_frame;
  hand_frame.varint(1, 1).f64(2, 2.0).f64(3, 3.0).varint(4, 0);
  HandEncoder hand_geometry;
  hand_geometry.message(1, hand_minimal_field());
  HandEncoder hand;
  hand.message(1, hand_frame).message(2, hand_geometry).varint(3, 5);

  const auto decoded = expect_wire(packet, hand);
  EXPECT_EQ(decoded.source(), SSL_SOURCE_ERFORCE_SIM);
  EXPECT_EQ(decoded.geometry().field().field_length(), 9000);
  EXPECT_EQ(SSL_SOURCE_VISION_PROCESSOR, 3);
  EXPECT_EQ(SSL_SOURCE_GRSIM, 4);
}

// ---------------------------------------------------------------------------------------------------
// ssl_vision_geometry_legacy.proto, ssl_vision_wrapper_legacy.proto

TEST(LeagueWireFormat, LegacyGeometryAndWrapper) {
  RoboCup2014Legacy::Wrapper::SSL_WrapperPacket packet;
  auto* field = packet.mutable_geometry()->mutable_field();
  field->set_line_width(10);
  field->set_field_length(6050);
  field->set_field_width(4050);
  field->set_boundary_width(250);
  field->set_referee_width(425);
  field->set_goal_width(700);
  field->set_goal_depth(180);
  field->set_goal_wall_width(20);
  field->set_center_circle_radius(500);
  field->set_defense_radius(500);
  field->set_defense_stretch(350);
  field->set_free_kick_from_defense_dist(200);
  field->set_penalty_spot_from_field_line_dist(750);
  field->set_penalty_line_from_spot_dist(400);
  auto* calib = packet.mutable_geometry()->add_calib();
  calib->set_camera_id(1);
  for (auto setter : {&SSL_GeometryCameraCalibration::set_focal_length,
                      &SSL_GeometryCameraCalibration::set_principal_point_x,
                      &SSL_GeometryCameraCalibration::set_principal_point_y,
                      &SSL_GeometryCameraCalibration::set_distortion, &SSL_GeometryCameraCalibration::set_q0,
                      &SSL_GeometryCameraCalibration::set_q1, &SSL_GeometryCameraCalibration::set_q2,
                      &SSL_GeometryCameraCalibration::set_q3, &SSL_GeometryCameraCalibration::set_tx,
                      &SSL_GeometryCameraCalibration::set_ty, &SSL_GeometryCameraCalibration::set_tz}) {
    (calib->*setter)(1.0F);
  }

  HandEncoder hand_field;
  hand_field.varint(1, 10).varint(2, 6050).varint(3, 4050).varint(4, 250).varint(5, 425).varint(6, 700);
  hand_field.varint(7, 180).varint(8, 20).varint(9, 500).varint(10, 500).varint(11, 350).varint(12, 200);
  hand_field.varint(13, 750).varint(14, 400);
  HandEncoder hand_calib;
  hand_calib.varint(1, 1);
  for (std::uint32_t number = 2; number <= 12; ++number) {
    hand_calib.f32(number, 1.0F);
  }
  HandEncoder hand_geometry;
  hand_geometry.message(1, hand_field).message(2, hand_calib);
  HandEncoder hand;
  hand.message(2, hand_geometry);

  const auto decoded = expect_wire(packet, hand);
  EXPECT_EQ(decoded.GetTypeName(), "RoboCup2014Legacy.Wrapper.SSL_WrapperPacket");
  EXPECT_EQ(decoded.geometry().GetTypeName(), "RoboCup2014Legacy.Geometry.SSL_GeometryData");
  EXPECT_EQ(decoded.geometry().field().penalty_line_from_spot_dist(), 400);
  EXPECT_EQ(decoded.geometry().field().referee_width(), 425);
  EXPECT_FALSE(decoded.has_detection());
  // The legacy stream decodes through its own named decoder too.
  EXPECT_TRUE(decode_legacy_vision_wrapper(byte_span(hand.str())).ok());
}

// ---------------------------------------------------------------------------------------------------
// ssl_gc_common.proto, ssl_gc_geometry.proto

TEST(LeagueWireFormat, GcCommonAndGeometry) {
  RobotId id;
  id.set_id(5);
  id.set_team(YELLOW);
  HandEncoder hand_id;
  hand_id.varint(1, 5).varint(2, 1);
  EXPECT_EQ(expect_wire(id, hand_id).team(), YELLOW);

  Vector3 v;
  v.set_x(1.0F);
  v.set_y(-2.5F);
  v.set_z(0.125F);
  EXPECT_FLOAT_EQ(expect_wire(v, vec3(1.0F, -2.5F, 0.125F)).z(), 0.125F);

  Vector2 w;
  w.set_x(0.5F);
  w.set_y(-0.5F);
  EXPECT_FLOAT_EQ(expect_wire(w, vec2(0.5F, -0.5F)).y(), -0.5F);

  EXPECT_EQ(BLUE, 2);
  EXPECT_EQ(DIV_A, 1);
  EXPECT_EQ(DIV_B, 2);
  EXPECT_EQ(Vector2::descriptor()->full_name(), "Vector2");  // one Vector2, in the global namespace
}

// ---------------------------------------------------------------------------------------------------
// ssl_vision_detection_tracked.proto, ssl_vision_wrapper_tracked.proto

TEST(LeagueWireFormat, TrackerWrapperPacket) {
  TrackerWrapperPacket packet;
  packet.set_uuid("3f2a-77");
  packet.set_source_name("TIGERs");
  auto* frame = packet.mutable_tracked_frame();
  frame->set_frame_number(7);
  frame->set_timestamp(1700000000.5);
  auto* ball = frame->add_balls();
  ball->mutable_pos()->set_x(1.0F);
  ball->mutable_pos()->set_y(2.0F);
  ball->mutable_pos()->set_z(0.125F);
  ball->mutable_vel()->set_x(0.5F);
  ball->mutable_vel()->set_y(0.0F);
  ball->mutable_vel()->set_z(0.0F);
  ball->set_visibility(1.0F);
  auto* robot = frame->add_robots();
  robot->mutable_robot_id()->set_id(3);
  robot->mutable_robot_id()->set_team(BLUE);
  robot->mutable_pos()->set_x(-1.0F);
  robot->mutable_pos()->set_y(2.0F);
  robot->set_orientation(3.0F);
  robot->mutable_vel()->set_x(0.25F);
  robot->mutable_vel()->set_y(0.5F);
  robot->set_vel_angular(-0.5F);
  robot->set_visibility(0.75F);
  auto* kicked = frame->mutable_kicked_ball();
  kicked->mutable_pos()->set_x(0.0F);
  kicked->mutable_pos()->set_y(0.0F);
  kicked->mutable_vel()->set_x(4.0F);
  kicked->mutable_vel()->set_y(0.0F);
  kicked->mutable_vel()->set_z(1.0F);
  kicked->set_start_timestamp(1700000000.25);
  kicked->set_stop_timestamp(1700000002.0);
  kicked->mutable_stop_pos()->set_x(3.0F);
  kicked->mutable_stop_pos()->set_y(0.0F);
  kicked->mutable_robot_id()->set_id(3);
  kicked->mutable_robot_id()->set_team(BLUE);
  frame->add_capabilities(CAPABILITY_DETECT_FLYING_BALLS);
  frame->add_capabilities(CAPABILITY_DETECT_KICKED_BALLS);

  HandEncoder hand_robot_id;
  hand_robot_id.varint(1, 3).varint(2, 2);
  HandEncoder hand_ball;
  hand_ball.message(1, vec3(1.0F, 2.0F, 0.125F)).message(2, vec3(0.5F, 0.0F, 0.0F)).f32(3, 1.0F);
  HandEncoder hand_robot;
  hand_robot.message(1, hand_robot_id)
      .message(2, vec2(-1.0F, 2.0F))
      .f32(3, 3.0F)
      .message(4, vec2(0.25F, 0.5F));
  hand_robot.f32(5, -0.5F).f32(6, 0.75F);
  HandEncoder hand_kicked;
  hand_kicked.message(1, vec2(0.0F, 0.0F)).message(2, vec3(4.0F, 0.0F, 1.0F)).f64(3, 1700000000.25);
  hand_kicked.f64(4, 1700000002.0).message(5, vec2(3.0F, 0.0F)).message(6, hand_robot_id);
  HandEncoder hand_frame;
  hand_frame.varint(1, 7).f64(2, 1700000000.5).message(3, hand_ball).message(4, hand_robot);
  hand_frame.message(5, hand_kicked).varint(6, 1).varint(6, 3);  // proto2 repeated enum: not packed
  HandEncoder hand;
  hand.bytes(1, "3f2a-77").bytes(2, "TIGERs").message(3, hand_frame);

  const auto decoded = expect_wire(packet, hand);
  EXPECT_EQ(decoded.uuid(), "3f2a-77");
  EXPECT_EQ(decoded.tracked_frame().robots(0).robot_id().team(), BLUE);
  EXPECT_FLOAT_EQ(decoded.tracked_frame().balls(0).pos().z(), 0.125F);
  EXPECT_DOUBLE_EQ(decoded.tracked_frame().kicked_ball().start_timestamp(), 1700000000.25);
  ASSERT_EQ(decoded.tracked_frame().capabilities_size(), 2);
  EXPECT_EQ(decoded.tracked_frame().capabilities(1), CAPABILITY_DETECT_KICKED_BALLS);
  EXPECT_TRUE(decode_tracker_wrapper(byte_span(hand.str())).ok());
}

// ---------------------------------------------------------------------------------------------------
// ssl_gc_game_event.proto

enum class Payload { kNone, kByTeam, kByTeamAndReason, kByTeamAndAccepted };

struct EventRow {
  const char* oneof_name;  // the Type enum name is the same in upper case
  std::uint32_t field;     // oneof field number
  int type;                // GameEvent.Type value
  Payload payload;         // required fields of the payload message
};

// Every oneof member of GameEvent, from the reference table (section 8).
constexpr EventRow kEvents[] = {
    {"ball_left_field_touch_line", 6, 6, Payload::kByTeam},
    {"ball_left_field_goal_line", 7, 7, Payload::kByTeam},
    {"aimless_kick", 11, 11, Payload::kByTeam},
    {"attacker_too_close_to_defense_area", 19, 19, Payload::kByTeam},
    {"defender_in_defense_area", 31, 31, Payload::kByTeam},
    {"boundary_crossing", 43, 41, Payload::kByTeam},
    {"keeper_held_ball", 13, 13, Payload::kByTeam},
    {"bot_dribbled_ball_too_far", 17, 17, Payload::kByTeam},
    {"bot_pushed_bot", 24, 24, Payload::kByTeam},
    {"bot_held_ball_deliberately", 26, 26, Payload::kByTeam},
    {"bot_tipped_over", 27, 27, Payload::kByTeam},
    {"bot_dropped_parts", 51, 47, Payload::kByTeam},
    {"attacker_touched_ball_in_defense_area", 15, 15, Payload::kByTeam},
    {"bot_kicked_ball_too_fast", 18, 18, Payload::kByTeam},
    {"bot_crash_unique", 22, 22, Payload::kByTeam},
    {"bot_crash_drawn", 21, 21, Payload::kNone},
    {"defender_too_close_to_kick_point", 29, 29, Payload::kByTeam},
    {"bot_too_fast_in_stop", 28, 28, Payload::kByTeam},
    {"bot_interfered_placement", 20, 20, Payload::kByTeam},
    {"excessive_bot_substitution", 52, 48, Payload::kByTeam},
    {"possible_goal", 39, 39, Payload::kByTeam},
    {"goal", 8, 8, Payload::kByTeam},
    {"invalid_goal", 44, 42, Payload::kByTeam},
    {"attacker_double_touched_ball", 14, 14, Payload::kByTeam},
    {"placement_succeeded", 5, 5, Payload::kByTeam},
    {"penalty_kick_failed", 45, 43, Payload::kByTeam},
    {"no_progress_in_game", 2, 2, Payload::kNone},
    {"placement_failed", 3, 3, Payload::kByTeam},
    {"multiple_cards", 32, 32, Payload::kByTeam},
    {"multiple_fouls", 34, 34, Payload::kByTeam},
    {"bot_substitution", 37, 37, Payload::kByTeam},
    {"too_many_robots", 38, 38, Payload::kByTeam},
    {"challenge_flag", 46, 44, Payload::kByTeam},
    {"challenge_flag_handled", 48, 46, Payload::kByTeamAndAccepted},
    {"emergency_stop", 47, 45, Payload::kByTeam},
    {"unsporting_behavior_minor", 35, 35, Payload::kByTeamAndReason},
    {"unsporting_behavior_major", 36, 36, Payload::kByTeamAndReason},
    {"prepared", 1, 1, Payload::kNone},
    {"indirect_goal", 9, 9, Payload::kByTeam},
    {"chipped_goal", 10, 10, Payload::kByTeam},
    {"kick_timeout", 12, 12, Payload::kByTeam},
    {"attacker_touched_opponent_in_defense_area", 16, 16, Payload::kByTeam},
    {"attacker_touched_opponent_in_defense_area_skipped", 42, 40, Payload::kByTeam},
    {"bot_crash_unique_skipped", 23, 23, Payload::kByTeam},
    {"bot_pushed_bot_skipped", 25, 25, Payload::kByTeam},
    {"defender_in_defense_area_partially", 30, 30, Payload::kByTeam},
    {"multiple_placement_failures", 33, 33, Payload::kByTeam},
};

std::string upper(std::string text) {
  for (char& c : text) {
    if (c >= 'a' && c <= 'z') {
      c = static_cast<char>(c - 'a' + 'A');
    }
  }
  return text;
}

TEST(LeagueWireFormat, EveryGameEventOneofNumberAndTypeValue) {
  const auto* descriptor = GameEvent::descriptor();
  const auto* oneof = descriptor->FindOneofByName("event");
  ASSERT_NE(oneof, nullptr);
  EXPECT_EQ(oneof->field_count(), static_cast<int>(std::size(kEvents)));  // nothing missing, nothing extra

  for (const EventRow& row : kEvents) {
    SCOPED_TRACE(row.oneof_name);
    const auto* field = descriptor->FindFieldByName(row.oneof_name);
    ASSERT_NE(field, nullptr);
    EXPECT_EQ(field->number(), static_cast<int>(row.field));
    EXPECT_EQ(field->containing_oneof(), oneof);
    const auto* type_value = GameEvent::Type_descriptor()->FindValueByName(upper(row.oneof_name));
    ASSERT_NE(type_value, nullptr);
    ASSERT_EQ(type_value->number(), row.type);

    // Build the event through reflection (type + payload with its required fields set)...
    GameEvent event;
    event.set_type(static_cast<GameEvent::Type>(row.type));
    auto* payload = event.GetReflection()->MutableMessage(&event, field);
    const auto* payload_reflection = payload->GetReflection();
    const auto* payload_descriptor = payload->GetDescriptor();
    HandEncoder hand_payload;
    if (row.payload != Payload::kNone) {
      const auto* by_team = payload_descriptor->FindFieldByName("by_team");
      ASSERT_NE(by_team, nullptr);
      ASSERT_EQ(by_team->number(), 1);
      ASSERT_TRUE(by_team->is_required());
      payload_reflection->SetEnumValue(payload, by_team, BLUE);
      hand_payload.varint(1, 2);
    }
    if (row.payload == Payload::kByTeamAndReason) {
      payload_reflection->SetString(payload, payload_descriptor->FindFieldByNumber(2), "pushing");
      hand_payload.bytes(2, "pushing");
    }
    if (row.payload == Payload::kByTeamAndAccepted) {
      payload_reflection->SetBool(payload, payload_descriptor->FindFieldByNumber(2), true);
      hand_payload.varint(2, 1);
    }
    // ...and by hand: fields in number order, type is 40.
    HandEncoder hand;
    if (row.field < 40) {
      hand.message(row.field, hand_payload).varint(40, static_cast<std::uint64_t>(row.type));
    } else {
      hand.varint(40, static_cast<std::uint64_t>(row.type)).message(row.field, hand_payload);
    }

    const auto decoded = expect_wire(event, hand);
    EXPECT_EQ(static_cast<std::uint32_t>(decoded.event_case()), row.field);
    EXPECT_EQ(static_cast<int>(decoded.type()), row.type);
    EXPECT_TRUE(decoded.GetReflection()->HasField(decoded, field));
  }
}

TEST(LeagueWireFormat, GameEventGoalWithAllFields) {
  GameEvent event;
  event.set_id("a1b2");
  event.set_type(GameEvent::INVALID_GOAL);
  event.add_origin("TIGERs AutoRef");
  event.add_origin("ER-Force");
  event.set_created_timestamp(1700000000123456ULL);
  auto* goal = event.mutable_invalid_goal();
  goal->set_by_team(YELLOW);
  goal->set_kicking_team(BLUE);
  goal->set_kicking_bot(4);
  goal->mutable_location()->set_x(6.0F);
  goal->mutable_location()->set_y(0.25F);
  goal->mutable_kick_location()->set_x(-1.0F);
  goal->mutable_kick_location()->set_y(0.5F);
  goal->set_max_ball_height(0.2F);
  goal->set_num_robots_by_team(12);
  goal->set_last_touch_by_team(1699999999000000ULL);
  goal->set_message("too many robots");

  HandEncoder hand_goal;
  hand_goal.varint(1, 1).varint(2, 4).message(3, vec2(6.0F, 0.25F)).message(4, vec2(-1.0F, 0.5F));
  hand_goal.f32(5, 0.2F)
      .varint(6, 2)
      .varint(7, 12)
      .varint(8, 1699999999000000ULL)
      .bytes(9, "too many robots");
  HandEncoder hand;
  hand.varint(40, 42).bytes(41, "TIGERs AutoRef").bytes(41, "ER-Force").message(44, hand_goal);
  hand.varint(49, 1700000000123456ULL).bytes(50, "a1b2");

  const auto decoded = expect_wire(event, hand);
  EXPECT_EQ(decoded.event_case(), GameEvent::kInvalidGoal);
  EXPECT_EQ(decoded.invalid_goal().kicking_team(), BLUE);
  EXPECT_EQ(decoded.invalid_goal().last_touch_by_team(), 1699999999000000ULL);
  EXPECT_EQ(decoded.origin_size(), 2);
  EXPECT_EQ(decoded.id(), "a1b2");
}

TEST(LeagueWireFormat, GameEventMultipleFoulsNestsEvents) {
  GameEvent event;
  event.set_type(GameEvent::MULTIPLE_FOULS);
  auto* fouls = event.mutable_multiple_fouls();
  fouls->set_by_team(BLUE);
  auto* cause = fouls->add_caused_game_events();
  cause->set_type(GameEvent::BOT_CRASH_DRAWN);
  auto* crash = cause->mutable_bot_crash_drawn();
  crash->set_bot_yellow(1);
  crash->set_bot_blue(2);
  crash->set_crash_speed(2.5F);
  crash->set_speed_diff(0.1F);
  crash->set_crash_angle(3.0F);

  HandEncoder hand_crash;
  hand_crash.varint(1, 1).varint(2, 2).f32(4, 2.5F).f32(5, 0.1F).f32(6, 3.0F);
  HandEncoder hand_cause;
  hand_cause.message(21, hand_crash).varint(40, 21);
  HandEncoder hand_fouls;
  hand_fouls.varint(1, 2).message(2, hand_cause);
  HandEncoder hand;
  hand.message(34, hand_fouls).varint(40, 34);

  const auto decoded = expect_wire(event, hand);
  ASSERT_EQ(decoded.multiple_fouls().caused_game_events_size(), 1);
  EXPECT_EQ(decoded.multiple_fouls().caused_game_events(0).bot_crash_drawn().bot_blue(), 2U);
}

// ---------------------------------------------------------------------------------------------------
// ssl_gc_referee_message.proto

TEST(LeagueWireFormat, RefereeEveryTrap) {
  Referee referee;
  referee.set_packet_timestamp(1700000000000000ULL);
  referee.set_stage(Referee::NORMAL_FIRST_HALF);
  referee.set_stage_time_left(-3000000000LL);  // beyond 32 bits: sint64, zigzag
  referee.set_command(Referee::BALL_PLACEMENT_YELLOW);
  referee.set_command_counter(12);
  referee.set_command_timestamp(1699999999000000ULL);
  auto* yellow = referee.mutable_yellow();
  yellow->set_name("ER-Force");
  yellow->set_score(3);
  yellow->set_red_cards(0);
  yellow->add_yellow_card_times(45000000);
  yellow->add_yellow_card_times(120000000);
  yellow->set_yellow_cards(2);
  yellow->set_timeouts(4);
  yellow->set_timeout_time(300000000);
  yellow->set_goalkeeper(1);
  yellow->set_foul_counter(2);
  yellow->set_ball_placement_failures(1);
  yellow->set_can_place_ball(true);
  yellow->set_max_allowed_bots(10);
  yellow->set_bot_substitution_intent(true);
  yellow->set_ball_placement_failures_reached(false);
  yellow->set_bot_substitution_allowed(true);
  yellow->set_bot_substitutions_left(4);
  yellow->set_bot_substitution_time_left(15000000);
  yellow->set_hull_color(HULL_COLOR_DARK);
  auto* blue = referee.mutable_blue();
  blue->set_name("TIGERs Mannheim");
  blue->set_score(1);
  blue->set_red_cards(1);
  blue->set_yellow_cards(0);
  blue->set_timeouts(4);
  blue->set_timeout_time(300000000);
  blue->set_goalkeeper(0);
  blue->set_hull_color(HULL_COLOR_LIGHT);
  referee.mutable_designated_position()->set_x(-1500.0F);  // mm
  referee.mutable_designated_position()->set_y(2250.5F);
  referee.set_blue_team_on_positive_half(true);
  referee.set_next_command(Referee::DIRECT_FREE_YELLOW);
  referee.set_current_action_time_remaining(-250000);  // int64: ten-byte varint
  auto* event = referee.add_game_events();
  event->set_type(GameEvent::BOUNDARY_CROSSING);
  event->mutable_boundary_crossing()->set_by_team(YELLOW);
  event->mutable_boundary_crossing()->mutable_location()->set_x(6.25F);  // m
  event->mutable_boundary_crossing()->mutable_location()->set_y(-1.0F);
  auto* proposal = referee.add_game_event_proposals();
  proposal->set_id("group-1");
  *proposal->add_game_events() = *event;
  proposal->set_accepted(true);
  referee.set_source_identifier("5d9c-uuid");
  referee.set_match_type(ELIMINATION_PHASE);
  referee.set_status_message("Ball placement by yellow");

  HandEncoder hand_yellow;
  hand_yellow.bytes(1, "ER-Force").varint(2, 3).varint(3, 0).packed_varints(4, {45000000, 120000000});
  hand_yellow.varint(5, 2).varint(6, 4).varint(7, 300000000).varint(8, 1).varint(9, 2).varint(10, 1);
  hand_yellow.varint(12, 1).varint(13, 10).varint(14, 1).varint(15, 0).varint(16, 1).varint(17, 4);
  hand_yellow.varint(18, 15000000).varint(19, 1);
  HandEncoder hand_blue;
  hand_blue.bytes(1, "TIGERs Mannheim")
      .varint(2, 1)
      .varint(3, 1)
      .varint(5, 0)
      .varint(6, 4)
      .varint(7, 300000000);
  hand_blue.varint(8, 0).varint(19, 2);
  HandEncoder hand_crossing;
  hand_crossing.varint(1, 1).message(2, vec2(6.25F, -1.0F));
  HandEncoder hand_event;
  hand_event.varint(40, 41).message(43, hand_crossing);
  HandEncoder hand_proposal;
  hand_proposal.message(1, hand_event).varint(2, 1).bytes(3, "group-1");
  HandEncoder hand;
  hand.varint(1, 1700000000000000ULL).varint(2, 1).sint(3, -3000000000LL).varint(4, 16).varint(5, 12);
  hand.varint(6, 1699999999000000ULL).message(7, hand_yellow).message(8, hand_blue);
  hand.message(9, vec2(-1500.0F, 2250.5F)).varint(10, 1).varint(12, 8).int64(15, -250000);
  hand.message(16, hand_event).message(17, hand_proposal).bytes(18, "5d9c-uuid").varint(19, 2);
  hand.bytes(20, "Ball placement by yellow");

  // Spot checks of the traps on the raw bytes: zigzag 64-bit stage time, packed card times.
  EXPECT_NE(hand.str().find(HandEncoder().varint(3, 5999999999ULL).str()), std::string::npos);
  EXPECT_NE(hand_yellow.str().find(std::string("\x22\x08", 2)), std::string::npos);

  const auto decoded = expect_wire(referee, hand);
  EXPECT_EQ(decoded.stage_time_left(), -3000000000LL);
  EXPECT_EQ(decoded.current_action_time_remaining(), -250000);
  EXPECT_FLOAT_EQ(decoded.designated_position().x(), -1500.0F);
  ASSERT_EQ(decoded.yellow().yellow_card_times_size(), 2);
  EXPECT_EQ(decoded.yellow().yellow_card_times(1), 120000000U);
  EXPECT_TRUE(decoded.yellow().can_place_ball());
  EXPECT_EQ(decoded.yellow().max_allowed_bots(), 10U);
  EXPECT_EQ(decoded.yellow().bot_substitutions_left(), 4U);
  EXPECT_EQ(decoded.yellow().bot_substitution_time_left(), 15000000U);
  EXPECT_EQ(decoded.yellow().hull_color(), HULL_COLOR_DARK);
  EXPECT_EQ(decoded.blue().hull_color(), HULL_COLOR_LIGHT);
  EXPECT_EQ(decoded.game_events(0).event_case(), GameEvent::kBoundaryCrossing);
  EXPECT_EQ(decoded.game_event_proposals(0).id(), "group-1");
  EXPECT_EQ(decoded.match_type(), ELIMINATION_PHASE);
  EXPECT_EQ(decoded.status_message(), "Ball placement by yellow");
  EXPECT_TRUE(decode_referee(byte_span(hand.str())).ok());
  EXPECT_EQ(Referee::POST_GAME, 13);
  EXPECT_EQ(Referee::BALL_PLACEMENT_BLUE, 17);
  EXPECT_EQ(FRIENDLY, 3);
}

// ---------------------------------------------------------------------------------------------------
// ssl_gc_rcon.proto, ssl_gc_rcon_team.proto, ssl_gc_rcon_autoref.proto

TEST(LeagueWireFormat, GcRemoteControlCommon) {
  ControllerReply reply;
  reply.set_status_code(ControllerReply::REJECTED);
  reply.set_reason("unknown team");
  reply.set_next_token("tok-9");
  reply.set_verification(ControllerReply::UNVERIFIED);
  HandEncoder hand_reply;
  hand_reply.varint(1, 2).bytes(2, "unknown team").bytes(3, "tok-9").varint(4, 2);
  EXPECT_EQ(expect_wire(reply, hand_reply).verification(), ControllerReply::UNVERIFIED);

  Signature signature;
  signature.set_token("tok-8");
  signature.set_pkcs1v15(std::string("\x00\xff\x10", 3));
  HandEncoder hand_signature;
  hand_signature.bytes(1, "tok-8").bytes(2, std::string("\x00\xff\x10", 3));
  EXPECT_EQ(expect_wire(signature, hand_signature).pkcs1v15().size(), 3U);
}

TEST(LeagueWireFormat, GcTeamProtocol) {
  TeamRegistration registration;
  registration.set_team_name("ER-Force");
  registration.mutable_signature()->set_token("t");
  registration.mutable_signature()->set_pkcs1v15("s");
  registration.set_team(BLUE);
  HandEncoder hand_signature;
  hand_signature.bytes(1, "t").bytes(2, "s");
  HandEncoder hand_registration;
  hand_registration.bytes(1, "ER-Force").message(2, hand_signature).varint(3, 2);
  EXPECT_EQ(expect_wire(registration, hand_registration).team(), BLUE);

  TeamToController advantage;
  *advantage.mutable_signature() = registration.signature();
  advantage.set_advantage_choice(CONTINUE);
  HandEncoder hand_advantage;
  hand_advantage.message(1, hand_signature).varint(3, 1);
  EXPECT_EQ(expect_wire(advantage, hand_advantage).msg_case(), TeamToController::kAdvantageChoice);

  TeamToController keeper;
  keeper.set_desired_keeper(5);
  HandEncoder hand_keeper;
  hand_keeper.varint(2, 5);
  EXPECT_EQ(expect_wire(keeper, hand_keeper).desired_keeper(), 5);

  TeamToController substitute;
  substitute.set_substitute_bot(true);
  HandEncoder hand_substitute;
  hand_substitute.varint(4, 1);
  EXPECT_TRUE(expect_wire(substitute, hand_substitute).substitute_bot());

  ControllerToTeam answer;
  answer.mutable_controller_reply()->set_status_code(ControllerReply::OK);
  HandEncoder hand_status;
  hand_status.varint(1, 1);
  HandEncoder hand_answer;
  hand_answer.message(1, hand_status);
  EXPECT_EQ(expect_wire(answer, hand_answer).controller_reply().status_code(), ControllerReply::OK);
}

TEST(LeagueWireFormat, GcAutoRefProtocol) {
  AutoRefRegistration registration;
  registration.set_identifier("TIGERs AutoRef");
  HandEncoder hand_registration;
  hand_registration.bytes(1, "TIGERs AutoRef");
  EXPECT_EQ(expect_wire(registration, hand_registration).identifier(), "TIGERs AutoRef");

  AutoRefToController proposal;
  proposal.mutable_game_event()->set_type(GameEvent::BOT_DROPPED_PARTS);
  proposal.mutable_game_event()->mutable_bot_dropped_parts()->set_by_team(YELLOW);
  proposal.mutable_game_event()->mutable_bot_dropped_parts()->set_by_bot(9);
  HandEncoder hand_dropped;
  hand_dropped.varint(1, 1).varint(2, 9);
  HandEncoder hand_event;
  hand_event.varint(40, 47).message(51, hand_dropped);
  HandEncoder hand_proposal;
  hand_proposal.message(2, hand_event);
  EXPECT_EQ(expect_wire(proposal, hand_proposal).game_event().bot_dropped_parts().by_bot(), 9U);

  ControllerToAutoRef answer;
  answer.mutable_controller_reply()->set_next_token("n");
  HandEncoder hand_reply;
  hand_reply.bytes(3, "n");
  HandEncoder hand_answer;
  hand_answer.message(1, hand_reply);
  EXPECT_EQ(expect_wire(answer, hand_answer).controller_reply().next_token(), "n");
}

// ---------------------------------------------------------------------------------------------------
// ssl_gc_ci.proto

TEST(LeagueWireFormat, GcCiInputAndOutput) {
  CiInput input;
  input.set_timestamp(1700000000123456789LL);  // ns
  input.mutable_tracker_packet()->set_uuid("u");
  input.add_api_inputs(std::string("\x10\x01", 2));
  *input.mutable_geometry()->mutable_field() = minimal_field();
  HandEncoder hand_tracker;
  hand_tracker.bytes(1, "u");
  HandEncoder hand_geometry;
  hand_geometry.message(1, hand_minimal_field());
  HandEncoder hand_input;
  hand_input.varint(1, 1700000000123456789ULL).message(2, hand_tracker).bytes(3, std::string("\x10\x01", 2));
  hand_input.message(4, hand_geometry);
  EXPECT_EQ(expect_wire(input, hand_input).timestamp(), 1700000000123456789LL);

  CiOutput output;
  auto* referee = output.mutable_referee_msg();
  referee->set_packet_timestamp(1);
  referee->set_stage(Referee::NORMAL_FIRST_HALF_PRE);
  referee->set_command(Referee::HALT);
  referee->set_command_counter(0);
  referee->set_command_timestamp(0);
  for (auto* team : {referee->mutable_yellow(), referee->mutable_blue()}) {
    team->set_name("");
    team->set_score(0);
    team->set_red_cards(0);
    team->set_yellow_cards(0);
    team->set_timeouts(4);
    team->set_timeout_time(300000000);
    team->set_goalkeeper(0);
  }
  HandEncoder hand_team;
  hand_team.bytes(1, "")
      .varint(2, 0)
      .varint(3, 0)
      .varint(5, 0)
      .varint(6, 4)
      .varint(7, 300000000)
      .varint(8, 0);
  HandEncoder hand_referee;
  hand_referee.varint(1, 1)
      .varint(2, 0)
      .varint(4, 0)
      .varint(5, 0)
      .varint(6, 0)
      .message(7, hand_team)
      .message(8, hand_team);
  HandEncoder hand_output;
  hand_output.message(1, hand_referee);
  EXPECT_EQ(expect_wire(output, hand_output).referee_msg().blue().timeouts(), 4U);
}

// ---------------------------------------------------------------------------------------------------
// ssl_simulation_robot_control.proto

TEST(LeagueWireFormat, SimulationRobotControl) {
  RobotControl control;
  auto* kicker = control.add_robot_commands();
  kicker->set_id(3);
  auto* local = kicker->mutable_move_command()->mutable_local_velocity();
  local->set_forward(1.5F);
  local->set_left(-0.5F);
  local->set_angular(2.0F);
  kicker->set_kick_speed(6.0F);
  kicker->set_kick_angle(45.0F);        // degrees: a chip
  kicker->set_dribbler_speed(1000.0F);  // rpm
  auto* wheels = control.add_robot_commands();
  wheels->set_id(4);
  auto* wheel = wheels->mutable_move_command()->mutable_wheel_velocity();
  wheel->set_front_right(1.0F);
  wheel->set_back_right(2.0F);
  wheel->set_back_left(3.0F);
  wheel->set_front_left(4.0F);
  auto* global = control.add_robot_commands();
  global->set_id(5);
  auto* velocity = global->mutable_move_command()->mutable_global_velocity();
  velocity->set_x(0.5F);
  velocity->set_y(-0.5F);
  velocity->set_angular(1.0F);

  HandEncoder hand_local;
  hand_local.message(2, vec3(1.5F, -0.5F, 2.0F));
  HandEncoder hand_kicker;
  hand_kicker.varint(1, 3).message(2, hand_local).f32(3, 6.0F).f32(4, 45.0F).f32(5, 1000.0F);
  HandEncoder hand_wheel_values;
  hand_wheel_values.f32(1, 1.0F).f32(2, 2.0F).f32(3, 3.0F).f32(4, 4.0F);
  HandEncoder hand_wheel;
  hand_wheel.message(1, hand_wheel_values);
  HandEncoder hand_wheels;
  hand_wheels.varint(1, 4).message(2, hand_wheel);
  HandEncoder hand_global_move;
  hand_global_move.message(3, vec3(0.5F, -0.5F, 1.0F));
  HandEncoder hand_global;
  hand_global.varint(1, 5).message(2, hand_global_move);
  HandEncoder hand;
  hand.message(1, hand_kicker).message(1, hand_wheels).message(1, hand_global);

  const auto decoded = expect_wire(control, hand);
  ASSERT_EQ(decoded.robot_commands_size(), 3);
  EXPECT_FLOAT_EQ(decoded.robot_commands(0).kick_angle(), 45.0F);
  EXPECT_FLOAT_EQ(decoded.robot_commands(0).dribbler_speed(), 1000.0F);
  EXPECT_EQ(decoded.robot_commands(1).move_command().command_case(), RobotMoveCommand::kWheelVelocity);
  EXPECT_FLOAT_EQ(decoded.robot_commands(2).move_command().global_velocity().y(), -0.5F);
  EXPECT_TRUE(decode_robot_control(byte_span(hand.str())).ok());
}

// ---------------------------------------------------------------------------------------------------
// ssl_simulation_error.proto, ssl_simulation_robot_feedback.proto

TEST(LeagueWireFormat, SimulationErrorAndRobotFeedback) {
  SimulatorError error;
  error.set_code("UNSUPPORTED_CHIP");
  error.set_message("chip kicks are not supported");
  HandEncoder hand_error;
  hand_error.bytes(1, "UNSUPPORTED_CHIP").bytes(2, "chip kicks are not supported");
  EXPECT_EQ(expect_wire(error, hand_error).code(), "UNSUPPORTED_CHIP");

  RobotControlResponse response;
  *response.add_errors() = error;
  auto* feedback = response.add_feedback();
  feedback->set_id(3);
  feedback->set_dribbler_ball_contact(true);
  RobotSpecErForce custom;
  custom.set_shoot_radius(0.0715F);
  feedback->mutable_custom()->PackFrom(custom);
  EXPECT_EQ(feedback->custom().type_url(), "type.googleapis.com/RobotSpecErForce");

  HandEncoder hand_custom_value;
  hand_custom_value.f32(1, 0.0715F);
  HandEncoder hand_any;
  hand_any.bytes(1, "type.googleapis.com/RobotSpecErForce").bytes(2, hand_custom_value.str());
  HandEncoder hand_feedback;
  hand_feedback.varint(1, 3).varint(2, 1).message(3, hand_any);
  HandEncoder hand;
  hand.message(1, hand_error).message(2, hand_feedback);

  const auto decoded = expect_wire(response, hand);
  ASSERT_EQ(decoded.feedback_size(), 1);
  EXPECT_TRUE(decoded.feedback(0).dribbler_ball_contact());
  RobotSpecErForce unpacked;
  ASSERT_TRUE(decoded.feedback(0).custom().UnpackTo(&unpacked));
  EXPECT_FLOAT_EQ(unpacked.shoot_radius(), 0.0715F);
  EXPECT_TRUE(decode_robot_control_response(byte_span(hand.str())).ok());
}

// ---------------------------------------------------------------------------------------------------
// ssl_simulation_config.proto, ssl_simulation_custom_erforce_*.proto

TEST(LeagueWireFormat, SimulationConfigWithErForceCustomMessages) {
  SimulatorCommand command;
  auto* config = command.mutable_config();
  *config->mutable_geometry()->mutable_field() = minimal_field();
  auto* specs = config->add_robot_specs();
  specs->mutable_id()->set_id(3);
  specs->mutable_id()->set_team(YELLOW);
  specs->set_radius(0.09F);
  specs->set_height(0.143F);
  specs->set_mass(2.7F);
  specs->set_max_linear_kick_speed(6.0F);
  specs->set_max_chip_kick_speed(6.0F);
  specs->set_center_to_dribbler(0.078F);
  auto* limits = specs->mutable_limits();
  limits->set_acc_speedup_absolute_max(2.0F);
  limits->set_acc_speedup_angular_max(20.0F);
  limits->set_acc_brake_absolute_max(2.0F);
  limits->set_acc_brake_angular_max(20.0F);
  limits->set_vel_absolute_max(2.0F);
  limits->set_vel_angular_max(5.0F);
  auto* angles = specs->mutable_wheel_angles();
  angles->set_front_right(1.0F);
  angles->set_back_right(2.5F);
  angles->set_back_left(3.75F);
  angles->set_front_left(5.25F);
  RobotSpecErForce robot_custom;
  robot_custom.set_shoot_radius(0.0715F);
  robot_custom.set_dribbler_width(0.065F);
  specs->add_custom()->PackFrom(robot_custom);
  RealismConfigErForce realism;
  realism.set_stddev_ball_p(0.0014F);
  realism.set_enable_invisible_ball(true);
  realism.set_vision_delay(35000000);
  config->mutable_realism_config()->add_custom()->PackFrom(realism);
  config->set_vision_port(10020);

  HandEncoder hand_robot_custom;
  hand_robot_custom.f32(1, 0.0715F).f32(3, 0.065F);  // field 2 is reserved
  HandEncoder hand_robot_any;
  hand_robot_any.bytes(1, "type.googleapis.com/RobotSpecErForce").bytes(2, hand_robot_custom.str());
  HandEncoder hand_realism_custom;
  hand_realism_custom.f32(1, 0.0014F).varint(5, 1).varint(13, 35000000);
  HandEncoder hand_realism_any;
  hand_realism_any.bytes(1, "type.googleapis.com/RealismConfigErForce").bytes(2, hand_realism_custom.str());
  HandEncoder hand_id;
  hand_id.varint(1, 3).varint(2, 1);
  HandEncoder hand_limits;
  hand_limits.f32(1, 2.0F).f32(2, 20.0F).f32(3, 2.0F).f32(4, 20.0F).f32(5, 2.0F).f32(6, 5.0F);
  HandEncoder hand_angles;
  hand_angles.f32(1, 1.0F).f32(2, 2.5F).f32(3, 3.75F).f32(4, 5.25F);
  HandEncoder hand_specs;
  hand_specs.message(1, hand_id)
      .f32(2, 0.09F)
      .f32(3, 0.143F)
      .f32(4, 2.7F)
      .f32(7, 6.0F)
      .f32(8, 6.0F)
      .f32(9, 0.078F);
  hand_specs.message(10, hand_limits).message(13, hand_angles).message(14, hand_robot_any);
  HandEncoder hand_geometry;
  hand_geometry.message(1, hand_minimal_field());
  HandEncoder hand_realism;
  hand_realism.message(1, hand_realism_any);
  HandEncoder hand_config;
  hand_config.message(1, hand_geometry).message(2, hand_specs).message(3, hand_realism).varint(4, 10020);
  HandEncoder hand;
  hand.message(2, hand_config);

  const auto decoded = expect_wire(command, hand);
  EXPECT_EQ(decoded.config().vision_port(), 10020U);
  EXPECT_FLOAT_EQ(decoded.config().robot_specs(0).center_to_dribbler(), 0.078F);
  EXPECT_FLOAT_EQ(decoded.config().robot_specs(0).wheel_angles().front_left(), 5.25F);
  RealismConfigErForce realism_back;
  ASSERT_TRUE(decoded.config().realism_config().custom(0).UnpackTo(&realism_back));
  EXPECT_EQ(realism_back.vision_delay(), 35000000);
  EXPECT_TRUE(realism_back.enable_invisible_ball());
  RobotSpecErForce robot_back;
  ASSERT_TRUE(decoded.config().robot_specs(0).custom(0).UnpackTo(&robot_back));
  EXPECT_FLOAT_EQ(robot_back.dribbler_width(), 0.065F);
  // Defaults of unset fields come from the tables.
  EXPECT_FLOAT_EQ(RobotSpecs().radius(), 0.09F);
  EXPECT_FLOAT_EQ(RobotSpecs().height(), 0.15F);
}

TEST(LeagueWireFormat, ErForceRealismAllFields) {
  RealismConfigErForce realism;
  realism.set_stddev_ball_p(0.1F);
  realism.set_stddev_robot_p(0.2F);
  realism.set_stddev_robot_phi(0.3F);
  realism.set_stddev_ball_area(6.5F);
  realism.set_enable_invisible_ball(true);
  realism.set_ball_visibility_threshold(0.4F);
  realism.set_camera_overlap(1.0F);
  realism.set_dribbler_ball_detections(0.03F);
  realism.set_camera_position_error(0.1F);
  realism.set_robot_command_loss(0.03F);
  realism.set_robot_response_loss(0.1F);
  realism.set_missing_ball_detections(0.05F);
  realism.set_vision_delay(35000000);
  realism.set_vision_processing_time(10000000);
  realism.set_simulate_dribbling(false);
  HandEncoder hand;
  hand.f32(1, 0.1F).f32(2, 0.2F).f32(3, 0.3F).f32(4, 6.5F).varint(5, 1).f32(6, 0.4F).f32(7, 1.0F);
  hand.f32(8, 0.03F).f32(9, 0.1F).f32(10, 0.03F).f32(11, 0.1F).f32(12, 0.05F).varint(13, 35000000);
  hand.varint(14, 10000000).varint(15, 0);
  const auto decoded = expect_wire(realism, hand);
  EXPECT_EQ(decoded.vision_processing_time(), 10000000);
  EXPECT_TRUE(decoded.has_simulate_dribbling());
}

// ---------------------------------------------------------------------------------------------------
// ssl_simulation_control.proto

TEST(LeagueWireFormat, SimulationControlTeleports) {
  SimulatorCommand command;
  auto* control = command.mutable_control();
  auto* ball = control->mutable_teleport_ball();
  ball->set_x(1.0F);
  ball->set_y(2.0F);
  ball->set_z(0.0F);
  ball->set_vx(0.5F);
  ball->set_vy(-0.5F);
  ball->set_vz(0.0F);
  ball->set_teleport_safely(true);
  ball->set_roll(true);
  ball->set_by_force(true);
  auto* robot = control->add_teleport_robot();
  robot->mutable_id()->set_id(2);
  robot->mutable_id()->set_team(BLUE);
  robot->set_x(-3.0F);
  robot->set_y(1.5F);
  robot->set_orientation(3.0F);
  robot->set_v_x(0.0F);
  robot->set_v_y(0.0F);
  robot->set_v_angular(0.0F);
  robot->set_present(true);
  robot->set_by_force(false);
  control->set_simulation_speed(2.0F);

  HandEncoder hand_ball;
  hand_ball.f32(1, 1.0F).f32(2, 2.0F).f32(3, 0.0F).f32(4, 0.5F).f32(5, -0.5F).f32(6, 0.0F);
  hand_ball.varint(7, 1).varint(8, 1).varint(9, 1);
  HandEncoder hand_id;
  hand_id.varint(1, 2).varint(2, 2);
  HandEncoder hand_robot;
  hand_robot.message(1, hand_id)
      .f32(2, -3.0F)
      .f32(3, 1.5F)
      .f32(4, 3.0F)
      .f32(5, 0.0F)
      .f32(6, 0.0F)
      .f32(7, 0.0F);
  hand_robot.varint(8, 1).varint(9, 0);
  HandEncoder hand_control;
  hand_control.message(1, hand_ball).message(2, hand_robot).f32(3, 2.0F);
  HandEncoder hand;
  hand.message(1, hand_control);

  const auto decoded = expect_wire(command, hand);
  EXPECT_TRUE(decoded.control().teleport_ball().by_force());
  EXPECT_TRUE(decoded.control().teleport_robot(0).has_by_force());
  EXPECT_FALSE(decoded.control().teleport_robot(0).by_force());
  EXPECT_FLOAT_EQ(decoded.control().simulation_speed(), 2.0F);
  EXPECT_TRUE(decode_simulator_command(byte_span(hand.str())).ok());

  SimulatorResponse response;
  response.add_errors()->set_code("E1");
  HandEncoder hand_error;
  hand_error.bytes(1, "E1");
  HandEncoder hand_response;
  hand_response.message(1, hand_error);
  EXPECT_EQ(expect_wire(response, hand_response).errors(0).code(), "E1");
  EXPECT_TRUE(decode_simulator_response(byte_span(hand_response.str())).ok());
}

// ---------------------------------------------------------------------------------------------------
// ssl_simulation_synchronous.proto

TEST(LeagueWireFormat, SimulationSynchronous) {
  SimulationSyncRequest request;
  request.set_sim_step(0.015625F);
  request.mutable_simulator_command()->mutable_control()->set_simulation_speed(1.0F);
  request.mutable_robot_control()->add_robot_commands()->set_id(1);
  HandEncoder hand_control;
  hand_control.f32(3, 1.0F);
  HandEncoder hand_command;
  hand_command.message(1, hand_control);
  HandEncoder hand_robot;
  hand_robot.varint(1, 1);
  HandEncoder hand_robot_control;
  hand_robot_control.message(1, hand_robot);
  HandEncoder hand_request;
  hand_request.f32(1, 0.015625F).message(2, hand_command).message(3, hand_robot_control);
  EXPECT_FLOAT_EQ(expect_wire(request, hand_request).sim_step(), 0.015625F);

  SimulationSyncResponse response;
  auto* frame = response.add_detection();
  frame->set_frame_number(9);
  frame->set_t_capture(1.0);
  frame->set_t_sent(1.0);
  frame->set_camera_id(1);
  response.mutable_robot_control_response()->add_feedback()->set_id(1);
  HandEncoder hand_frame;
  hand_frame.varint(1, 9).f64(2, 1.0).f64(3, 1.0).varint(4, 1);
  HandEncoder hand_feedback;
  hand_feedback.varint(1, 1);
  HandEncoder hand_feedback_response;
  hand_feedback_response.message(2, hand_feedback);
  HandEncoder hand_response;
  hand_response.message(1, hand_frame).message(2, hand_feedback_response);
  EXPECT_EQ(expect_wire(response, hand_response).detection(0).frame_number(), 9U);
}

// ---------------------------------------------------------------------------------------------------
// grsim_commands.proto, grsim_replacement.proto, grsim_packet.proto, grsim_robotstatus.proto

TEST(LeagueWireFormat, GrSimPacket) {
  grSim_Packet packet;
  auto* commands = packet.mutable_commands();
  commands->set_timestamp(12.5);
  commands->set_isteamyellow(true);
  auto* velocity = commands->add_robot_commands();
  velocity->set_id(2);
  velocity->set_kickspeedx(4.0F);
  velocity->set_kickspeedz(0.0F);
  velocity->set_veltangent(1.0F);
  velocity->set_velnormal(-0.5F);
  velocity->set_velangular(3.0F);
  velocity->set_spinner(true);
  velocity->set_wheelsspeed(false);
  auto* wheels = commands->add_robot_commands();
  wheels->set_id(3);
  wheels->set_kickspeedx(0.0F);
  wheels->set_kickspeedz(2.0F);
  wheels->set_veltangent(0.0F);
  wheels->set_velnormal(0.0F);
  wheels->set_velangular(0.0F);
  wheels->set_spinner(false);
  wheels->set_wheelsspeed(true);
  wheels->set_wheel1(10.0F);
  wheels->set_wheel2(-10.0F);
  wheels->set_wheel3(10.0F);
  wheels->set_wheel4(-10.0F);
  auto* replacement = packet.mutable_replacement();
  auto* ball = replacement->mutable_ball();
  ball->set_x(0.5);
  ball->set_y(-0.5);
  ball->set_vx(1.0);
  ball->set_vy(0.0);
  auto* robot = replacement->add_robots();
  robot->set_x(-2.0);
  robot->set_y(1.0);
  robot->set_dir(90.0);  // degrees
  robot->set_id(6);
  robot->set_yellowteam(false);
  robot->set_turnon(true);

  HandEncoder hand_velocity;
  hand_velocity.varint(1, 2)
      .f32(2, 4.0F)
      .f32(3, 0.0F)
      .f32(4, 1.0F)
      .f32(5, -0.5F)
      .f32(6, 3.0F)
      .varint(7, 1)
      .varint(8, 0);
  HandEncoder hand_wheels;
  hand_wheels.varint(1, 3)
      .f32(2, 0.0F)
      .f32(3, 2.0F)
      .f32(4, 0.0F)
      .f32(5, 0.0F)
      .f32(6, 0.0F)
      .varint(7, 0)
      .varint(8, 1);
  hand_wheels.f32(9, 10.0F).f32(10, -10.0F).f32(11, 10.0F).f32(12, -10.0F);
  HandEncoder hand_commands;
  hand_commands.f64(1, 12.5).varint(2, 1).message(3, hand_velocity).message(3, hand_wheels);
  HandEncoder hand_ball;
  hand_ball.f64(1, 0.5).f64(2, -0.5).f64(3, 1.0).f64(4, 0.0);
  HandEncoder hand_robot;
  hand_robot.f64(1, -2.0).f64(2, 1.0).f64(3, 90.0).varint(4, 6).varint(5, 0).varint(6, 1);
  HandEncoder hand_replacement;
  hand_replacement.message(1, hand_ball).message(2, hand_robot);
  HandEncoder hand;
  hand.message(1, hand_commands).message(2, hand_replacement);

  const auto decoded = expect_wire(packet, hand);
  EXPECT_TRUE(decoded.commands().isteamyellow());
  EXPECT_FLOAT_EQ(decoded.commands().robot_commands(1).wheel4(), -10.0F);
  EXPECT_DOUBLE_EQ(decoded.replacement().robots(0).dir(), 90.0);
  EXPECT_TRUE(decoded.replacement().robots(0).turnon());
  EXPECT_TRUE(decode_grsim_packet(byte_span(hand.str())).ok());
}

TEST(LeagueWireFormat, GrSimRobotsStatus) {
  Robots_Status status;
  auto* robot = status.add_robots_status();
  robot->set_robot_id(1);
  robot->set_infrared(true);
  robot->set_flat_kick(false);
  robot->set_chip_kick(true);
  HandEncoder hand_robot;
  hand_robot.varint(1, 1).varint(2, 1).varint(3, 0).varint(4, 1);
  HandEncoder hand;
  hand.message(1, hand_robot);
  const auto decoded = expect_wire(status, hand);
  EXPECT_TRUE(decoded.robots_status(0).chip_kick());
  EXPECT_TRUE(decode_grsim_robots_status(byte_span(hand.str())).ok());
}

}  // namespace
}  // namespace ssl::league
