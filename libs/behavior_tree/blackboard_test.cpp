#include "libs/behavior_tree/blackboard.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "libs/behavior_tree/builders.h"
#include "libs/behavior_tree/test_util.h"
#include "libs/behavior_tree/tree.h"

namespace ssl::bt {
namespace {

using ::testing::HasSubstr;
using testing::at_ms;

constexpr Key<double> kBallSpeed{"ball_speed"};
constexpr Key<int> kReceiver{"receiver"};
constexpr Key<std::vector<int>> kFormation{"formation"};

struct Point {
  double x = 0.0;
  double y = 0.0;
};

/// An action that answers SUCCESS and does nothing; it only declares `ports`.
NodePtr declaring(const std::string& name, Ports ports) {
  return action(name, [](LeafContext&) { return NodeStatus::kSuccess; }, std::move(ports));
}

/// A condition callable that reads `key`, keeps the error message (if any) in `message` and answers
/// whether the read worked.
template <typename T>
ConditionFunction reading(Key<T> key, std::string& message) {
  return [key, &message](const LeafContext& leaf) {
    const Result<T> value = leaf.get(key);
    if (!value) message = value.error().message;
    return value.ok();
  };
}

TEST(BehaviorTreeBlackboardTest, TheOwnerWritesAndReadsDeclaredKeys) {
  Tree tree(declaring("Root", {reads(kBallSpeed), writes(kReceiver)}));
  ASSERT_TRUE(tree.blackboard().set(kBallSpeed, 2.5).ok());
  ASSERT_TRUE(tree.blackboard().set(kReceiver, 4).ok());
  EXPECT_EQ(*tree.blackboard().get(kBallSpeed), 2.5);
  EXPECT_EQ(*tree.blackboard().get(kReceiver), 4);
}

TEST(BehaviorTreeBlackboardTest, ReadingAnUnsetKeyIsAnError) {
  Tree tree(declaring("Root", {reads(kBallSpeed)}));
  const Result<double> speed = tree.blackboard().get(kBallSpeed);
  ASSERT_FALSE(speed);
  EXPECT_EQ(speed.error().message, "blackboard key 'ball_speed' has no value yet (read by the tree's owner)");
}

TEST(BehaviorTreeBlackboardTest, TheOwnerCannotUseAKeyNoNodeDeclares) {
  Tree tree(declaring("Root", {reads(kBallSpeed)}));
  const Status written = tree.blackboard().set(kReceiver, 1);
  ASSERT_FALSE(written);
  EXPECT_EQ(written.error().message, "blackboard key 'receiver' is not declared by any node of the tree");
  EXPECT_FALSE(tree.blackboard().get(kReceiver));
}

TEST(BehaviorTreeBlackboardTest, AccessWithAnotherTypeIsAnErrorNamingBothTypes) {
  Tree tree(declaring("Root", {reads(kBallSpeed)}));
  constexpr Key<int> kSpeedAsInt{"ball_speed"};
  const Status written = tree.blackboard().set(kSpeedAsInt, 3);
  ASSERT_FALSE(written);
  EXPECT_EQ(written.error().message, "blackboard key 'ball_speed' holds double, not int");
  const Result<int> read = tree.blackboard().get(kSpeedAsInt);
  ASSERT_FALSE(read);
  EXPECT_EQ(read.error().message, "blackboard key 'ball_speed' holds double, not int");
}

TEST(BehaviorTreeBlackboardTest, ATreeRejectsOneKeyDeclaredWithTwoTypes) {
  constexpr Key<int> kSpeedAsInt{"ball_speed"};
  try {
    Tree tree(sequence("Root", {declaring("Fast?", {reads(kBallSpeed)}),  //
                                declaring("Slow", {writes(kSpeedAsInt)})}));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(),
                 "blackboard key 'ball_speed' is declared as double by node 'Root/Fast?' and as int by node "
                 "'Root/Slow'");
  }
}

TEST(BehaviorTreeBlackboardTest, NodesShareValuesWithinOneTick) {
  const auto choose_seven = [](LeafContext& leaf) {
    return leaf.set(kReceiver, 7) ? NodeStatus::kSuccess : NodeStatus::kFailure;
  };
  const auto is_seven = [](const LeafContext& leaf) {
    const Result<int> receiver = leaf.get(kReceiver);
    return receiver && *receiver == 7;
  };
  Tree tree(sequence("Root", {action("Choose", choose_seven, {writes(kReceiver)}),
                              condition("IsSeven?", is_seven, {reads(kReceiver)})}));
  EXPECT_EQ(tree.tick(at_ms(0)), NodeStatus::kSuccess);
  EXPECT_EQ(*tree.blackboard().get(kReceiver), 7);
}

TEST(BehaviorTreeBlackboardTest, ANodeReadingAnUndeclaredKeyGetsAClearError) {
  std::string message;
  Tree tree(sequence("Root", {declaring("Writer", {writes(kBallSpeed)}),
                              condition("Peek?", reading(kBallSpeed, message))}));
  ASSERT_TRUE(tree.blackboard().set(kBallSpeed, 1.0).ok());
  EXPECT_EQ(tree.tick(at_ms(0)), NodeStatus::kFailure);
  EXPECT_EQ(message,
            "node 'Root/Peek?' reads blackboard key 'ball_speed' without declaring it; add bt::reads(key) "
            "to its ports");
}

TEST(BehaviorTreeBlackboardTest, ANodeWritingThroughAReadPortGetsAClearError) {
  std::string message;
  const auto cheat = [&](LeafContext& leaf) {
    const Status written = leaf.set(kBallSpeed, 9.0);
    if (!written) message = written.error().message;
    return NodeStatus::kSuccess;
  };
  Tree tree(action("Cheat", cheat, {reads(kBallSpeed)}));
  tree.tick(at_ms(0));
  EXPECT_EQ(message,
            "node 'Cheat' writes blackboard key 'ball_speed' but declares it only for read; add "
            "bt::writes(key) to its ports");
  EXPECT_FALSE(tree.blackboard().get(kBallSpeed));
}

TEST(BehaviorTreeBlackboardTest, ANodeReadingWithAnotherTypeThanDeclaredGetsAClearError) {
  constexpr Key<float> kSpeedAsFloat{"ball_speed"};
  std::string message;
  Tree tree(condition("Fast?", reading(kSpeedAsFloat, message), {reads(kBallSpeed)}));
  tree.tick(at_ms(0));
  EXPECT_EQ(message, "node 'Fast?' accesses blackboard key 'ball_speed' as float but declares it as double");
}

TEST(BehaviorTreeBlackboardTest, ANodeReadingAnUnsetKeyGetsAnErrorNamingTheNode) {
  std::string message;
  Tree tree(condition("Fast?", reading(kBallSpeed, message), {reads(kBallSpeed)}));
  tree.tick(at_ms(0));
  EXPECT_EQ(message, "blackboard key 'ball_speed' has no value yet (read by node 'Fast?')");
}

TEST(BehaviorTreeBlackboardTest, ANodeOutsideATreeHasNoBlackboard) {
  std::string message;
  Condition detached("Fast?", reading(kBallSpeed, message), {reads(kBallSpeed)});
  detached.tick(TickContext{at_ms(0), 1});
  EXPECT_EQ(message, "node 'Fast?' is not part of a Tree, so its ports have no blackboard");
}

TEST(BehaviorTreeBlackboardTest, StoresUserTypesAndOptionals) {
  constexpr Key<Point> kTarget{"target"};
  constexpr Key<std::optional<Point>> kBall{"ball"};
  Tree tree(declaring("Root", {reads(kTarget), reads(kBall)}));
  ASSERT_TRUE(tree.blackboard().set(kTarget, Point{1.0, -2.0}).ok());
  ASSERT_TRUE(tree.blackboard().set(kBall, std::nullopt).ok());
  EXPECT_EQ(tree.blackboard().get(kTarget)->y, -2.0);
  ASSERT_TRUE(tree.blackboard().get(kBall).ok());
  EXPECT_FALSE(tree.blackboard().get(kBall)->has_value());
}

TEST(BehaviorTreeBlackboardTest, OverwritingAValueReplacesIt) {
  Tree tree(declaring("Root", {reads(kFormation)}));
  ASSERT_TRUE(tree.blackboard().set(kFormation, std::vector<int>(64, 1)).ok());
  const std::vector<int> smaller(8, 2);
  ASSERT_TRUE(tree.blackboard().set(kFormation, smaller).ok());
  EXPECT_EQ(*tree.blackboard().get(kFormation), smaller);
}

TEST(BehaviorTreeBlackboardTest, ListsItsKeysWithTypesAndWhetherTheyAreSet) {
  Tree tree(sequence("Root", {declaring("A", {reads(kBallSpeed)}), declaring("B", {writes(kReceiver)}),
                              declaring("C", {reads(kReceiver)})}));
  ASSERT_TRUE(tree.blackboard().set(kReceiver, 2).ok());
  const std::vector<KeyInfo> keys = tree.blackboard().keys();
  ASSERT_EQ(keys.size(), 2u);
  EXPECT_EQ(keys[0].name, "ball_speed");
  EXPECT_EQ(keys[0].type_name, "double");
  EXPECT_FALSE(keys[0].has_value);
  EXPECT_EQ(keys[1].name, "receiver");
  EXPECT_EQ(keys[1].type_name, "int");
  EXPECT_TRUE(keys[1].has_value);
  EXPECT_TRUE(tree.blackboard().contains("receiver"));
  EXPECT_FALSE(tree.blackboard().contains("nobody"));
}

TEST(BehaviorTreeBlackboardTest, TypeNamesAreReadable) {
  EXPECT_THAT(reads(kFormation).type_name, HasSubstr("std::vector<int"));
  EXPECT_THAT(reads(Key<Point>{"p"}).type_name, HasSubstr("Point"));
}

}  // namespace
}  // namespace ssl::bt
