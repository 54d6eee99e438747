#include "libs/behavior_tree/composites.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "libs/behavior_tree/builders.h"
#include "libs/behavior_tree/test_util.h"
#include "libs/behavior_tree/tree.h"

namespace ssl::bt {
namespace {

using ::testing::ElementsAre;
using ::testing::IsEmpty;
using testing::at_ms;
using testing::ScriptedLeaves;

using testing::kFailure;
using testing::kIdle;
using testing::kRunning;
using testing::kSuccess;

// ---- Sequence (with memory) ----

TEST(BehaviorTreeSequenceTest, SucceedsWhenEveryChildSucceeds) {
  ScriptedLeaves leaves;
  Tree tree(sequence("Root", {leaves.make("A"), leaves.make("B"), leaves.make("C")}));
  EXPECT_EQ(tree.tick(at_ms(0)), kSuccess);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick A", "tick B", "tick C"));
}

TEST(BehaviorTreeSequenceTest, FailsAtTheFirstFailureWithoutTickingLaterChildren) {
  ScriptedLeaves leaves;
  Tree tree(sequence("Root", {leaves.make("A"), leaves.make("B", kFailure), leaves.make("C")}));
  EXPECT_EQ(tree.tick(at_ms(0)), kFailure);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick A", "tick B"));
  EXPECT_EQ(leaves["C"].status(), kIdle);
}

TEST(BehaviorTreeSequenceTest, ResumesAtTheRunningChildWithoutRecheckingEarlierChildren) {
  ScriptedLeaves leaves;
  Tree tree(sequence("Root", {leaves.make("A"), leaves.make("B", kRunning), leaves.make("C")}));
  EXPECT_EQ(tree.tick(at_ms(0)), kRunning);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick A", "tick B"));

  leaves["A"].answer(kFailure);  // would fail the sequence if it were re-checked
  EXPECT_EQ(tree.tick(at_ms(10)), kRunning);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick B"));

  leaves["B"].answer(kSuccess);
  EXPECT_EQ(tree.tick(at_ms(20)), kSuccess);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick B", "tick C"));
}

TEST(BehaviorTreeSequenceTest, StartsAgainAtTheFirstChildAfterFinishing) {
  ScriptedLeaves leaves;
  Tree tree(sequence("Root", {leaves.make("A"), leaves.make("B", kFailure)}));
  EXPECT_EQ(tree.tick(at_ms(0)), kFailure);
  leaves.take_log();
  EXPECT_EQ(tree.tick(at_ms(10)), kFailure);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick A", "tick B"));
}

TEST(BehaviorTreeSequenceTest, HaltHaltsTheRunningChildAndTheNextRunStartsAtTheFirstChild) {
  ScriptedLeaves leaves;
  Tree tree(sequence("Root", {leaves.make("A"), leaves.make("B", kRunning)}));
  tree.tick(at_ms(0));
  leaves.take_log();

  tree.halt();
  EXPECT_THAT(leaves.take_log(), ElementsAre("halt B"));
  EXPECT_EQ(tree.root().status(), kIdle);
  EXPECT_EQ(leaves["B"].status(), kIdle);
  EXPECT_EQ(leaves["A"].status(), kSuccess);  // finished nodes keep their last answer for debugging

  tree.tick(at_ms(10));
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick A", "tick B"));
}

// ---- ReactiveSequence ----

TEST(BehaviorTreeReactiveSequenceTest, RechecksEarlierChildrenOnEveryTick) {
  ScriptedLeaves leaves;
  Tree tree(reactive_sequence("Root", {leaves.make("Check"), leaves.make("Work", kRunning)}));
  EXPECT_EQ(tree.tick(at_ms(0)), kRunning);
  EXPECT_EQ(tree.tick(at_ms(10)), kRunning);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick Check", "tick Work", "tick Check", "tick Work"));
}

TEST(BehaviorTreeReactiveSequenceTest, HaltsTheRunningLaterChildWhenAnEarlierChildFails) {
  ScriptedLeaves leaves;
  Tree tree(reactive_sequence("Root", {leaves.make("Check"), leaves.make("Work", kRunning)}));
  tree.tick(at_ms(0));
  leaves.take_log();

  leaves["Check"].answer(kFailure);
  EXPECT_EQ(tree.tick(at_ms(10)), kFailure);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick Check", "halt Work"));
  EXPECT_EQ(leaves["Work"].status(), kIdle);
}

TEST(BehaviorTreeReactiveSequenceTest, HaltsTheRunningLaterChildWhenAnEarlierChildRuns) {
  ScriptedLeaves leaves;
  Tree tree(reactive_sequence("Root", {leaves.make("First"), leaves.make("Second", kRunning)}));
  tree.tick(at_ms(0));
  leaves.take_log();

  leaves["First"].answer(kRunning);
  EXPECT_EQ(tree.tick(at_ms(10)), kRunning);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick First", "halt Second"));
}

// ---- Selector (with memory) ----

TEST(BehaviorTreeSelectorTest, SucceedsAtTheFirstSuccessWithoutTickingLaterChildren) {
  ScriptedLeaves leaves;
  Tree tree(selector("Root", {leaves.make("A", kFailure), leaves.make("B"), leaves.make("C")}));
  EXPECT_EQ(tree.tick(at_ms(0)), kSuccess);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick A", "tick B"));
}

TEST(BehaviorTreeSelectorTest, FailsWhenEveryChildFails) {
  ScriptedLeaves leaves;
  Tree tree(selector("Root", {leaves.make("A", kFailure), leaves.make("B", kFailure)}));
  EXPECT_EQ(tree.tick(at_ms(0)), kFailure);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick A", "tick B"));
}

TEST(BehaviorTreeSelectorTest, ResumesAtTheRunningChildWithoutRetryingEarlierChildren) {
  ScriptedLeaves leaves;
  Tree tree(selector("Root", {leaves.make("PlanA", kFailure), leaves.make("PlanB", kRunning)}));
  EXPECT_EQ(tree.tick(at_ms(0)), kRunning);
  leaves.take_log();

  leaves["PlanA"].answer(kSuccess);  // would win if it were re-tried
  EXPECT_EQ(tree.tick(at_ms(10)), kRunning);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick PlanB"));

  leaves["PlanB"].answer(kFailure);
  EXPECT_EQ(tree.tick(at_ms(20)), kFailure);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick PlanB"));
}

// ---- ReactiveSelector ----

TEST(BehaviorTreeReactiveSelectorTest, EarlierChildThatNowSucceedsPreemptsTheRunningLaterChild) {
  ScriptedLeaves leaves;
  Tree tree(reactive_selector("Root", {leaves.make("Urgent", kFailure), leaves.make("Default", kRunning)}));
  EXPECT_EQ(tree.tick(at_ms(0)), kRunning);
  leaves.take_log();

  leaves["Urgent"].answer(kSuccess);
  EXPECT_EQ(tree.tick(at_ms(10)), kSuccess);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick Urgent", "halt Default"));
  EXPECT_EQ(leaves["Default"].status(), kIdle);
}

TEST(BehaviorTreeReactiveSelectorTest, EarlierChildThatNowRunsPreemptsTheRunningLaterChild) {
  ScriptedLeaves leaves;
  Tree tree(reactive_selector("Root", {leaves.make("Urgent", kFailure), leaves.make("Default", kRunning)}));
  tree.tick(at_ms(0));
  leaves.take_log();

  leaves["Urgent"].answer(kRunning);
  EXPECT_EQ(tree.tick(at_ms(10)), kRunning);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick Urgent", "halt Default"));
}

TEST(BehaviorTreeReactiveSelectorTest, KeepsTheLaterChildRunningWhileEarlierChildrenFail) {
  ScriptedLeaves leaves;
  Tree tree(reactive_selector("Root", {leaves.make("Urgent", kFailure), leaves.make("Default", kRunning)}));
  tree.tick(at_ms(0));
  tree.tick(at_ms(10));
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick Urgent", "tick Default", "tick Urgent", "tick Default"));
  EXPECT_EQ(leaves["Default"].halts(), 0);
}

// ---- Parallel ----

TEST(BehaviorTreeParallelTest, SuccessOnAllWaitsForEveryChildAndDoesNotRetickFinishedOnes) {
  ScriptedLeaves leaves;
  Tree tree(parallel("Root", ParallelPolicy::kSuccessOnAll,
                     {leaves.make("Fast"), leaves.make("Slow", kRunning)}));
  EXPECT_EQ(tree.tick(at_ms(0)), kRunning);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick Fast", "tick Slow"));

  leaves["Fast"].answer(kFailure);  // finished already: must not be asked again in this run
  EXPECT_EQ(tree.tick(at_ms(10)), kRunning);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick Slow"));

  leaves["Slow"].answer(kSuccess);
  EXPECT_EQ(tree.tick(at_ms(20)), kSuccess);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick Slow"));
}

TEST(BehaviorTreeParallelTest, SuccessOnAllFailsAtTheFirstFailureAndHaltsTheRunningChildren) {
  ScriptedLeaves leaves;
  Tree tree(parallel("Root", ParallelPolicy::kSuccessOnAll,
                     {leaves.make("A", kRunning), leaves.make("B", kFailure), leaves.make("C", kRunning)}));
  EXPECT_EQ(tree.tick(at_ms(0)), kFailure);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick A", "tick B", "halt A"));
  EXPECT_EQ(leaves["A"].status(), kIdle);
  EXPECT_EQ(leaves["C"].ticks(), 0);
}

TEST(BehaviorTreeParallelTest, SuccessOnOneSucceedsAtTheFirstSuccessAndHaltsTheRunningChildren) {
  ScriptedLeaves leaves;
  Tree tree(parallel("Root", ParallelPolicy::kSuccessOnOne,
                     {leaves.make("Search", kRunning), leaves.make("Aim", kRunning)}));
  EXPECT_EQ(tree.tick(at_ms(0)), kRunning);
  leaves.take_log();

  leaves["Aim"].answer(kSuccess);
  EXPECT_EQ(tree.tick(at_ms(10)), kSuccess);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick Search", "tick Aim", "halt Search"));
}

TEST(BehaviorTreeParallelTest, SuccessOnOneFailsOnlyOnceEveryChildFailed) {
  ScriptedLeaves leaves;
  Tree tree(parallel("Root", ParallelPolicy::kSuccessOnOne,
                     {leaves.make("A", kFailure), leaves.make("B", kRunning)}));
  EXPECT_EQ(tree.tick(at_ms(0)), kRunning);
  leaves["B"].answer(kFailure);
  EXPECT_EQ(tree.tick(at_ms(10)), kFailure);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick A", "tick B", "tick B"));
}

TEST(BehaviorTreeParallelTest, TicksEveryChildAgainInTheNextRun) {
  ScriptedLeaves leaves;
  Tree tree(parallel("Root", ParallelPolicy::kSuccessOnAll, {leaves.make("A"), leaves.make("B")}));
  EXPECT_EQ(tree.tick(at_ms(0)), kSuccess);
  EXPECT_EQ(tree.tick(at_ms(10)), kSuccess);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick A", "tick B", "tick A", "tick B"));
}

TEST(BehaviorTreeParallelTest, HaltHaltsEveryRunningChild) {
  ScriptedLeaves leaves;
  Tree tree(parallel("Root", ParallelPolicy::kSuccessOnAll,
                     {leaves.make("A", kRunning), leaves.make("B"), leaves.make("C", kRunning)}));
  tree.tick(at_ms(0));
  leaves.take_log();
  tree.halt();
  EXPECT_THAT(leaves.take_log(), ElementsAre("halt A", "halt C"));
}

// ---- all composites ----

TEST(BehaviorTreeCompositeTest, RejectsACompositeWithoutChildren) {
  EXPECT_THROW(Sequence("Empty", {}), std::invalid_argument);
  EXPECT_THROW(ReactiveSelector("Empty", {}), std::invalid_argument);
  EXPECT_THROW(Parallel("Empty", ParallelPolicy::kSuccessOnOne, {}), std::invalid_argument);
}

TEST(BehaviorTreeCompositeTest, RejectsANullChild) {
  std::vector<NodePtr> children;
  children.push_back(nullptr);
  EXPECT_THROW(Selector("Root", std::move(children)), std::invalid_argument);
}

TEST(BehaviorTreeCompositeTest, NestedHaltReachesTheRunningLeafAndLeavesNothingRunning) {
  ScriptedLeaves leaves;
  Tree tree(reactive_selector("Root", {
      leaves.make("Interrupt", kFailure),
      sequence("Plan", {
          leaves.make("Step1"),
          selector("Step2", {leaves.make("Deep", kRunning)}),
      }),
  }));
  EXPECT_EQ(tree.tick(at_ms(0)), kRunning);
  leaves.take_log();

  leaves["Interrupt"].answer(kSuccess);
  EXPECT_EQ(tree.tick(at_ms(10)), kSuccess);
  EXPECT_THAT(leaves.take_log(), ElementsAre("tick Interrupt", "halt Deep"));
  for (const NodeSnapshot& row : tree.snapshot()) {
    EXPECT_NE(row.status, kRunning) << row.path;
  }
}

TEST(BehaviorTreeCompositeTest, HaltingANodeThatIsNotRunningDoesNothing) {
  ScriptedLeaves leaves;
  Tree tree(sequence("Root", {leaves.make("A")}));
  tree.tick(at_ms(0));
  leaves.take_log();
  tree.halt();
  EXPECT_THAT(leaves.take_log(), IsEmpty());
  EXPECT_EQ(tree.root().status(), kSuccess);
}

}  // namespace
}  // namespace ssl::bt
