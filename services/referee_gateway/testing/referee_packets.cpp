#include "services/referee_gateway/testing/referee_packets.h"

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

namespace ssl::referee {

void PrintTo(const GameEvent& e, std::ostream* os) {
  *os << "{" << to_string(e.type) << " id='" << e.id << "' team=" << static_cast<int>(e.by_team);
  if (e.by_bot) *os << " bot=" << *e.by_bot;
  if (e.other_bot) *os << " other=" << *e.other_bot;
  if (e.location) *os << " loc=(" << e.location->x() << "," << e.location->y() << ")";
  if (e.secondary_location)
    *os << " loc2=(" << e.secondary_location->x() << "," << e.secondary_location->y() << ")";
  if (e.value) *os << " value=" << *e.value;
  *os << " text='" << e.text << "'}";
}

}  // namespace ssl::referee

namespace ssl::referee::testing {

::Referee referee_packet(::Referee::Command command, std::uint32_t counter, std::string_view source) {
  ::Referee packet;
  packet.set_source_identifier(std::string(source));
  packet.set_packet_timestamp(1'700'000'000'000'000ull);
  packet.set_stage(::Referee::NORMAL_FIRST_HALF);
  packet.set_command(command);
  packet.set_command_counter(counter);
  packet.set_command_timestamp(1'700'000'000'000'000ull);
  for (auto* team : {packet.mutable_yellow(), packet.mutable_blue()}) {
    team->set_score(0);
    team->set_red_cards(0);
    team->set_yellow_cards(0);
    team->set_timeouts(4);
    team->set_timeout_time(300'000'000);
    team->set_goalkeeper(0);
  }
  packet.mutable_yellow()->set_name("yellow");
  packet.mutable_blue()->set_name("blue");
  return packet;
}

::Referee full_referee_packet() {
  ::Referee packet;
  packet.set_source_identifier("6f1c2a4e-1b2d-4c3e-9f00-0123456789ab");
  packet.set_match_type(::ELIMINATION_PHASE);
  packet.set_packet_timestamp(1'712'345'678'901'234ull);  // µs -> 1712345678901234000 ns
  packet.set_stage(::Referee::EXTRA_SECOND_HALF);
  packet.set_stage_time_left(-5'000'000'123ll);  // µs, beyond 32 bits -> -5000.000123 s
  packet.set_command(::Referee::BALL_PLACEMENT_BLUE);
  packet.set_command_counter(4'000'000'000u);
  packet.set_command_timestamp(1'712'345'600'000'001ull);  // -> 1712345600000001000 ns
  auto fill_team = [](::Referee::TeamInfo& team, std::uint32_t base, const char* name) {
    team.set_name(name);
    team.set_score(base + 1);
    team.set_red_cards(base + 2);
    team.add_yellow_card_times(1'500'000);                   // 1.5 s
    team.add_yellow_card_times(base * 1'000'000 + 250'000);  // base + 0.25 s
    team.set_yellow_cards(base + 3);
    team.set_timeouts(base + 4);
    team.set_timeout_time(base * 1'000'000 + 500'000);  // base + 0.5 s
    team.set_goalkeeper(base + 5);
    team.set_foul_counter(base + 6);
    team.set_ball_placement_failures(base + 7);
    team.set_can_place_ball(true);
    team.set_max_allowed_bots(base + 8);
    team.set_bot_substitution_intent(true);
    team.set_ball_placement_failures_reached(true);
    team.set_bot_substitution_allowed(true);
    team.set_bot_substitutions_left(base + 9);
    team.set_bot_substitution_time_left(base * 1'000'000 + 750'000);  // base + 0.75 s
    team.set_hull_color(base == 10 ? ::HULL_COLOR_DARK : ::HULL_COLOR_LIGHT);
  };
  fill_team(*packet.mutable_yellow(), 10, "Yellow Tigers");
  fill_team(*packet.mutable_blue(), 20, "Blue Whales");
  packet.mutable_designated_position()->set_x(-1250.5f);  // mm -> -1.2505 m
  packet.mutable_designated_position()->set_y(3000.0f);   // mm -> 3.0 m
  packet.set_blue_team_on_positive_half(true);
  packet.set_next_command(::Referee::DIRECT_FREE_BLUE);
  *packet.add_game_events() = game_event(
      R"(id: "ev-1" type: BALL_LEFT_FIELD_TOUCH_LINE origin: "TIGERs AutoRef" origin: "ER-Force"
         created_timestamp: 1712345601000000
         ball_left_field_touch_line { by_team: YELLOW by_bot: 7 location { x: 1.5 y: -4.5 } })");
  *packet.add_game_events() = game_event(
      R"(id: "ev-2" bot_dropped_parts { by_team: BLUE by_bot: 2 location { x: 0.25 y: 0.5 }
                                       ball_location { x: -1 y: 2 } })");
  auto* proposal = packet.add_game_event_proposals();
  proposal->set_id("proposal-9");
  proposal->set_accepted(true);
  *proposal->add_game_events() = game_event(R"(id: "ev-3" possible_goal { by_team: BLUE kicking_bot: 4 })");
  packet.set_current_action_time_remaining(-2'500'000'000ll);  // µs -> -2500 s
  packet.set_status_message("Ball placement by blue");
  return packet;
}

::GameEvent game_event(std::string_view text) {
  ::GameEvent event;
  if (!google::protobuf::TextFormat::ParseFromString(std::string(text), &event)) {
    ADD_FAILURE() << "bad GameEvent text: " << text;
  }
  return event;
}

std::string encode(const ::Referee& packet) {
  std::string bytes;
  EXPECT_TRUE(packet.SerializeToString(&bytes)) << packet.InitializationErrorString();
  return bytes;
}

void expect_every_field_set(const ::Referee& packet) {
  auto expect_set = [](const google::protobuf::Message& message, const google::protobuf::FieldDescriptor* field,
                       const char* where) {
    if (field->is_repeated()) {
      EXPECT_GT(message.GetReflection()->FieldSize(message, field), 0) << where << field->name();
    } else {
      EXPECT_TRUE(message.GetReflection()->HasField(message, field)) << where << field->name();
    }
  };
  const auto* descriptor = ::Referee::descriptor();
  for (int i = 0; i < descriptor->field_count(); ++i) expect_set(packet, descriptor->field(i), "");
  const auto* team_descriptor = ::Referee::TeamInfo::descriptor();
  for (int i = 0; i < team_descriptor->field_count(); ++i) {
    expect_set(packet.yellow(), team_descriptor->field(i), "yellow.");
    expect_set(packet.blue(), team_descriptor->field(i), "blue.");
  }
}

}  // namespace ssl::referee::testing
