#include "libs/dds/health.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace ssl::dds
