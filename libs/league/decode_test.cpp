// The datagram decoders on bad input: every truncation of valid packets, seeded random bytes, mutated
// packets, oversized and deeply nested buffers give either a valid message or an error that names
// the type and the byte count; never a crash. Missing required fields are named.
#include "libs/league/decode.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "libs/league/testing/hand_encoder.h"

namespace ssl::league {
namespace {

using testing::HandEncoder;
using ::testing::HasSubstr;

// ---------------------------------------------------------------------------------------------------
// Valid sample packets, one per stream.

Referee::TeamInfo team(const std::string& name) {
  Referee::TeamInfo info;
  info.set_name(name);
  info.set_score(1);
  info.set_red_cards(0);
  info.add_yellow_card_times(60000000);
  info.set_yellow_cards(1);
  info.set_timeouts(4);
  info.set_timeout_time(300000000);
  info.set_goalkeeper(0);
  info.set_max_allowed_bots(11);
  return info;
}

Referee sample_referee() {
  Referee referee;
  referee.set_packet_timestamp(1700000000000000ULL);
  referee.set_stage(Referee::NORMAL_SECOND_HALF);
  referee.set_stage_time_left(120000000);
  referee.set_command(Referee::BALL_PLACEMENT_BLUE);
  referee.set_command_counter(7);
  referee.set_command_timestamp(1699999990000000ULL);
  *referee.mutable_yellow() = team("ER-Force");
  *referee.mutable_blue() = team("TIGERs Mannheim");
  referee.mutable_designated_position()->set_x(1000.0F);
  referee.mutable_designated_position()->set_y(-500.0F);
  auto* event = referee.add_game_events();
  event->set_type(GameEvent::BALL_LEFT_FIELD_TOUCH_LINE);
  event->mutable_ball_left_field_touch_line()->set_by_team(YELLOW);
  event->mutable_ball_left_field_touch_line()->mutable_location()->set_x(2.0F);
  event->mutable_ball_left_field_touch_line()->mutable_location()->set_y(4.5F);
  return referee;
}

SSL_WrapperPacket sample_vision() {
  SSL_WrapperPacket packet;
  auto* frame = packet.mutable_detection();
  frame->set_frame_number(100);
  frame->set_t_capture(1700000000.0);
  frame->set_t_sent(1700000000.01);
  frame->set_camera_id(1);
  auto* ball = frame->add_balls();
  ball->set_confidence(0.9F);
  ball->set_x(100.0F);
  ball->set_y(200.0F);
  ball->set_pixel_x(10.0F);
  ball->set_pixel_y(20.0F);
  for (std::uint32_t id = 0; id < 3; ++id) {
    auto* robot = frame->add_robots_blue();
    robot->set_confidence(1.0F);
    robot->set_robot_id(id);
    robot->set_x(100.0F * static_cast<float>(id));
    robot->set_y(-50.0F);
    robot->set_orientation(0.5F);
    robot->set_pixel_x(1.0F);
    robot->set_pixel_y(2.0F);
  }
  auto* field = packet.mutable_geometry()->mutable_field();
  field->set_field_length(12000);
  field->set_field_width(9000);
  field->set_goal_width(1800);
  field->set_goal_depth(180);
  field->set_boundary_width(300);
  packet.set_source(SSL_SOURCE_SSL_VISION);
  return packet;
}

RoboCup2014Legacy::Wrapper::SSL_WrapperPacket sample_legacy_vision() {
  RoboCup2014Legacy::Wrapper::SSL_WrapperPacket packet;
  *packet.mutable_detection() = sample_vision().detection();
  auto* field = packet.mutable_geometry()->mutable_field();
  const auto* descriptor = field->GetDescriptor();
  for (int i = 0; i < descriptor->field_count(); ++i) {
    field->GetReflection()->SetInt32(field, descriptor->field(i), 100 + i);
  }
  return packet;
}

TrackerWrapperPacket sample_tracker() {
  TrackerWrapperPacket packet;
  packet.set_uuid("c0ffee");
  packet.set_source_name("ER-Force");
  auto* frame = packet.mutable_tracked_frame();
  frame->set_frame_number(5);
  frame->set_timestamp(1700000000.5);
  auto* ball = frame->add_balls();
  ball->mutable_pos()->set_x(1.0F);
  ball->mutable_pos()->set_y(2.0F);
  ball->mutable_pos()->set_z(0.0F);
  auto* robot = frame->add_robots();
  robot->mutable_robot_id()->set_id(4);
  robot->mutable_robot_id()->set_team(YELLOW);
  robot->mutable_pos()->set_x(-1.0F);
  robot->mutable_pos()->set_y(0.5F);
  robot->set_orientation(1.0F);
  frame->add_capabilities(CAPABILITY_DETECT_MULTIPLE_BALLS);
  return packet;
}

SimulatorCommand sample_simulator_command() {
  SimulatorCommand command;
  auto* ball = command.mutable_control()->mutable_teleport_ball();
  ball->set_x(0.0F);
  ball->set_y(0.0F);
  ball->set_by_force(false);
  auto* robot = command.mutable_control()->add_teleport_robot();
  robot->mutable_id()->set_id(1);
  robot->mutable_id()->set_team(BLUE);
  robot->set_present(true);
  auto* specs = command.mutable_config()->add_robot_specs();
  specs->mutable_id()->set_id(1);
  specs->mutable_id()->set_team(BLUE);
  specs->mutable_wheel_angles()->set_front_right(1.0F);
  specs->mutable_wheel_angles()->set_back_right(2.0F);
  specs->mutable_wheel_angles()->set_back_left(4.0F);
  specs->mutable_wheel_angles()->set_front_left(5.0F);
  return command;
}

SimulatorResponse sample_simulator_response() {
  SimulatorResponse response;
  auto* error = response.add_errors();
  error->set_code("UNKNOWN_ROBOT");
  error->set_message("robot 17 does not exist");
  return response;
}

RobotControl sample_robot_control() {
  RobotControl control;
  for (std::uint32_t id = 0; id < 3; ++id) {
    auto* command = control.add_robot_commands();
    command->set_id(id);
    auto* velocity = command->mutable_move_command()->mutable_local_velocity();
    velocity->set_forward(1.0F);
    velocity->set_left(0.0F);
    velocity->set_angular(0.5F);
    command->set_kick_speed(3.0F);
    command->set_kick_angle(30.0F);
  }
  return control;
}

RobotControlResponse sample_robot_control_response() {
  RobotControlResponse response;
  auto* feedback = response.add_feedback();
  feedback->set_id(2);
  feedback->set_dribbler_ball_contact(true);
  response.add_errors()->set_code("E");
  return response;
}

grSim_Packet sample_grsim_packet() {
  grSim_Packet packet;
  auto* commands = packet.mutable_commands();
  commands->set_timestamp(1.0);
  commands->set_isteamyellow(false);
  auto* command = commands->add_robot_commands();
  command->set_id(1);
  command->set_kickspeedx(0.0F);
  command->set_kickspeedz(0.0F);
  command->set_veltangent(1.0F);
  command->set_velnormal(0.0F);
  command->set_velangular(0.0F);
  command->set_spinner(false);
  command->set_wheelsspeed(false);
  auto* robot = packet.mutable_replacement()->add_robots();
  robot->set_x(1.0);
  robot->set_y(2.0);
  robot->set_dir(180.0);
  robot->set_id(1);
  robot->set_yellowteam(true);
  return packet;
}

Robots_Status sample_robots_status() {
  Robots_Status status;
  auto* robot = status.add_robots_status();
  robot->set_robot_id(3);
  robot->set_infrared(true);
  robot->set_flat_kick(true);
  robot->set_chip_kick(false);
  return status;
}

// One row per named decoder: how to call it and a valid datagram for it.
struct DecoderCase {
  std::string type_name;
  std::function<Status(std::span<const std::uint8_t>)> decode;
  std::string sample;
};

template <typename M, typename Decode>
DecoderCase make_case(Decode decode_function, const M& sample) {
  return DecoderCase{M::descriptor()->full_name(),
                     [decode_function](std::span<const std::uint8_t> bytes) -> Status {
                       auto result = decode_function(bytes);
                       if (!result) {
                         return result.error();
                       }
                       // A successful decode must always give a complete message.
                       EXPECT_TRUE(result->IsInitialized());
                       return Status::success();
                     },
                     sample.SerializeAsString()};
}

std::vector<DecoderCase> all_decoders() {
  return {
      make_case(decode_vision_wrapper, sample_vision()),
      make_case(decode_legacy_vision_wrapper, sample_legacy_vision()),
      make_case(decode_referee, sample_referee()),
      make_case(decode_tracker_wrapper, sample_tracker()),
      make_case(decode_simulator_command, sample_simulator_command()),
      make_case(decode_simulator_response, sample_simulator_response()),
      make_case(decode_robot_control, sample_robot_control()),
      make_case(decode_robot_control_response, sample_robot_control_response()),
      make_case(decode_grsim_packet, sample_grsim_packet()),
      make_case(decode_grsim_robots_status, sample_robots_status()),
  };
}

TEST(LeagueDecode, EverySampleDecodes) {
  for (const DecoderCase& c : all_decoders()) {
    SCOPED_TRACE(c.type_name);
    ASSERT_GT(c.sample.size(), 5U);
    const Status status = c.decode(byte_span(c.sample));
    EXPECT_TRUE(status.ok()) << status.error().message;
  }
}

TEST(LeagueDecode, EveryTruncationIsAValidMessageOrANamedError) {
  for (const DecoderCase& c : all_decoders()) {
    SCOPED_TRACE(c.type_name);
    int errors = 0;
    for (std::size_t length = 0; length < c.sample.size(); ++length) {
      const std::string prefix = c.sample.substr(0, length);
      const Status status = c.decode(byte_span(prefix));
      if (!status.ok()) {
        ++errors;
        EXPECT_THAT(status.error().message, HasSubstr(c.type_name));
        EXPECT_THAT(status.error().message, HasSubstr("(" + std::to_string(length) + " bytes)"));
      }
    }
    // Cutting inside the outermost sub-message always breaks the encoding.
    EXPECT_GT(errors, 0);
  }
}

TEST(LeagueDecode, TruncatedRefereeNamesMissingFields) {
  const std::string bytes = sample_referee().SerializeAsString();
  // The first three fields only: packet_timestamp, stage, stage_time_left.
  const HandEncoder head =
      HandEncoder().varint(1, 1700000000000000ULL).varint(2, Referee::NORMAL_SECOND_HALF).sint(3, 120000000);
  ASSERT_EQ(bytes.substr(0, head.str().size()), head.str());
  auto decoded = decode_referee(byte_span(head.str()));
  ASSERT_FALSE(decoded.ok());
  EXPECT_THAT(decoded.error().message, HasSubstr("missing required fields"));
  EXPECT_THAT(decoded.error().message, HasSubstr("command"));
  EXPECT_THAT(decoded.error().message, HasSubstr("yellow"));
}

TEST(LeagueDecode, SeededRandomBytesNeverCrash) {
  std::mt19937 random(20240601U);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<std::size_t> length(0, 700);
  const auto decoders = all_decoders();
  std::vector<std::uint8_t> buffer;
  int accepted = 0;
  int rejected = 0;
  for (int round = 0; round < 3000; ++round) {
    buffer.resize(length(random));
    for (auto& b : buffer) {
      b = static_cast<std::uint8_t>(byte(random));
    }
    for (const DecoderCase& c : decoders) {
      const Status status = c.decode(buffer);
      if (status.ok()) {
        ++accepted;
      } else {
        ++rejected;
        EXPECT_THAT(status.error().message, HasSubstr(c.type_name));
      }
    }
  }
  EXPECT_GT(rejected, 0);
  EXPECT_EQ(accepted + rejected, 3000 * static_cast<int>(decoders.size()));
}

TEST(LeagueDecode, SeededMutationsOfValidPacketsNeverCrash) {
  std::mt19937 random(7U);
  for (const DecoderCase& c : all_decoders()) {
    SCOPED_TRACE(c.type_name);
    std::uniform_int_distribution<std::size_t> position(0, c.sample.size() - 1);
    std::uniform_int_distribution<int> byte(0, 255);
    std::uniform_int_distribution<int> flips(1, 4);
    for (int round = 0; round < 2000; ++round) {
      std::string mutated = c.sample;
      for (int i = flips(random); i > 0; --i) {
        mutated[position(random)] = static_cast<char>(byte(random));
      }
      const Status status = c.decode(byte_span(mutated));
      if (!status.ok()) {
        EXPECT_THAT(status.error().message, HasSubstr(c.type_name));
      }
    }
  }
}

TEST(LeagueDecode, DatagramSizeLimitIsTheUdpMaximum) {
  // A valid packet padded with an unknown length-delimited field (number 15) to an exact size.
  const std::string base = sample_vision().SerializeAsString();
  auto padded_to = [&](std::size_t total) {
    // tag (1 byte) + 3-byte length varint + padding
    const std::size_t padding = total - base.size() - 1 - 3;
    std::string bytes = base + HandEncoder().bytes(15, std::string(padding, 'x')).str();
    EXPECT_EQ(bytes.size(), total);
    return bytes;
  };
  const std::string largest = padded_to(kMaxDatagramBytes);
  auto accepted = decode_vision_wrapper(byte_span(largest));
  ASSERT_TRUE(accepted.ok()) << accepted.error().message;
  EXPECT_EQ(accepted->detection().frame_number(), 100U);

  const std::string oversized = padded_to(kMaxDatagramBytes + 1);
  auto rejected = decode_vision_wrapper(byte_span(oversized));
  ASSERT_FALSE(rejected.ok());
  EXPECT_THAT(rejected.error().message, HasSubstr("SSL_WrapperPacket (65508 bytes)"));
  EXPECT_THAT(rejected.error().message, HasSubstr("UDP maximum of 65507 bytes"));

  const std::vector<std::uint8_t> huge(1 << 20, 0x08);
  for (const DecoderCase& c : all_decoders()) {
    EXPECT_FALSE(c.decode(huge).ok()) << c.type_name;
  }
}

TEST(LeagueDecode, MissingRequiredFieldIsNamed) {
  Referee referee = sample_referee();
  referee.mutable_blue()->clear_goalkeeper();
  std::string bytes;
  ASSERT_TRUE(referee.SerializePartialToString(&bytes));
  auto decoded = decode_referee(byte_span(bytes));
  ASSERT_FALSE(decoded.ok());
  EXPECT_THAT(decoded.error().message, HasSubstr("Referee (" + std::to_string(bytes.size()) + " bytes)"));
  EXPECT_THAT(decoded.error().message, HasSubstr("missing required fields: blue.goalkeeper"));

  SSL_WrapperPacket packet = sample_vision();
  packet.mutable_detection()->mutable_balls(0)->clear_confidence();
  ASSERT_TRUE(packet.SerializePartialToString(&bytes));
  auto vision = decode_vision_wrapper(byte_span(bytes));
  ASSERT_FALSE(vision.ok());
  EXPECT_THAT(vision.error().message, HasSubstr("detection.balls[0].confidence"));

  // A game event payload without its required by_team.
  Referee with_event = sample_referee();
  with_event.mutable_game_events(0)->mutable_ball_left_field_touch_line()->clear_by_team();
  ASSERT_TRUE(with_event.SerializePartialToString(&bytes));
  auto event = decode_referee(byte_span(bytes));
  ASSERT_FALSE(event.ok());
  EXPECT_THAT(event.error().message, HasSubstr("game_events[0].ball_left_field_touch_line.by_team"));
}

TEST(LeagueDecode, DeeplyNestedGameEventsAreRejectedNotOverflowed) {
  // MultipleFouls contains GameEvents, which may contain MultipleFouls: nest far beyond protobuf's
  // recursion limit (100).
  HandEncoder event;
  event.message(33, HandEncoder().varint(1, 1));  // innermost: multiple_placement_failures
  for (int depth = 0; depth < 3000; ++depth) {
    HandEncoder fouls;
    fouls.varint(1, 1).message(2, event);
    HandEncoder outer;
    outer.message(34, fouls);
    event = outer;
  }
  Referee referee = sample_referee();
  std::string bytes = referee.SerializeAsString() + HandEncoder().message(16, event).str();
  ASSERT_LE(bytes.size(), kMaxDatagramBytes);
  auto decoded = decode_referee(byte_span(bytes));
  ASSERT_FALSE(decoded.ok());
  EXPECT_THAT(decoded.error().message, HasSubstr("malformed"));
}

TEST(LeagueDecode, WrongStreamIsAnErrorOrHarmless) {
  // Every sample fed to every decoder: never a crash. Protobuf keeps fields whose wire type does not
  // match as unknown fields, so only required fields reliably tell streams apart.
  const auto decoders = all_decoders();
  for (const DecoderCase& source : decoders) {
    for (const DecoderCase& c : decoders) {
      (void)c.decode(byte_span(source.sample));
    }
  }
  auto referee = decode_referee(byte_span(sample_vision().SerializeAsString()));
  ASSERT_FALSE(referee.ok());
  EXPECT_THAT(referee.error().message, HasSubstr("missing required fields"));
}

TEST(LeagueDecode, EmptyDatagram) {
  EXPECT_TRUE(decode_vision_wrapper({}).ok());  // every field optional
  auto referee = decode_referee({});
  ASSERT_FALSE(referee.ok());
  EXPECT_THAT(referee.error().message, HasSubstr("Referee (0 bytes): missing required fields"));
}

TEST(LeagueEncodeDatagram, ChecksRequiredFieldsAndSize) {
  const Referee referee = sample_referee();
  auto encoded = encode_datagram(referee);
  ASSERT_TRUE(encoded.ok()) << encoded.error().message;
  EXPECT_EQ(*encoded, referee.SerializeAsString());

  Referee incomplete = referee;
  incomplete.mutable_yellow()->clear_name();
  auto missing = encode_datagram(incomplete);
  ASSERT_FALSE(missing.ok());
  EXPECT_THAT(missing.error().message, HasSubstr("yellow.name"));

  SSL_WrapperPacket big = sample_vision();
  for (int i = 0; i < 3000; ++i) {
    *big.mutable_detection()->add_robots_yellow() = big.detection().robots_blue(0);
  }
  auto too_big = encode_datagram(big);
  ASSERT_FALSE(too_big.ok());
  EXPECT_THAT(too_big.error().message, HasSubstr("exceeds the UDP maximum"));
}

}  // namespace
}  // namespace ssl::league
