#include "libs/behavior_tree/render.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "libs/behavior_tree/builders.h"
#include "libs/behavior_tree/test_util.h"
#include "libs/behavior_tree/tree.h"

namespace ssl::bt {
namespace {

using namespace std::chrono_literals;
using testing::at_ms;

constexpr Key<int> kBallOwner{"ball_owner"};
constexpr Key<double> kBallPosition{"ball_position"};
constexpr Key<double> kKickTarget{"kick_target"};

/// A striker that has the ball at tick 1 (so it starts kicking) and loses it at tick 2 (so the kick is
/// halted and it goes to the ball instead).
class BehaviorTreeRenderStrikerTest : public ::testing::Test {
 protected:
  NodePtr striker() {
    const auto have_ball = [this](const LeafContext&) { return have_ball_; };
    const auto keep_running = [](LeafContext&) { return NodeStatus::kRunning; };
    return reactive_selector("Root", {
        reactive_sequence("Shoot", {
            condition("HaveBall?", have_ball, {reads(kBallOwner)}),
            timeout(action("Kick", keep_running, {writes(kKickTarget)}), 2s),
        }),
        action("GoToBall", keep_running, {reads(kBallPosition)}),
    });
  }

  void play_two_ticks() {
    have_ball_ = true;
    tree_.tick(at_ms(0));
    have_ball_ = false;
    tree_.tick(at_ms(10));
  }

  bool have_ball_ = false;
  Tree tree_{striker()};
};

TEST_F(BehaviorTreeRenderStrikerTest, AsciiShowsTheLegendPortsAndStatusesAligned) {
  play_two_ticks();
  EXPECT_EQ(to_ascii(tree_.root()),
            "(?*) Root                           RUNNING\n"
            "|--(S*) Shoot                       FAILURE\n"
            "|  |--{ HaveBall? } <-- ball_owner  FAILURE\n"
            "|  `--<Timeout 2s>                  IDLE (tick 1)\n"
            "|     `--[ Kick ] --> kick_target   IDLE (tick 1)\n"
            "`--[ GoToBall ] <-- ball_position   RUNNING\n");
}

TEST_F(BehaviorTreeRenderStrikerTest, AsciiOfANeverTickedTreeIsAllIdle) {
  EXPECT_EQ(to_ascii(tree_.root(), {.show_ports = false}),
            "(?*) Root            IDLE\n"
            "|--(S*) Shoot        IDLE\n"
            "|  |--{ HaveBall? }  IDLE\n"
            "|  `--<Timeout 2s>   IDLE\n"
            "|     `--[ Kick ]    IDLE\n"
            "`--[ GoToBall ]      IDLE\n");
}

TEST_F(BehaviorTreeRenderStrikerTest, DotDrawsShapesByTypeAndColoursByStatus) {
  play_two_ticks();
  EXPECT_EQ(to_dot(tree_.root()),
            R"dot(digraph behavior_tree {
  node [fontname="Helvetica"];
  n0 [label="Root\nReactiveSelector\nRUNNING", shape=octagon, style="filled", fillcolor="#ffd966", peripheries=2];
  n0 -> n1;
  n1 [label="Shoot\nReactiveSequence\nFAILURE", shape=box, style="filled", fillcolor="#e06666", peripheries=2];
  n1 -> n2;
  n2 [label="HaveBall?\nCondition\n<-- ball_owner\nFAILURE", shape=ellipse, style="filled", fillcolor="#e06666"];
  n1 -> n3;
  n3 [label="Timeout: 2s\nIDLE (tick 1)", shape=hexagon, style="filled,dashed", fillcolor="#ffffff"];
  n3 -> n4;
  n4 [label="Kick\nAction\n--> kick_target\nIDLE (tick 1)", shape=box, style="filled,rounded,dashed", fillcolor="#ffffff"];
  n0 -> n5;
  n5 [label="GoToBall\nAction\n<-- ball_position\nRUNNING", shape=box, style="filled,rounded", fillcolor="#ffd966"];
}
)dot");
}

TEST(BehaviorTreeRenderTest, AsciiLabelsEveryNodeTypeAndNamedDecorators) {
  const auto work = [](LeafContext&) { return NodeStatus::kSuccess; };
  const NodePtr root = selector("Root", {
      sequence("Plan", {
          parallel("Both", ParallelPolicy::kSuccessOnOne, {action("A", work), action("B", work)}),
          repeater(action("C", work), 3, "ThreeKicks"),
          retry_until_successful(action("D", work), 2),
      }),
      reactive_sequence("Guarded", {succeeder(action("E", work)), failer(action("F", work))}),
      repeat_forever(inverter(condition("G?", [](const LeafContext&) { return true; }))),
  });
  EXPECT_EQ(to_ascii(*root, {.show_status = false}),
            "(?) Root\n"
            "|--(S) Plan\n"
            "|  |--(P) Both (success on one)\n"
            "|  |  |--[ A ]\n"
            "|  |  `--[ B ]\n"
            "|  |--<Repeater 3 times> ThreeKicks\n"
            "|  |  `--[ C ]\n"
            "|  `--<RetryUntilSuccessful 2 attempts>\n"
            "|     `--[ D ]\n"
            "|--(S*) Guarded\n"
            "|  |--<Succeeder>\n"
            "|  |  `--[ E ]\n"
            "|  `--<Failer>\n"
            "|     `--[ F ]\n"
            "`--<Repeater forever>\n"
            "   `--<Inverter>\n"
            "      `--{ G? }\n");
}

TEST(BehaviorTreeRenderTest, DotEscapesQuotesAndBackslashesAndCanOmitStatus) {
  const NodePtr root = action(R"(Say "hi" C:\temp)", [](LeafContext&) { return NodeStatus::kSuccess; });
  EXPECT_EQ(to_dot(*root, {.show_status = false}),
            R"dot(digraph behavior_tree {
  node [fontname="Helvetica"];
  n0 [label="Say \"hi\" C:\\temp\nAction", shape=box, style="filled,rounded", fillcolor="#ffffff"];
}
)dot");
}

}  // namespace
}  // namespace ssl::bt
