#include "libs/common/shutdown.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

namespace ssl {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

TEST(ShutdownSignalTest, NotRequestedUntilSomethingAsks) {
  ShutdownSignal shutdown;
  EXPECT_FALSE(shutdown.requested());
  EXPECT_FALSE(shutdown.wait_for(milliseconds(20)));
}

TEST(ShutdownSignalTest, SigtermToTheProcessRequestsStopAndNamesTheSignal) {
  ShutdownSignal shutdown;
  ASSERT_EQ(kill(getpid(), SIGTERM), 0);
  EXPECT_TRUE(shutdown.wait_for(seconds(10)));
  EXPECT_EQ(shutdown.signal_number(), SIGTERM);
}

TEST(ShutdownSignalTest, SigintToTheProcessRequestsStop) {
  ShutdownSignal shutdown;
  ASSERT_EQ(kill(getpid(), SIGINT), 0);
  EXPECT_TRUE(shutdown.wait_for(seconds(10)));
  EXPECT_EQ(shutdown.signal_number(), SIGINT);
}

TEST(ShutdownSignalTest, RequestFromAnotherThreadWakesAWaiter) {
  ShutdownSignal shutdown;
  std::thread requester([&] { shutdown.request(); });
  shutdown.wait();
  requester.join();
  EXPECT_TRUE(shutdown.requested());
  EXPECT_EQ(shutdown.signal_number(), 0);
}

}  // namespace
}  // namespace ssl
