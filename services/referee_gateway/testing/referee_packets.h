// Test-only builders of the Game Controller's Referee packets (league protobuf, wire units: µs, mm), for
// the referee gateway's unit and process tests, and gtest printing of core game events. Every packet they
// return has all proto2 `required` fields set, so it encodes and decodes.
//
//   ::Referee packet = referee_packet(::Referee::STOP, 7, "gc-1");
//   *packet.add_game_events() = game_event("ball_left_field_touch_line { by_team: BLUE by_bot: 3 }");
//   std::string bytes = encode(packet);
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>

#include "proto/ssl_gc_referee_message.pb.h"
#include "services/referee_gateway/core/types.h"

namespace ssl::referee {

/// Readable gtest failure messages for the core's game events (found by argument-dependent lookup).
void PrintTo(const GameEvent& e, std::ostream* os);

}  // namespace ssl::referee

namespace ssl::referee::testing {

/// A minimal valid packet: the given command and counter, stage NORMAL_FIRST_HALF, team names "yellow"
/// and "blue", time stamps at 1.7e15 µs.
::Referee referee_packet(::Referee::Command command, std::uint32_t counter, std::string_view source = "gc-1");

/// A packet with EVERY field of Referee and of both TeamInfos set to distinctive values (documented in
/// the .cpp next to each value), and two game events plus one proposal group.
::Referee full_referee_packet();

/// A GameEvent from protobuf text format (e.g. "goal { by_team: BLUE kicking_bot: 4 }"); fails the
/// current test (and returns an empty event) when the text does not parse.
::GameEvent game_event(std::string_view text);

/// Fails the current test for each field of Referee and of both TeamInfos that `packet` does not set (an
/// empty repeated field counts as not set).
void expect_every_field_set(const ::Referee& packet);

/// Serialized bytes of a packet (fails the current test if a required field is missing).
std::string encode(const ::Referee& packet);

}  // namespace ssl::referee::testing
