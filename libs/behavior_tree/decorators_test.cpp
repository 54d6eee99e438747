#include "libs/behavior_tree/decorators.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>

#include "libs/behavior_tree/builders.h"
#include "libs/behavior_tree/test_util.h"
#include "libs/behavior_tree/tree.h"

namespace ssl::bt {
namespace {

using namespace std::chrono_literals;
using ::testing::ElementsAre;
using testing::at_ms;
using testing::ScriptedLeaves;

using testing::kFailure;
using testing::kIdle;
using testing::kRunning;
using testing::kSuccess;

// ---- Inverter, Succeeder, Failer ----

TEST(BehaviorTreeInverterTest, SwapsSuccessAndFailureAndPassesRunning) {
  ScriptedLeaves leaves;
  Tree tree(inverter(leaves.make("Child")));
  EXPECT_EQ(tree.tick(at_ms(0)), kFailure);
  leaves["Child"].answer(kFailure);
  EXPECT_EQ(tree.tick(at_ms(10)), kSuccess);
  leaves["Child"].answer(kRunning);
  EXPECT_EQ(tree.tick(at_ms(20)), kRunning);
}

TEST(BehaviorTreeSucceederTest, TurnsEveryFinishedAnswerIntoSuccessAndPassesRunning) {
  ScriptedLeaves leaves;
  Tree tree(succeeder(leaves.make("Child", kFailure)));
  EXPECT_EQ(tree.tick(at_ms(0)), kSuccess);
  leaves["Child"].answer(kSuccess);
  EXPECT_EQ(tree.tick(at_ms(10)), kSuccess);
  leaves["Child"].answer(kRunning);
  EXPECT_EQ(tree.tick(at_ms(20)), kRunning);
}

TEST(BehaviorTreeFailerTest, TurnsEveryFinishedAnswerIntoFailureAndPassesRunning) {
  ScriptedLeaves leaves;
  Tree tree(failer(leaves.make("Child", kSuccess)));
  EXPECT_EQ(tree.tick(at_ms(0)), kFailure);
  leaves["Child"].answer(kFailure);
  EXPECT_EQ(tree.tick(at_ms(10)), kFailure);
  leaves["Child"].answer(kRunning);
  EXPECT_EQ(tree.tick(at_ms(20)), kRunning);
}

TEST(BehaviorTreeDecoratorTest, HaltingADecoratorHaltsItsRunningChild) {
  ScriptedLeaves leaves;
  Tree tree(inverter(leaves.make("Child", kRunning)));
  tree.tick(at_ms(0));
  leaves.take_log();
  tree.halt();
  EXPECT_THAT(leaves.take_log(), ElementsAre("halt Child"));
  EXPECT_EQ(tree.root().status(), kIdle);
}

// ---- Repeater ----

TEST(BehaviorTreeRepeaterTest, CompletesTheChildNTimesOneRunPerTick) {
  ScriptedLeaves leaves;
  Tree tree(repeater(leaves.make("Kick"), 3));
  EXPECT_EQ(tree.tick(at_ms(0)), kRunning);
  EXPECT_EQ(tree.tick(at_ms(10)), kRunning);
  EXPECT_EQ(tree.tick(at_ms(20)), kSuccess);
  EXPECT_EQ(leaves["Kick"].ticks(), 3);
}

TEST(BehaviorTreeRepeaterTest, ARunningChildDoesNotCountAsARun) {
  ScriptedLeaves leaves;
  Tree tree(repeater(leaves.make("Kick", kRunning), 2));
  EXPECT_EQ(tree.tick(at_ms(0)), kRunning);
  leaves["Kick"].answer(kSuccess);
  EXPECT_EQ(tree.tick(at_ms(10)), kRunning);
  EXPECT_EQ(tree.tick(at_ms(20)), kSuccess);
}

TEST(BehaviorTreeRepeaterTest, FailsWhenTheChildFailsAndCountsAgainFromZeroInTheNextRun) {
  ScriptedLeaves leaves;
  Tree tree(repeater(leaves.make("Kick"), 2));
  EXPECT_EQ(tree.tick(at_ms(0)), kRunning);
  leaves["Kick"].answer(kFailure);
  EXPECT_EQ(tree.tick(at_ms(10)), kFailure);

  leaves["Kick"].answer(kSuccess);
  EXPECT_EQ(tree.tick(at_ms(20)), kRunning);  // the first of two runs again, not the second
  EXPECT_EQ(tree.tick(at_ms(30)), kSuccess);
}

TEST(BehaviorTreeRepeaterTest, HaltRestartsTheCount) {
  ScriptedLeaves leaves;
  Tree tree(repeater(leaves.make("Kick"), 2));
  EXPECT_EQ(tree.tick(at_ms(0)), kRunning);
  tree.halt();
  EXPECT_EQ(tree.tick(at_ms(10)), kRunning);
  EXPECT_EQ(tree.tick(at_ms(20)), kSuccess);
}

TEST(BehaviorTreeRepeaterTest, ForeverNeverSucceedsButStillFailsWithTheChild) {
  ScriptedLeaves leaves;
  Tree tree(repeat_forever(leaves.make("Patrol")));
  for (int i = 0; i < 100; ++i) ASSERT_EQ(tree.tick(at_ms(i)), kRunning);
  EXPECT_EQ(leaves["Patrol"].ticks(), 100);
  leaves["Patrol"].answer(kFailure);
  EXPECT_EQ(tree.tick(at_ms(100)), kFailure);
}

TEST(BehaviorTreeRepeaterTest, RejectsZeroRepetitions) {
  ScriptedLeaves leaves;
  EXPECT_THROW(repeater(leaves.make("Kick"), 0), std::invalid_argument);
}

// ---- RetryUntilSuccessful ----

TEST(BehaviorTreeRetryTest, SucceedsAsSoonAsTheChildSucceeds) {
  ScriptedLeaves leaves;
  Tree tree(retry_until_successful(leaves.make("Connect", kFailure), 3));
  EXPECT_EQ(tree.tick(at_ms(0)), kRunning);
  leaves["Connect"].answer(kSuccess);
  EXPECT_EQ(tree.tick(at_ms(10)), kSuccess);
}

TEST(BehaviorTreeRetryTest, FailsAfterTheLastAllowedAttemptOneAttemptPerTick) {
  ScriptedLeaves leaves;
  Tree tree(retry_until_successful(leaves.make("Connect", kFailure), 3));
  EXPECT_EQ(tree.tick(at_ms(0)), kRunning);
  EXPECT_EQ(tree.tick(at_ms(10)), kRunning);
  EXPECT_EQ(tree.tick(at_ms(20)), kFailure);
  EXPECT_EQ(leaves["Connect"].ticks(), 3);

  EXPECT_EQ(tree.tick(at_ms(30)), kRunning);  // a new run has all its attempts again
}

TEST(BehaviorTreeRetryTest, ARunningAttemptIsNotAFailedAttempt) {
  ScriptedLeaves leaves;
  Tree tree(retry_until_successful(leaves.make("Connect", kRunning), 1));
  EXPECT_EQ(tree.tick(at_ms(0)), kRunning);
  EXPECT_EQ(tree.tick(at_ms(10)), kRunning);
  leaves["Connect"].answer(kFailure);
  EXPECT_EQ(tree.tick(at_ms(20)), kFailure);
}

TEST(BehaviorTreeRetryTest, RejectsZeroAttempts) {
  ScriptedLeaves leaves;
  EXPECT_THROW(retry_until_successful(leaves.make("Connect"), 0), std::invalid_argument);
}

// ---- Timeout ----

TEST(BehaviorTreeTimeoutTest, FailsAndHaltsTheChildWhenNowReachesTheLimit) {
  ScriptedLeaves leaves;
  Tree tree(timeout(leaves.make("Chase", kRunning), 2s));
  EXPECT_EQ(tree.tick(at_ms(1'000)), kRunning);
  EXPECT_EQ(tree.tick(at_ms(2'999)), kRunning);
  leaves.take_log();

  EXPECT_EQ(tree.tick(at_ms(3'000)), kFailure);
  EXPECT_THAT(leaves.take_log(), ElementsAre("halt Chase"));  // halted instead of ticked
  EXPECT_EQ(leaves["Chase"].status(), kIdle);
}

TEST(BehaviorTreeTimeoutTest, PassesTheChildsAnswerWhenItFinishesInTime) {
  ScriptedLeaves leaves;
  Tree tree(timeout(leaves.make("Chase", kRunning), 2s));
  EXPECT_EQ(tree.tick(at_ms(0)), kRunning);
  leaves["Chase"].answer(kSuccess);
  EXPECT_EQ(tree.tick(at_ms(1'999)), kSuccess);
  EXPECT_EQ(leaves["Chase"].halts(), 0);
}

TEST(BehaviorTreeTimeoutTest, EachRunStartsItsOwnClock) {
  ScriptedLeaves leaves;
  Tree tree(timeout(leaves.make("Chase"), 100ms));
  EXPECT_EQ(tree.tick(at_ms(0)), kSuccess);
  leaves["Chase"].answer(kRunning);
  EXPECT_EQ(tree.tick(at_ms(500)), kRunning);  // a new run: started at 500 ms, not at 0
  EXPECT_EQ(tree.tick(at_ms(599)), kRunning);
  EXPECT_EQ(tree.tick(at_ms(600)), kFailure);
}

TEST(BehaviorTreeTimeoutTest, AlwaysTicksTheChildOnTheFirstTickOfARun) {
  ScriptedLeaves leaves;
  Tree tree(timeout(leaves.make("Chase", kRunning), 1ns));
  EXPECT_EQ(tree.tick(at_ms(0)), kRunning);
  EXPECT_EQ(leaves["Chase"].ticks(), 1);
  EXPECT_EQ(tree.tick(at_ms(0) + 1ns), kFailure);
}

TEST(BehaviorTreeTimeoutTest, AHaltedTimeoutStartsAFreshRun) {
  ScriptedLeaves leaves;
  Tree tree(timeout(leaves.make("Chase", kRunning), 100ms));
  tree.tick(at_ms(0));
  tree.halt();
  EXPECT_EQ(tree.tick(at_ms(1'000)), kRunning);
  EXPECT_EQ(tree.tick(at_ms(1'099)), kRunning);
}

TEST(BehaviorTreeTimeoutTest, RejectsANonPositiveLimit) {
  ScriptedLeaves leaves;
  EXPECT_THROW(timeout(leaves.make("Chase"), 0s), std::invalid_argument);
  EXPECT_THROW(timeout(leaves.make("Chase2"), -1ms), std::invalid_argument);
}

TEST(BehaviorTreeTimeoutTest, DescribesItsLimitCompactly) {
  EXPECT_EQ(compact_duration(2s), "2s");
  EXPECT_EQ(compact_duration(1500ms), "1500ms");
  EXPECT_EQ(compact_duration(250us), "250us");
  EXPECT_EQ(compact_duration(10ns), "10ns");
  ScriptedLeaves leaves;
  EXPECT_EQ(timeout(leaves.make("Chase"), 150ms)->parameters(), "150ms");
}

TEST(BehaviorTreeDecoratorTest, RejectsANullChild) {
  EXPECT_THROW(inverter(nullptr), std::invalid_argument);
  EXPECT_THROW(timeout(nullptr, 1s), std::invalid_argument);
}

TEST(BehaviorTreeDecoratorTest, ATimeoutOnlyCountsTimeWithinARun) {
  ScriptedLeaves leaves;
  Tree tree(timeout(leaves.make("Quick"), 1s));
  tree.tick(at_ms(0));
  tree.tick(at_ms(5'000));  // the previous run finished, so no timeout fires
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick Quick", "tick Quick"));
}

}  // namespace
}  // namespace ssl::bt
