#include "libs/behavior_tree/leaves.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>

#include "libs/behavior_tree/builders.h"
#include "libs/behavior_tree/test_util.h"
#include "libs/behavior_tree/tree.h"

namespace ssl::bt {
namespace {

using testing::at_ms;

TEST(BehaviorTreeActionTest, TheCallableSeesTheTickTimeAndNumber) {
  time::Timestamp seen_now;
  std::uint64_t seen_tick = 0;
  Tree tree(action("Probe", [&](LeafContext& leaf) {
    seen_now = leaf.now();
    seen_tick = leaf.tick_number();
    return NodeStatus::kSuccess;
  }));
  tree.tick(at_ms(5));
  tree.tick(at_ms(17));
  EXPECT_EQ(seen_now, at_ms(17));
  EXPECT_EQ(seen_tick, 2u);
}

TEST(BehaviorTreeActionTest, TheHaltCallableRunsOnlyWhenTheActionIsHaltedWhileRunning) {
  NodeStatus answer = NodeStatus::kSuccess;
  int halts = 0;
  Tree tree(action("Drive", [&](LeafContext&) { return answer; }, {}, [&] { ++halts; }));
  tree.tick(at_ms(0));
  tree.halt();
  EXPECT_EQ(halts, 0);

  answer = NodeStatus::kRunning;
  tree.tick(at_ms(10));
  tree.halt();
  EXPECT_EQ(halts, 1);
  EXPECT_EQ(tree.root().status(), NodeStatus::kIdle);
}

TEST(BehaviorTreeActionTest, AnActionWithoutHaltCallableCanBeHalted) {
  Tree tree(action("Drive", [](LeafContext&) { return NodeStatus::kRunning; }));
  tree.tick(at_ms(0));
  tree.halt();
  EXPECT_EQ(tree.root().status(), NodeStatus::kIdle);
}

TEST(BehaviorTreeActionTest, AnsweringIdleIsABugReportedAsLogicError) {
  Tree tree(action("Broken", [](LeafContext&) { return NodeStatus::kIdle; }));
  try {
    tree.tick(at_ms(0));
    FAIL() << "expected std::logic_error";
  } catch (const std::logic_error& error) {
    EXPECT_STREQ(error.what(),
                 "node 'Broken' answered IDLE to a tick; a tick must answer RUNNING, SUCCESS or FAILURE");
  }
}

TEST(BehaviorTreeActionTest, RejectsAnEmptyCallableAndABadName) {
  EXPECT_THROW(action("Nothing", nullptr), std::invalid_argument);
  EXPECT_THROW(action("", [](LeafContext&) { return NodeStatus::kSuccess; }), std::invalid_argument);
  EXPECT_THROW(action("a/b", [](LeafContext&) { return NodeStatus::kSuccess; }), std::invalid_argument);
}

TEST(BehaviorTreeConditionTest, TrueIsSuccessAndFalseIsFailure) {
  bool ball_visible = true;
  Tree tree(condition("BallVisible?", [&](const LeafContext&) { return ball_visible; }));
  EXPECT_EQ(tree.tick(at_ms(0)), NodeStatus::kSuccess);
  ball_visible = false;
  EXPECT_EQ(tree.tick(at_ms(10)), NodeStatus::kFailure);
}

TEST(BehaviorTreeConditionTest, RejectsWritePortsAndAnEmptyCallable) {
  constexpr Key<int> kCount{"count"};
  try {
    condition("Counts?", [](const LeafContext&) { return true; }, {writes(kCount)});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "condition 'Counts?' declares a write port for key 'count'; "
                 "conditions only read (make it an action)");
  }
  EXPECT_THROW(condition("Nothing?", nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace ssl::bt
