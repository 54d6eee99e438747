#include "tests/support/process.h"

#include <gtest/gtest.h>
#include <signal.h>

namespace ssl::testing {
namespace {

using std::chrono::seconds;

TEST(ChildProcessTest, ReadsStdoutLinesAndExitCode) {
  auto child = ChildProcess::start("/bin/sh", {"-c", "echo first; echo second; exit 3"});
  ASSERT_TRUE(child) << child.error().message;
  EXPECT_EQ(child->read_line(seconds(10)), "first");
  EXPECT_EQ(child->read_line(seconds(10)), "second");
  EXPECT_EQ(child->wait(seconds(10)), 3);
}

TEST(ChildProcessTest, ReadLineTimesOutOnASilentChildAndSignalEndsIt) {
  auto child = ChildProcess::start("/bin/sleep", {"30"});
  ASSERT_TRUE(child);
  EXPECT_EQ(child->read_line(std::chrono::milliseconds(50)), std::nullopt);
  child->signal(SIGTERM);
  EXPECT_EQ(child->wait(seconds(10)), 128 + SIGTERM);
}

TEST(ChildProcessTest, MissingProgramIsAnError) {
  auto child = ChildProcess::start("/no/such/program", {});
  ASSERT_FALSE(child);
  EXPECT_NE(child.error().message.find("/no/such/program"), std::string::npos);
}

}  // namespace
}  // namespace ssl::testing
