// Checks that ticking a tree allocates nothing once it is warm. This binary replaces the global operator
// new with one that counts while `counting` is set, which is why it is separate from behavior_tree_test.
#include <gtest/gtest.h>

#include <chrono>
#include <cstddef>
#include <cstdlib>
#include <new>
#include <vector>

#include "libs/behavior_tree/behavior_tree.h"
#include "libs/behavior_tree/test_util.h"

namespace {

std::size_t allocations = 0;
bool counting = false;

}  // namespace

// GCC cannot see that these replacements pair malloc with free and warns about mismatched allocation
// functions once it inlines them into callers.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

void* operator new(std::size_t size) {
  if (counting) ++allocations;
  if (void* memory = std::malloc(size == 0 ? 1 : size)) return memory;
  throw std::bad_alloc();
}

void operator delete(void* memory) noexcept { std::free(memory); }
void operator delete(void* memory, std::size_t) noexcept { std::free(memory); }

#pragma GCC diagnostic pop

namespace ssl::bt {
namespace {

using namespace std::chrono_literals;
using testing::at_ms;

struct Point {
  double x = 0.0;
  double y = 0.0;
};

constexpr Key<bool> kHaveBall{"have_ball"};
constexpr Key<int> kReceiver{"receiver"};
constexpr Key<double> kBallSpeed{"ball_speed"};
constexpr Key<Point> kKickTarget{"kick_target"};
constexpr Key<std::vector<int>> kFormation{"formation"};

/// Answers RUNNING for `ticks_per_run - 1` ticks, then SUCCESS.
/// Answers RUNNING, and SUCCESS on every `ticks_per_run`-th tick.
NodeStatus run_for(const LeafContext& leaf, std::uint64_t ticks_per_run) {
  return leaf.tick_number() % ticks_per_run == 0 ? NodeStatus::kSuccess : NodeStatus::kRunning;
}

bool have_ball(const LeafContext& leaf) {
  const Result<bool> have = leaf.get(kHaveBall);
  return have && *have;
}

bool can_pass(const LeafContext& leaf) {
  const Result<int> receiver = leaf.get(kReceiver);
  return receiver && *receiver >= 0;
}

NodeStatus kick(LeafContext& leaf) {
  if (!leaf.set(kKickTarget, Point{6.0, 0.3})) return NodeStatus::kFailure;
  return run_for(leaf, 4);
}

NodeStatus go_to_ball(LeafContext& leaf) {
  const Result<double> speed = leaf.get(kBallSpeed);
  return speed && *speed > 1.0 ? NodeStatus::kRunning : NodeStatus::kSuccess;
}

NodeStatus watch(LeafContext& leaf) { return run_for(leaf, 5); }

/// One robot's tree; the inputs change over the ticks so that branches pre-empt and halt each other.
NodePtr robot_tree(const std::vector<int>& formation) {
  const auto pass_ball = [&formation](LeafContext& leaf) {
    if (!leaf.set(kFormation, formation)) return NodeStatus::kFailure;  // copy-assigns: same size, no alloc
    return leaf.tick_number() % 3 == 0 ? NodeStatus::kFailure : run_for(leaf, 2);
  };
  return reactive_selector("Robot", {
      reactive_sequence("Shoot", {
          condition("HaveBall?", have_ball, {reads(kHaveBall)}),
          timeout(action("Kick", kick, {writes(kKickTarget)}, [] {}), 30ms),
      }),
      sequence("Pass", {
          condition("CanPass?", can_pass, {reads(kReceiver)}),
          retry_until_successful(action("PassBall", pass_ball, {reads(kReceiver), writes(kFormation)}), 3),
      }),
      parallel("Support", ParallelPolicy::kSuccessOnOne, {
          repeat_forever(action("GoToBall", go_to_ball, {reads(kBallSpeed)})),
          succeeder(inverter(action("Watch", watch))),
      }),
  });
}

TEST(BehaviorTreeAllocationTest, TickingAllocatesNothingInSteadyState) {
  const std::vector<int> formation(11, 1);
  std::vector<NodePtr> robots;
  for (int robot = 0; robot < 11; ++robot) robots.push_back(robot_tree(formation));
  Tree tree(parallel("Team", ParallelPolicy::kSuccessOnAll, std::move(robots)));

  std::vector<NodeSnapshot> rows;
  bool inputs_written = true;
  const auto tick = [&](int i) {
    inputs_written = tree.blackboard().set(kHaveBall, i % 7 < 3).ok() && inputs_written;
    inputs_written = tree.blackboard().set(kReceiver, i % 5 < 2 ? 3 : -1).ok() && inputs_written;
    inputs_written = tree.blackboard().set(kBallSpeed, (i % 4) * 0.5).ok() && inputs_written;
    tree.tick(at_ms(10 * i));
    tree.snapshot(rows);
  };
  for (int i = 0; i < 200; ++i) tick(i);  // warm-up: every value set, every vector at its size

  allocations = 0;
  counting = true;
  for (int i = 200; i < 2200; ++i) tick(i);
  counting = false;
  EXPECT_EQ(allocations, 0u);
  EXPECT_TRUE(inputs_written);
  EXPECT_EQ(rows.size(), tree.size());
}

TEST(BehaviorTreeAllocationTest, TheCounterSeesAllocations) {
  allocations = 0;
  counting = true;
  int* volatile counted = new int(3);  // volatile: the compiler may not elide the allocation
  counting = false;
  delete counted;
  EXPECT_EQ(allocations, 1u);
}

}  // namespace
}  // namespace ssl::bt
