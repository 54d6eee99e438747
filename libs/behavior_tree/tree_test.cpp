#include "libs/behavior_tree/tree.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "libs/behavior_tree/builders.h"
#include "libs/behavior_tree/test_util.h"

namespace ssl::bt {
namespace {

using ::testing::ElementsAre;
using testing::at_ms;
using testing::ScriptedLeaves;

using testing::kFailure;
using testing::kIdle;
using testing::kRunning;
using testing::kSuccess;

constexpr Key<double> kBallSpeed{"ball_speed"};
constexpr Key<int> kReceiver{"receiver"};
constexpr Key<int> kCount{"count"};

std::vector<std::string> paths_of(const Tree& tree) {
  std::vector<std::string> paths;
  for (const NodeSnapshot& row : tree.snapshot()) paths.emplace_back(row.path);
  return paths;
}

TEST(BehaviorTreeTreeTest, GivesEveryNodeItsPathInDepthFirstOrder) {
  ScriptedLeaves leaves;
  Tree tree(selector("Root", {
      sequence("Attack", {leaves.make("HaveBall"), leaves.make("Shoot")}),
      inverter(leaves.make("Defend")),
  }));
  EXPECT_THAT(paths_of(tree), ElementsAre("Root", "Root/Attack", "Root/Attack/HaveBall", "Root/Attack/Shoot",
                                          "Root/Inverter", "Root/Inverter/Defend"));
  EXPECT_EQ(tree.size(), 6u);
  EXPECT_EQ(leaves["Shoot"].path(), "Root/Attack/Shoot");
}

TEST(BehaviorTreeTreeTest, SiblingsWithTheSameNameGetTheirIndexInThePath) {
  ScriptedLeaves leaves;
  Tree tree(sequence("Root", {inverter(leaves.make("A")), leaves.make("B"), inverter(leaves.make("C"))}));
  EXPECT_THAT(paths_of(tree),
              ElementsAre("Root", "Root/Inverter[0]", "Root/Inverter[0]/A", "Root/B", "Root/Inverter[2]",
                          "Root/Inverter[2]/C"));
}

TEST(BehaviorTreeTreeTest, RejectsANullRoot) { EXPECT_THROW(Tree(nullptr), std::invalid_argument); }

TEST(BehaviorTreeTreeTest, NumbersTicksFromOne) {
  ScriptedLeaves leaves;
  Tree tree(leaves.make("Only"));
  EXPECT_EQ(tree.tick_count(), 0u);
  EXPECT_EQ(tree.root().last_tick(), 0u);
  tree.tick(at_ms(0));
  tree.tick(at_ms(10));
  EXPECT_EQ(tree.tick_count(), 2u);
  EXPECT_EQ(tree.root().last_tick(), 2u);
}

TEST(BehaviorTreeTreeTest, SnapshotHasEveryNodesTypeStatusLastTickAndDepth) {
  ScriptedLeaves leaves;
  Tree tree(reactive_selector("Root", {
      reactive_sequence("Attack", {leaves.make("HaveBall", kFailure), leaves.make("Shoot")}),
      leaves.make("GoToBall", kRunning),
  }));
  tree.tick(at_ms(0));
  leaves["HaveBall"].answer(kSuccess);
  leaves["Shoot"].answer(kRunning);
  tree.tick(at_ms(10));  // Attack pre-empts GoToBall
  leaves["HaveBall"].answer(kFailure);
  tree.tick(at_ms(20));  // back to GoToBall; Shoot is halted

  const std::vector<NodeSnapshot> rows = tree.snapshot();
  ASSERT_EQ(rows.size(), 5u);
  const auto expect_row = [&](std::size_t i, std::string_view path, std::string_view type, NodeStatus status,
                              std::uint64_t last_tick, std::size_t depth) {
    SCOPED_TRACE(path);
    EXPECT_EQ(rows[i].path, path);
    EXPECT_EQ(rows[i].type, type);
    EXPECT_EQ(rows[i].status, status);
    EXPECT_EQ(rows[i].last_tick, last_tick);
    EXPECT_EQ(rows[i].depth, depth);
  };
  expect_row(0, "Root", "ReactiveSelector", kRunning, 3, 0);
  expect_row(1, "Root/Attack", "ReactiveSequence", kFailure, 3, 1);
  expect_row(2, "Root/Attack/HaveBall", "Action", kFailure, 3, 2);
  expect_row(3, "Root/Attack/Shoot", "Action", kIdle, 2, 2);  // halted at tick 3, last ticked at tick 2
  expect_row(4, "Root/GoToBall", "Action", kRunning, 3, 1);
  EXPECT_EQ(rows[3].name, "Shoot");
}

TEST(BehaviorTreeTreeTest, SnapshotIntoAVectorReplacesItsRows) {
  ScriptedLeaves leaves;
  Tree tree(sequence("Root", {leaves.make("A"), leaves.make("B")}));
  std::vector<NodeSnapshot> rows(10);
  tree.tick(at_ms(0));
  tree.snapshot(rows);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[2].path, "Root/B");
  EXPECT_EQ(rows[2].status, kSuccess);
}

TEST(BehaviorTreeTreeTest, ListsEveryNodesDeclaredReadsAndWrites) {
  const auto always = [](const LeafContext&) { return true; };
  const auto done = [](LeafContext&) { return NodeStatus::kSuccess; };
  Tree tree(sequence("Root", {
      condition("Moving?", always, {reads(kBallSpeed)}),
      action("Pick", done, {reads(kBallSpeed), writes(kReceiver)}),
  }));
  const std::vector<PortDeclaration> ports = tree.port_declarations();
  ASSERT_EQ(ports.size(), 3u);
  EXPECT_EQ(ports[0].node_path, "Root/Moving?");
  EXPECT_EQ(ports[0].key, "ball_speed");
  EXPECT_EQ(ports[0].direction, PortDirection::kRead);
  EXPECT_EQ(ports[0].type_name, "double");
  EXPECT_EQ(ports[1].node_path, "Root/Pick");
  EXPECT_EQ(ports[1].direction, PortDirection::kRead);
  EXPECT_EQ(ports[2].node_path, "Root/Pick");
  EXPECT_EQ(ports[2].key, "receiver");
  EXPECT_EQ(ports[2].direction, PortDirection::kWrite);
  EXPECT_EQ(ports[2].type_name, "int");
}

TEST(BehaviorTreeTreeTest, HaltReturnsTheWholeRunningBranchToIdle) {
  ScriptedLeaves leaves;
  Tree tree(sequence("Root", {
      leaves.make("Prepare"),
      parallel("Both", ParallelPolicy::kSuccessOnAll, {
          timeout(leaves.make("Drive", kRunning), std::chrono::seconds(5)),
          leaves.make("Aim", kRunning),
      }),
  }));
  tree.tick(at_ms(0));
  leaves.take_log();
  tree.halt();
  EXPECT_THAT(leaves.take_log(), ElementsAre("halt Drive", "halt Aim"));
  for (const NodeSnapshot& row : tree.snapshot()) {
    if (row.path == "Root/Prepare") {
      EXPECT_EQ(row.status, kSuccess);
    } else {
      EXPECT_EQ(row.status, kIdle) << row.path;
    }
  }
}

TEST(BehaviorTreeTreeTest, ATreeCanBeMovedAndKeepsItsBlackboard) {
  const auto count_up = [](LeafContext& leaf) {
    const Result<int> count = leaf.get(kCount);
    return leaf.set(kCount, count ? *count + 1 : 1) ? NodeStatus::kSuccess : NodeStatus::kFailure;
  };
  Tree original(action("Count", count_up, {reads(kCount), writes(kCount)}));
  original.tick(at_ms(0));
  Tree moved = std::move(original);
  moved.tick(at_ms(10));
  EXPECT_EQ(*moved.blackboard().get(kCount), 2);
}

TEST(BehaviorTreeTreeTest, TreesShareNothing) {
  const auto make = [] {
    return Tree(action("Noop", [](LeafContext&) { return NodeStatus::kSuccess; }, {reads(kCount)}));
  };
  Tree first = make();
  Tree second = make();
  ASSERT_TRUE(first.blackboard().set(kCount, 1).ok());
  EXPECT_FALSE(second.blackboard().get(kCount).ok());
  first.tick(at_ms(0));
  EXPECT_EQ(second.root().status(), kIdle);
}

}  // namespace
}  // namespace ssl::bt
