// Loads deploy/qos/profiles.xml and checks that every topic's writer and reader profile exists and carries
// the QoS the design asks for; Fast DDS ignores unknown XML silently in places, so the values are read back
// from the created entities rather than trusted.
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <gtest/gtest.h>

#include "libs/dds/participant.h"

namespace ssl::dds {
namespace {

namespace fdds = eprosima::fastdds::dds;

class QosProfilesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto file = find_qos_file();
    ASSERT_TRUE(file) << file.error().message;
    // Creating a participant loads the file into the factory.
    auto participant = Participant::create({.domain_id = 201, .name = "qos_profiles_test"});
    ASSERT_TRUE(participant) << participant.error().message;
  }

  static fdds::DataWriterQos writer_qos(const std::string& profile) {
    fdds::DataWriterQos qos;
    auto* factory = fdds::DomainParticipantFactory::get_instance();
    // The factory exposes profiles through a participant-independent path only for participants, so a
    // throwaway publisher resolves data writer profiles.
    auto* participant = factory->create_participant(202, fdds::PARTICIPANT_QOS_DEFAULT);
    auto* publisher = participant->create_publisher(fdds::PUBLISHER_QOS_DEFAULT);
    EXPECT_EQ(publisher->get_datawriter_qos_from_profile(profile, qos), ReturnCode_t::RETCODE_OK)
        << "missing writer profile " << profile;
    participant->delete_contained_entities();
    factory->delete_participant(participant);
    return qos;
  }

  static fdds::DataReaderQos reader_qos(const std::string& profile) {
    fdds::DataReaderQos qos;
    auto* factory = fdds::DomainParticipantFactory::get_instance();
    auto* participant = factory->create_participant(202, fdds::PARTICIPANT_QOS_DEFAULT);
    auto* subscriber = participant->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);
    EXPECT_EQ(subscriber->get_datareader_qos_from_profile(profile, qos), ReturnCode_t::RETCODE_OK)
        << "missing reader profile " << profile;
    participant->delete_contained_entities();
    factory->delete_participant(participant);
    return qos;
  }
};

TEST_F(QosProfilesTest, EveryTopicHasAWriterAndAReaderProfileWithMatchingReliabilityAndDurability) {
  for (const TopicInfo& topic : all_topics()) {
    SCOPED_TRACE(topic.name);
    const auto writer = writer_qos(topic.writer_profile);
    const auto reader = reader_qos(topic.reader_profile);
    EXPECT_EQ(writer.reliability().kind, reader.reliability().kind);
    EXPECT_EQ(writer.durability().kind, reader.durability().kind);
    EXPECT_EQ(writer.history().kind, fdds::KEEP_LAST_HISTORY_QOS);
    // A reader may not request a shorter deadline than the writer offers, or they never match.
    EXPECT_LE(writer.deadline().period, reader.deadline().period);
  }
}

TEST_F(QosProfilesTest, HighRateStreamsAreBestEffortKeepLastOne) {
  for (const char* name : {"vision.detection", "world.state", "robot.commands", "robot.sent", "robot.feedback", "planner.debug"}) {
    SCOPED_TRACE(name);
    const auto writer = writer_qos(std::string(name) + ".writer");
    EXPECT_EQ(writer.reliability().kind, fdds::BEST_EFFORT_RELIABILITY_QOS);
    EXPECT_EQ(writer.history().depth, 1);
  }
}

TEST_F(QosProfilesTest, StateTopicsAreReliableTransientLocalWithAFastHeartbeat) {
  for (const char* name : {"vision.geometry", "referee.state", "system.params", "system.estop"}) {
    SCOPED_TRACE(name);
    const auto writer = writer_qos(std::string(name) + ".writer");
    EXPECT_EQ(writer.reliability().kind, fdds::RELIABLE_RELIABILITY_QOS);
    EXPECT_EQ(writer.durability().kind, fdds::TRANSIENT_LOCAL_DURABILITY_QOS);
    EXPECT_EQ(writer.history().depth, 1);
    EXPECT_LE(writer.reliable_writer_qos().times.heartbeatPeriod, eprosima::fastrtps::Duration_t(0, 100'000'000));
  }
}

TEST_F(QosProfilesTest, RefereeEventsKeepSixtyFourReliably) {
  const auto writer = writer_qos("referee.event.writer");
  EXPECT_EQ(writer.reliability().kind, fdds::RELIABLE_RELIABILITY_QOS);
  EXPECT_EQ(writer.history().depth, 64);
}

TEST_F(QosProfilesTest, RefereeOperatorCommandsAreReliableAndNotReplayedToLateJoiners) {
  const auto writer = writer_qos("referee.command.writer");
  const auto reader = reader_qos("referee.command.reader");
  EXPECT_EQ(writer.reliability().kind, fdds::RELIABLE_RELIABILITY_QOS);
  EXPECT_EQ(reader.reliability().kind, fdds::RELIABLE_RELIABILITY_QOS);
  EXPECT_EQ(writer.durability().kind, fdds::VOLATILE_DURABILITY_QOS);
  EXPECT_EQ(writer.history().depth, 16);
}

TEST_F(QosProfilesTest, RobotCommandsHaveDeadlineAndLifespanOfOneHundredMilliseconds) {
  const auto writer = writer_qos("robot.commands.writer");
  EXPECT_EQ(writer.deadline().period, eprosima::fastrtps::Duration_t(0, 100'000'000));
  EXPECT_EQ(writer.lifespan().duration, eprosima::fastrtps::Duration_t(0, 100'000'000));
}

TEST_F(QosProfilesTest, EstopDeclaresLiveliness) {
  const auto writer = writer_qos("system.estop.writer");
  EXPECT_EQ(writer.liveliness().kind, fdds::AUTOMATIC_LIVELINESS_QOS);
  EXPECT_EQ(writer.liveliness().lease_duration, eprosima::fastrtps::Duration_t(1, 0));
}

TEST_F(QosProfilesTest, TeamPartitionsAreNamedAfterTheTeams) {
  auto* factory = fdds::DomainParticipantFactory::get_instance();
  auto* participant = factory->create_participant(202, fdds::PARTICIPANT_QOS_DEFAULT);
  for (const char* team : {"blue", "yellow"}) {
    fdds::PublisherQos publisher;
    ASSERT_EQ(participant->get_publisher_qos_from_profile(std::string("team.") + team + ".publisher", publisher),
              ReturnCode_t::RETCODE_OK);
    ASSERT_EQ(publisher.partition().size(), 1u);
    EXPECT_STREQ(publisher.partition().names()[0].c_str(), team);
    fdds::SubscriberQos subscriber;
    ASSERT_EQ(participant->get_subscriber_qos_from_profile(std::string("team.") + team + ".subscriber", subscriber),
              ReturnCode_t::RETCODE_OK);
    ASSERT_EQ(subscriber.partition().size(), 1u);
  }
  factory->delete_participant(participant);
}

}  // namespace
}  // namespace ssl::dds
