// In-process tests of the DDS layer: typed delivery, team partitions, keep-last per key, late joiners,
// and clear errors for misuse. Each test uses its own domain id so concurrent tests never see each other.
#include "libs/dds/participant.h"

#include <gtest/gtest.h>

#include <atomic>
#include <vector>
#include <string>

namespace ssl::dds {
namespace {

using std::chrono::seconds;
constexpr auto kMatchTimeout = seconds(10);

Participant make_participant(int domain) {
  auto participant = Participant::create({.domain_id = domain, .name = "participant_test"});
  EXPECT_TRUE(participant) << participant.error().message;
  return std::move(participant).value();
}

idl::referee::RefereeState referee_state(std::uint32_t counter) {
  idl::referee::RefereeState state;
  state.command(idl::referee::COMMAND_STOP);
  state.command_counter(counter);
  state.status_message("counter " + std::to_string(counter));
  return state;
}

TEST(ParticipantTest, RejectsADomainIdOutOfRange) {
  auto participant = Participant::create({.domain_id = 500});
  ASSERT_FALSE(participant);
  EXPECT_NE(participant.error().message.find("out of range"), std::string::npos);
}

TEST(ParticipantTest, RejectsAMissingQosFileWithItsName) {
  auto participant = Participant::create({.domain_id = 1, .qos_file = "/nonexistent/profiles.xml"});
  ASSERT_FALSE(participant);
  EXPECT_NE(participant.error().message.find("/nonexistent/profiles.xml"), std::string::npos);
}

TEST(ParticipantTest, TeamScopedTopicsRequireATeamAndSharedOnesRefuseOne) {
  auto participant = make_participant(110);
  auto no_team = participant.make_writer(topics::kWorldState);
  ASSERT_FALSE(no_team);
  EXPECT_NE(no_team.error().message.find("team-scoped"), std::string::npos);
  auto with_team = participant.make_reader(topics::kRefereeState, TeamColor::kBlue);
  ASSERT_FALSE(with_team);
  EXPECT_NE(with_team.error().message.find("shared"), std::string::npos);
}

TEST(ParticipantTest, DeliversASampleBetweenTwoParticipants) {
  auto publisher_side = make_participant(111);
  auto subscriber_side = make_participant(111);
  auto writer = publisher_side.make_writer(topics::kRefereeEvent);
  auto reader = subscriber_side.make_reader(topics::kRefereeEvent);
  ASSERT_TRUE(writer && reader);
  ASSERT_TRUE(writer->wait_for_match(1, kMatchTimeout));

  idl::referee::RefereeEvent event;
  event.event().type(idl::referee::GAME_EVENT_BOT_TOO_FAST_IN_STOP);
  event.event().value(2.5);
  event.command_counter(42);
  ASSERT_TRUE(writer->write(event).ok());

  ASSERT_TRUE(reader->wait_for_data(kMatchTimeout));
  auto samples = reader->take();
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_EQ(samples[0].data.event().type(), idl::referee::GAME_EVENT_BOT_TOO_FAST_IN_STOP);
  EXPECT_DOUBLE_EQ(samples[0].data.event().value(), 2.5);
  EXPECT_EQ(samples[0].data.command_counter(), 42u);
  EXPECT_GT(samples[0].reception_unix_ns, 0);
  EXPECT_EQ(writer->counters().written, 1u);
  EXPECT_EQ(reader->counters().received, 1u);
}

TEST(ParticipantTest, TeamPartitionsKeepBlueAndYellowApart) {
  auto planner_side = make_participant(112);
  auto link_side = make_participant(112);
  auto blue_writer = planner_side.make_writer(topics::kRobotCommands, TeamColor::kBlue);
  auto yellow_reader = link_side.make_reader(topics::kRobotCommands, TeamColor::kYellow);
  auto blue_reader = link_side.make_reader(topics::kRobotCommands, TeamColor::kBlue);
  ASSERT_TRUE(blue_writer && yellow_reader && blue_reader);
  // Best effort: a sample sent before the reader side has matched the writer is legitimately lost, so
  // both sides must have matched.
  ASSERT_TRUE(blue_writer->wait_for_match(1, kMatchTimeout));
  ASSERT_TRUE(blue_reader->wait_for_match(1, kMatchTimeout));

  idl::robot::RobotCommands commands;
  commands.team(idl::common::TEAM_COLOR_BLUE);
  commands.commands().resize(3);
  ASSERT_TRUE(blue_writer->write(commands).ok());
  ASSERT_TRUE(blue_reader->wait_for_data(kMatchTimeout));
  EXPECT_EQ(blue_reader->take().size(), 1u);
  // The yellow reader never matched the blue writer, so nothing can be in flight towards it.
  EXPECT_EQ(yellow_reader->counters().matched_writers, 0u);
  EXPECT_TRUE(yellow_reader->take().empty());
}

TEST(ParticipantTest, AnEstopForOneTeamReachesOnlyItsReadersAndOneForEveryTeamReachesBoth) {
  auto operator_side = make_participant(178);
  auto links_side = make_participant(178);
  auto for_blue = operator_side.make_writer(topics::kSystemEstop, TeamColor::kBlue);
  auto for_everyone = operator_side.make_writer(topics::kSystemEstop);
  auto blue_link = links_side.make_reader(topics::kSystemEstop, TeamColor::kBlue);
  auto yellow_link = links_side.make_reader(topics::kSystemEstop, TeamColor::kYellow);
  ASSERT_TRUE(for_blue && for_everyone && blue_link && yellow_link);
  // Reliable and transient local: a matched reader gets what was written.
  ASSERT_TRUE(blue_link->wait_for_match(2, kMatchTimeout));
  ASSERT_TRUE(yellow_link->wait_for_match(1, kMatchTimeout));
  // One at a time: the e-stop keeps only the newest sample.
  const auto write = [](auto& writer, const std::string& source) {
    idl::system::Estop estop;
    estop.engaged(true);
    estop.source(source);
    ASSERT_TRUE(writer->write(estop).ok());
    ASSERT_TRUE(writer->wait_for_acknowledgments(kMatchTimeout));
  };
  const auto sources = [](auto& reader) {
    std::vector<std::string> seen;
    for (const auto& sample : reader->take()) seen.push_back(sample.data.source());
    return seen;
  };
  // The writer's acknowledgment can come a moment before the sample is there to take (2 in 60 runs): a
  // reader that should have it waits for it.
  const auto arrived = [&](auto& reader) {
    EXPECT_TRUE(reader->wait_for_data(kMatchTimeout));
    return sources(reader);
  };
  write(for_blue, "for blue");
  EXPECT_EQ(arrived(blue_link), std::vector<std::string>{"for blue"});
  EXPECT_TRUE(sources(yellow_link).empty());
  write(for_everyone, "for everyone");
  EXPECT_EQ(arrived(blue_link), std::vector<std::string>{"for everyone"});
  EXPECT_EQ(arrived(yellow_link), std::vector<std::string>{"for everyone"});
  EXPECT_EQ(yellow_link->counters().matched_writers, 1u);
}

TEST(ParticipantTest, CallbackReaderSeesEverySampleOnTheMiddlewareThread) {
  auto writer_side = make_participant(113);
  auto reader_side = make_participant(113);
  std::atomic<int> seen{0};
  auto reader = reader_side.make_reader(topics::kRefereeEvent, std::nullopt,
                                        [&](const Sample<idl::referee::RefereeEvent>&) { ++seen; });
  auto writer = writer_side.make_writer(topics::kRefereeEvent);
  ASSERT_TRUE(reader && writer);
  ASSERT_TRUE(writer->wait_for_match(1, kMatchTimeout));
  for (std::uint32_t i = 0; i < 5; ++i) {
    idl::referee::RefereeEvent event;
    event.command_counter(i);
    ASSERT_TRUE(writer->write(event).ok());
  }
  const auto deadline = std::chrono::steady_clock::now() + kMatchTimeout;
  while (seen.load() < 5 && std::chrono::steady_clock::now() < deadline) reader->wait_for_data(seconds(1));
  EXPECT_EQ(seen.load(), 5);
}

TEST(ParticipantTest, LateJoinerGetsTheLastRefereeStateOnly) {
  auto gateway = make_participant(114);
  auto writer = gateway.make_writer(topics::kRefereeState);
  ASSERT_TRUE(writer);
  for (std::uint32_t counter = 1; counter <= 3; ++counter) ASSERT_TRUE(writer->write(referee_state(counter)).ok());

  auto late = make_participant(114);
  auto reader = late.make_reader(topics::kRefereeState);
  ASSERT_TRUE(reader);
  ASSERT_TRUE(reader->wait_for_data(kMatchTimeout));
  const auto samples = reader->take();
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_EQ(samples[0].data.command_counter(), 3u);
}

// Fast DDS's default resource limits hold 10 instances of a keyed topic; the profiles raise them so that
// every robot id (0-15) and every service of an 11 v 11 match with its tools keeps its own instance.
TEST(ParticipantTest, KeyedTopicsTakeEveryRobotIdAndEveryServiceInstance) {
  auto writer_side = make_participant(116);
  auto reader_side = make_participant(116);
  auto feedback_writer = writer_side.make_writer(topics::kRobotFeedback, TeamColor::kBlue);
  auto feedback_reader = reader_side.make_reader(topics::kRobotFeedback, TeamColor::kBlue);
  auto health_writer = writer_side.make_writer(topics::kSystemHealth);
  auto health_reader = reader_side.make_reader(topics::kSystemHealth);
  ASSERT_TRUE(feedback_writer && feedback_reader && health_writer && health_reader);
  ASSERT_TRUE(feedback_writer->wait_for_match(1, kMatchTimeout));
  ASSERT_TRUE(feedback_reader->wait_for_match(1, kMatchTimeout));
  ASSERT_TRUE(health_writer->wait_for_match(1, kMatchTimeout));
  ASSERT_TRUE(health_reader->wait_for_match(1, kMatchTimeout));

  constexpr std::uint32_t kRobotIds = 16;
  constexpr int kServices = 40;
  for (std::uint32_t id = 0; id < kRobotIds; ++id) {
    idl::robot::RobotFeedback feedback;
    feedback.robot_id(id);
    EXPECT_TRUE(feedback_writer->write(feedback).ok()) << "robot " << id;
  }
  for (int i = 0; i < kServices; ++i) {
    idl::system::Health report;
    report.service("service/" + std::to_string(i));
    EXPECT_TRUE(health_writer->write(report).ok()) << "service " << i;
  }

  std::set<std::uint32_t> robots;
  std::set<std::string> services;
  const auto deadline = std::chrono::steady_clock::now() + kMatchTimeout;
  while ((robots.size() < kRobotIds || services.size() < kServices) && std::chrono::steady_clock::now() < deadline) {
    feedback_reader->wait_for_data(std::chrono::milliseconds(100));
    for (const auto& sample : feedback_reader->take()) robots.insert(sample.data.robot_id());
    for (const auto& sample : health_reader->take()) services.insert(sample.data.service());
  }
  EXPECT_EQ(robots.size(), kRobotIds);
  EXPECT_EQ(services.size(), static_cast<std::size_t>(kServices));
}

TEST(ParticipantTest, AllTopicsAreListedWithTypesAndProfiles) {
  const auto topics = all_topics();
  ASSERT_EQ(topics.size(), 14u);
  EXPECT_EQ(topics[0].name, "vision.detection");
  EXPECT_EQ(topics[0].type_name, "ssl::idl::vision::DetectionFrame");
  EXPECT_EQ(topics[0].writer_profile, "vision.detection.writer");
  bool found_world = false;
  for (const auto& topic : topics) {
    if (topic.name == "world.state") {
      found_world = true;
      EXPECT_EQ(topic.scope, TopicScope::kTeam);
    }
  }
  EXPECT_TRUE(found_world);
}

TEST(ParticipantTest, VisitTopicFindsTopicsByName) {
  std::string visited;
  EXPECT_TRUE(visit_topic("robot.feedback", [&](const auto& spec) { visited = spec.name; }));
  EXPECT_EQ(visited, "robot.feedback");
  EXPECT_FALSE(visit_topic("no.such.topic", [&](const auto&) { FAIL(); }));
}

}  // namespace
}  // namespace ssl::dds
