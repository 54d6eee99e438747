#include "libs/behavior_tree/builders.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

#include "libs/behavior_tree/test_util.h"
#include "libs/behavior_tree/tree.h"

namespace ssl::bt {
namespace {

using namespace std::chrono_literals;
using testing::ScriptedLeaves;

NodePtr succeed(const std::string& name) {
  return action(name, [](LeafContext&) { return NodeStatus::kSuccess; });
}

TEST(BehaviorTreeBuildersTest, EachBuilderMakesItsNodeType) {
  const auto type_of = [](const NodePtr& node) { return std::string(node->type_name()); };
  EXPECT_EQ(type_of(sequence("S", {succeed("A")})), "Sequence");
  EXPECT_EQ(type_of(reactive_sequence("S", {succeed("A")})), "ReactiveSequence");
  EXPECT_EQ(type_of(selector("S", {succeed("A")})), "Selector");
  EXPECT_EQ(type_of(reactive_selector("S", {succeed("A")})), "ReactiveSelector");
  EXPECT_EQ(type_of(parallel("P", ParallelPolicy::kSuccessOnAll, {succeed("A")})), "Parallel");
  EXPECT_EQ(type_of(succeed("A")), "Action");
  EXPECT_EQ(type_of(condition("C?", [](const LeafContext&) { return true; })), "Condition");
  EXPECT_EQ(type_of(inverter(succeed("A"))), "Inverter");
  EXPECT_EQ(type_of(succeeder(succeed("A"))), "Succeeder");
  EXPECT_EQ(type_of(failer(succeed("A"))), "Failer");
  EXPECT_EQ(type_of(repeater(succeed("A"), 2)), "Repeater");
  EXPECT_EQ(type_of(repeat_forever(succeed("A"))), "Repeater");
  EXPECT_EQ(type_of(retry_until_successful(succeed("A"), 2)), "RetryUntilSuccessful");
  EXPECT_EQ(type_of(timeout(succeed("A"), 1s)), "Timeout");
}

TEST(BehaviorTreeBuildersTest, DecoratorsAreNamedAfterTheirTypeUnlessNamed) {
  EXPECT_EQ(inverter(succeed("A"))->name(), "Inverter");
  EXPECT_EQ(inverter(succeed("A"), "NotA")->name(), "NotA");
  EXPECT_EQ(timeout(succeed("A"), 2s, "GiveUp")->name(), "GiveUp");
}

TEST(BehaviorTreeBuildersTest, ParametersDescribeTheSettings) {
  EXPECT_EQ(parallel("P", ParallelPolicy::kSuccessOnOne, {succeed("A")})->parameters(), "success on one");
  EXPECT_EQ(parallel("P", ParallelPolicy::kSuccessOnAll, {succeed("A")})->parameters(), "success on all");
  EXPECT_EQ(repeater(succeed("A"), 1)->parameters(), "1 time");
  EXPECT_EQ(repeater(succeed("A"), 3)->parameters(), "3 times");
  EXPECT_EQ(repeat_forever(succeed("A"))->parameters(), "forever");
  EXPECT_EQ(retry_until_successful(succeed("A"), 4)->parameters(), "4 attempts");
  EXPECT_EQ(timeout(succeed("A"), 2s)->parameters(), "2s");
  EXPECT_EQ(sequence("S", {succeed("A")})->parameters(), "");
}

TEST(BehaviorTreeBuildersTest, CompositesKeepTheChildOrderOfBracesAndOfVectors) {
  const NodePtr braced = sequence("S", {succeed("A"), succeed("B"), succeed("C")});
  ASSERT_EQ(braced->child_count(), 3u);
  EXPECT_EQ(braced->child(0).name(), "A");
  EXPECT_EQ(braced->child(2).name(), "C");

  std::vector<NodePtr> generated;
  for (int robot = 0; robot < 4; ++robot) generated.push_back(succeed("Robot" + std::to_string(robot)));
  const NodePtr from_vector = parallel("Team", ParallelPolicy::kSuccessOnAll, std::move(generated));
  ASSERT_EQ(from_vector->child_count(), 4u);
  EXPECT_EQ(from_vector->child(3).name(), "Robot3");
}

TEST(BehaviorTreeBuildersTest, ABuiltTreeReadsLikeItsDrawingAndRuns) {
  ScriptedLeaves leaves;
  Tree tree(reactive_selector("Striker", {
      sequence("Shoot", {
          inverter(leaves.make("BallLost")),
          timeout(leaves.make("Kick"), 2s),
      }),
      leaves.make("GoToBall"),
  }));
  EXPECT_EQ(tree.tick(testing::at_ms(0)), NodeStatus::kSuccess);
  EXPECT_EQ(leaves["Kick"].ticks(), 0);  // BallLost succeeded, so the inverter failed the sequence
  EXPECT_EQ(leaves["GoToBall"].ticks(), 1);
}

}  // namespace
}  // namespace ssl::bt
