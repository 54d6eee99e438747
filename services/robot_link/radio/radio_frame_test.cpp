// The radio frame codec: round trips of every field, the CRC's check value and single-bit detection,
// and a decoder that survives random, truncated and corrupt input; the stream assembler resynchronises.
#include "services/robot_link/radio/radio_frame.h"

#include <gtest/gtest.h>

#include <random>
#include <string_view>

namespace ssl::robot_link::radio {
namespace {

CommandFrame sample_command_frame() {
  CommandFrame frame;
  frame.sequence = 0xBEEF;
  frame.robots.push_back({.command = {.id = 0,
                                      .forward = 1.234,
                                      .left = -0.5,
                                      .angular = 3.141,
                                      .kick = KickType::kFlat,
                                      .kick_speed = 6.5,
                                      .chip_angle = 0,
                                      .dribbler_rpm = 12000},
                          .stop = false});
  frame.robots.push_back({.command = {.id = 7,
                                      .forward = -2.999,
                                      .left = 2.5,
                                      .angular = -10.0,
                                      .kick = KickType::kChip,
                                      .kick_speed = 4.25,
                                      .chip_angle = 0.785,
                                      .dribbler_rpm = 0},
                          .stop = false});
  frame.robots.push_back({.command = {.id = 15}, .stop = true});
  return frame;
}

StatusFrame sample_status_frame() {
  StatusFrame frame;
  frame.sequence = 65535;
  frame.robots.push_back({.robot_id = 2,
                          .ball_in_dribbler = true,
                          .battery_voltage = 15.872,
                          .kicker_charge = 0.87,
                          .link_quality = 0.99,
                          .last_command_sequence = 1234});
  frame.robots.push_back({.robot_id = 11,
                          .ball_in_dribbler = false,
                          .battery_voltage = std::nullopt,
                          .kicker_charge = 0.0,
                          .link_quality = std::nullopt,
                          .last_command_sequence = 0});
  return frame;
}

TEST(RobotLinkRadioFrameTest, CrcMatchesTheCcittFalseCheckValue) {
  constexpr std::string_view kCheck = "123456789";
  const std::vector<std::uint8_t> bytes(kCheck.begin(), kCheck.end());
  EXPECT_EQ(crc16_ccitt(bytes), 0x29B1);
  EXPECT_EQ(crc16_ccitt({}), 0xFFFF);
}

TEST(RobotLinkRadioFrameTest, CommandFrameRoundTripsEveryField) {
  const CommandFrame frame = sample_command_frame();
  auto bytes = encode_command_frame(frame);
  ASSERT_TRUE(bytes) << bytes.error().message;
  EXPECT_EQ(bytes->size(), kHeaderBytes + 1 + 3 * kCommandRecordBytes + kCrcBytes);
  EXPECT_EQ((*bytes)[0], 0xA5);
  EXPECT_EQ((*bytes)[1], 0x5A);
  EXPECT_EQ((*bytes)[3], 1);     // command
  EXPECT_EQ((*bytes)[4], 0xEF);  // sequence, little-endian
  EXPECT_EQ((*bytes)[5], 0xBE);

  auto decoded = decode_frame(*bytes);
  ASSERT_TRUE(decoded) << decoded.error().message;
  const auto* command = std::get_if<CommandFrame>(&*decoded);
  ASSERT_NE(command, nullptr);
  EXPECT_EQ(command->sequence, 0xBEEF);
  ASSERT_EQ(command->robots.size(), frame.robots.size());
  for (std::size_t i = 0; i < frame.robots.size(); ++i) {
    const RobotCommand& want = frame.robots[i].command;
    const RobotCommand& got = command->robots[i].command;
    SCOPED_TRACE("robot " + std::to_string(want.id));
    EXPECT_EQ(got.id, want.id);
    EXPECT_NEAR(got.forward, want.forward, 0.5 / kVelocityScale);
    EXPECT_NEAR(got.left, want.left, 0.5 / kVelocityScale);
    EXPECT_NEAR(got.angular, want.angular, 0.5 / kAngularScale);
    EXPECT_EQ(got.kick, want.kick);
    EXPECT_NEAR(got.kick_speed, want.kick_speed, 0.5 / kKickSpeedScale);
    EXPECT_NEAR(got.chip_angle, want.chip_angle, 0.5 / kChipAngleScale);
    EXPECT_DOUBLE_EQ(got.dribbler_rpm, want.dribbler_rpm);
    EXPECT_EQ(command->robots[i].stop, frame.robots[i].stop);
  }
}

TEST(RobotLinkRadioFrameTest, FixedPointSaturatesInsteadOfWrapping) {
  CommandFrame frame;
  frame.robots.push_back({.command = {.id = 1,
                                      .forward = 100.0,
                                      .left = -100.0,
                                      .angular = std::nan(""),
                                      .kick = KickType::kFlat,
                                      .kick_speed = -3,
                                      .dribbler_rpm = 1e9}});
  auto decoded = decode_frame(*encode_command_frame(frame));
  ASSERT_TRUE(decoded);
  const RobotCommand& got = std::get<CommandFrame>(*decoded).robots[0].command;
  EXPECT_DOUBLE_EQ(got.forward, 32.767);
  EXPECT_DOUBLE_EQ(got.left, -32.768);
  EXPECT_EQ(got.angular, 0);
  EXPECT_EQ(got.kick_speed, 0);
  EXPECT_EQ(got.dribbler_rpm, 65535);
}

TEST(RobotLinkRadioFrameTest, StatusFrameRoundTripsEveryField) {
  const StatusFrame frame = sample_status_frame();
  auto bytes = encode_status_frame(frame);
  ASSERT_TRUE(bytes) << bytes.error().message;
  auto decoded = decode_frame(*bytes);
  ASSERT_TRUE(decoded) << decoded.error().message;
  const auto* status = std::get_if<StatusFrame>(&*decoded);
  ASSERT_NE(status, nullptr);
  EXPECT_EQ(status->sequence, 65535);
  ASSERT_EQ(status->robots.size(), 2u);
  EXPECT_EQ(status->robots[0].robot_id, 2u);
  EXPECT_TRUE(status->robots[0].ball_in_dribbler);
  ASSERT_TRUE(status->robots[0].battery_voltage);
  EXPECT_DOUBLE_EQ(*status->robots[0].battery_voltage, 15.872);
  ASSERT_TRUE(status->robots[0].kicker_charge);
  EXPECT_DOUBLE_EQ(*status->robots[0].kicker_charge, 0.87);
  ASSERT_TRUE(status->robots[0].link_quality);
  EXPECT_DOUBLE_EQ(*status->robots[0].link_quality, 0.99);
  EXPECT_EQ(status->robots[0].last_command_sequence, 1234);
  EXPECT_EQ(status->robots[1], frame.robots[1]);
}

TEST(RobotLinkRadioFrameTest, EmptyAndFullFramesRoundTrip) {
  auto empty = decode_frame(*encode_command_frame({.sequence = 1}));
  ASSERT_TRUE(empty) << empty.error().message;
  EXPECT_TRUE(std::get<CommandFrame>(*empty).robots.empty());

  CommandFrame full;
  for (std::uint32_t id = 0; id < kMaxRecords; ++id)
    full.robots.push_back({.command = {.id = id, .forward = id * 0.1}});
  auto bytes = encode_command_frame(full);
  ASSERT_TRUE(bytes);
  EXPECT_LE(bytes->size(), kMaxFrameBytes);
  auto decoded = decode_frame(*bytes);
  ASSERT_TRUE(decoded) << decoded.error().message;
  EXPECT_EQ(std::get<CommandFrame>(*decoded).robots.size(), kMaxRecords);

  full.robots.push_back({.command = {.id = 1}});
  EXPECT_FALSE(encode_command_frame(full)) << "17 robots do not fit";
  EXPECT_FALSE(encode_command_frame({.robots = {{.command = {.id = 16}}}})) << "ids are 0..15";
}

TEST(RobotLinkRadioFrameTest, CrcDetectsEverySingleBitFlip) {
  for (const auto& bytes :
       {*encode_command_frame(sample_command_frame()), *encode_status_frame(sample_status_frame())}) {
    for (std::size_t bit = 0; bit < bytes.size() * 8; ++bit) {
      std::vector<std::uint8_t> flipped = bytes;
      flipped[bit / 8] ^= static_cast<std::uint8_t>(1u << (bit % 8));
      EXPECT_FALSE(decode_frame(flipped)) << "bit " << bit << " flipped was not detected";
    }
  }
}

TEST(RobotLinkRadioFrameTest, ErrorsSayWhatIsWrong) {
  auto bytes = *encode_command_frame(sample_command_frame());
  auto short_frame = decode_frame(std::span(bytes).first(5));
  ASSERT_FALSE(short_frame);
  EXPECT_NE(short_frame.error().message.find("shorter"), std::string::npos) << short_frame.error().message;

  auto truncated = decode_frame(std::span(bytes).first(bytes.size() - 1));
  ASSERT_FALSE(truncated);
  EXPECT_NE(truncated.error().message.find("length"), std::string::npos) << truncated.error().message;

  std::vector<std::uint8_t> corrupt = bytes;
  corrupt[10] ^= 0xFF;
  auto bad_crc = decode_frame(corrupt);
  ASSERT_FALSE(bad_crc);
  EXPECT_NE(bad_crc.error().message.find("CRC"), std::string::npos) << bad_crc.error().message;

  // A well-formed frame (valid CRC) with an invalid kick type in it.
  std::vector<std::uint8_t> bad_kick = bytes;
  bad_kick[kHeaderBytes + 1 + 7] = 0x03;
  const std::uint16_t crc = crc16_ccitt(std::span(bad_kick).first(bad_kick.size() - 2));
  bad_kick[bad_kick.size() - 2] = static_cast<std::uint8_t>(crc & 0xFF);
  bad_kick[bad_kick.size() - 1] = static_cast<std::uint8_t>(crc >> 8);
  auto kick = decode_frame(bad_kick);
  ASSERT_FALSE(kick);
  EXPECT_NE(kick.error().message.find("kick type"), std::string::npos) << kick.error().message;
}

TEST(RobotLinkRadioFrameTest, DecoderSurvivesThousandsOfRandomBuffersAndTruncations) {
  std::mt19937 random(20240611);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<std::size_t> length(0, 300);
  int accepted = 0;
  for (int i = 0; i < 20000; ++i) {
    std::vector<std::uint8_t> bytes(length(random));
    for (auto& b : bytes) b = static_cast<std::uint8_t>(byte(random));
    if (i % 2 == 1 && bytes.size() >= 2) {  // half of them look like frames, to get past the sync check
      bytes[0] = kSync0;
      bytes[1] = kSync1;
      if (bytes.size() >= kHeaderBytes) bytes[6] = static_cast<std::uint8_t>(bytes.size() - kMinFrameBytes);
    }
    accepted += decode_frame(bytes) ? 1 : 0;
  }
  EXPECT_LT(accepted, 20) << "random bytes are almost never a valid frame";

  const auto valid = *encode_command_frame(sample_command_frame());
  for (std::size_t n = 0; n < valid.size(); ++n) EXPECT_FALSE(decode_frame(std::span(valid).first(n))) << n;
  EXPECT_TRUE(decode_frame(valid));
  // Valid frames with random payload bytes and a recomputed CRC: structure errors, never a crash.
  for (int i = 0; i < 5000; ++i) {
    std::vector<std::uint8_t> mutated = valid;
    for (int k = 0; k < 3; ++k) {
      std::uniform_int_distribution<std::size_t> where(2, mutated.size() - 3);
      mutated[where(random)] = static_cast<std::uint8_t>(byte(random));
    }
    mutated[6] = static_cast<std::uint8_t>(mutated.size() - kMinFrameBytes);
    const std::uint16_t crc = crc16_ccitt(std::span(mutated).first(mutated.size() - 2));
    mutated[mutated.size() - 2] = static_cast<std::uint8_t>(crc & 0xFF);
    mutated[mutated.size() - 1] = static_cast<std::uint8_t>(crc >> 8);
    (void)decode_frame(mutated);
  }
}

TEST(RobotLinkRadioFrameTest, AssemblerCutsAStreamIntoFramesAndResynchronisesAfterGarbage) {
  const auto command = *encode_command_frame(sample_command_frame());
  const auto status = *encode_status_frame(sample_status_frame());
  std::vector<std::uint8_t> stream = {0x00, 0xA5, 0x13, 0x5A};  // garbage, including a false sync start
  stream.insert(stream.end(), command.begin(), command.end());
  std::vector<std::uint8_t> corrupt = status;
  corrupt[9] ^= 0x40;
  stream.insert(stream.end(), corrupt.begin(), corrupt.end());
  stream.insert(stream.end(), status.begin(), status.end());

  // Fed in odd-sized pieces, as a serial line delivers them.
  FrameAssembler assembler;
  std::vector<RadioFrame> frames;
  for (std::size_t at = 0; at < stream.size(); at += 7) {
    const auto piece = std::span(stream).subspan(at, std::min<std::size_t>(7, stream.size() - at));
    for (auto& frame : assembler.push(piece)) frames.push_back(std::move(frame));
  }
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_TRUE(std::holds_alternative<CommandFrame>(frames[0]));
  EXPECT_TRUE(std::holds_alternative<StatusFrame>(frames[1]));
  EXPECT_EQ(assembler.frames(), 2u);
  EXPECT_GE(assembler.bad_frames(), 1u);
  EXPECT_GE(assembler.skipped_bytes(), 4u + corrupt.size() - 1);

  // Random bytes never crash it and never grow its buffer without bound.
  std::mt19937 random(7);
  std::uniform_int_distribution<int> byte(0, 255);
  for (int i = 0; i < 2000; ++i) {
    std::vector<std::uint8_t> noise(64);
    for (auto& b : noise) b = static_cast<std::uint8_t>(byte(random));
    (void)assembler.push(noise);
  }
  // Good frames after the noise decode again (a false sync word in the noise may first hold up to one
  // maximum-length frame's worth of bytes: 6 copies cover it).
  std::size_t recovered = 0;
  for (int i = 0; i < 8; ++i) recovered += assembler.push(command).size();
  EXPECT_GE(recovered, 2u);
}

}  // namespace
}  // namespace ssl::robot_link::radio
