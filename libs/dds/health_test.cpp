#include "libs/dds/health.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <thread>

namespace ssl::dds {
namespace {

TEST(HealthReporterTest, PublishesAKeyedSampleWithCountersAndStamps) {
  auto participant = Participant::create({.domain_id = 115, .name = "health_test"});
  ASSERT_TRUE(participant) << participant.error().message;
  auto reader = participant->make_reader(topics::kSystemHealth);
  auto reporter = HealthReporter::create(*participant, "simulator");
  ASSERT_TRUE(reader && reporter);
  ASSERT_TRUE(reader->wait_for_match(1, std::chrono::seconds(10)));

  ASSERT_TRUE(reporter->publish({.level = HealthLevel::kWarn,
                                 .status = "stale vision",
                                 .rate_hz = 75,
                                 .errors = 2,
                                 .dropped = 5,
                                 .counters = {{"malformed_packets", 5}}})
                  .ok());
  ASSERT_TRUE(reader->wait_for_data(std::chrono::seconds(10)));
  const auto samples = reader->take();
  ASSERT_EQ(samples.size(), 1u);
  const auto& health = samples[0].data;
  EXPECT_EQ(health.service(), "simulator");
  EXPECT_EQ(health.level(), idl::system::HEALTH_WARN);
  EXPECT_EQ(health.status(), "stale vision");
  EXPECT_DOUBLE_EQ(health.rate_hz(), 75);
  EXPECT_EQ(health.dropped(), 5u);
  ASSERT_EQ(health.counters().size(), 1u);
  EXPECT_EQ(health.counters()[0].name(), "malformed_packets");
  EXPECT_EQ(health.counters()[0].value(), 5u);
  EXPECT_GT(health.stamp_unix_ns(), 0);
  EXPECT_GE(health.uptime_ns(), 0);
}

TEST(HealthReporterTest, ReportsEveryTenthOfASecondUntilTheFirstHealthyReportThenEverySecond) {
  auto participant = Participant::create({.domain_id = 118, .name = "health_test"});
  ASSERT_TRUE(participant) << participant.error().message;
  auto reporter = HealthReporter::create(*participant, "planner/blue");
  ASSERT_TRUE(reporter);
  EXPECT_EQ(reporter->period(), HealthReporter::kStartupPeriod);
  ASSERT_TRUE(reporter->publish({.level = HealthLevel::kWarn, .status = "no world state"}).ok());
  EXPECT_EQ(reporter->period(), HealthReporter::kStartupPeriod);
  ASSERT_TRUE(reporter->publish({.level = HealthLevel::kOk, .status = "running"}).ok());
  EXPECT_EQ(reporter->period(), HealthReporter::kPeriod);
  ASSERT_TRUE(reporter->publish({.level = HealthLevel::kWarn, .status = "no world state"}).ok());
  EXPECT_EQ(reporter->period(), HealthReporter::kPeriod) << "only while starting";
}

TEST(HealthReporterTest, AServiceThatNeverGetsHealthyFallsBackToOneReportASecond) {
  auto participant = Participant::create({.domain_id = 126, .name = "health_test"});
  ASSERT_TRUE(participant) << participant.error().message;
  auto reporter = HealthReporter::create(*participant, "planner/blue");
  ASSERT_TRUE(reporter);
  for (int i = 0; i + 1 < HealthReporter::kStartupReports; ++i) {
    ASSERT_TRUE(reporter->publish({.level = HealthLevel::kWarn, .status = "no world state"}).ok());
  }
  EXPECT_EQ(reporter->period(), HealthReporter::kStartupPeriod);
  ASSERT_TRUE(reporter->publish({.level = HealthLevel::kWarn, .status = "no world state"}).ok());
  EXPECT_EQ(reporter->period(), HealthReporter::kPeriod);
}

TEST(HealthReporterDeathTest, AReportLongerThanTheLeaseAfterThePreviousOneEndsTheProcessForAFreshStart) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        auto participant = Participant::create({.domain_id = 117, .name = "health_test"});
        if (!participant) std::_Exit(1);
        auto reporter = HealthReporter::create(*participant, "planner/blue");
        if (!reporter) std::_Exit(1);
        reporter->exit_when_stalled();
        if (!reporter->publish({.status = "running"}).ok()) std::_Exit(2);  // within the lease: goes on
        std::this_thread::sleep_for(participant->lease_duration() + std::chrono::milliseconds(100));  // the stall
        (void)reporter->publish({.status = "running"});
        std::_Exit(0);
      },
      testing::ExitedWithCode(HealthReporter::kExitStalled), "stood still .* longer than the DDS lease");
}

TEST(HealthReporterTest, TheLeaseIsTheProfilesThreeSeconds) {
  auto participant = Participant::create({.domain_id = 129, .name = "health_test"});
  ASSERT_TRUE(participant) << participant.error().message;
  EXPECT_EQ(participant->lease_duration(), std::chrono::seconds(3));
}

}  // namespace
}  // namespace ssl::dds
