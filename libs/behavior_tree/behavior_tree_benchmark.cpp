// Time per tick of a team-sized tree: 11 robot subtrees of 20 nodes each (selectors, sequences, conditions,
// actions, decorators) under one parallel root, with blackboard reads and writes in the leaves. The inputs
// change every tick (from a fixed schedule) so that branches switch and running actions get halted, as in a
// match; the "visited" counter is how many nodes an average tick reaches. Budget context: the planner ticks
// this for 11 robots at 100 Hz within 2 ms, trajectories included.
//
//   ./build/bench/behavior_tree_benchmark
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "libs/behavior_tree/behavior_tree.h"

namespace ssl::bt {
namespace {

using namespace std::chrono_literals;

constexpr int kRobots = 11;

struct Point {
  double x = 0.0;
  double y = 0.0;
};

constexpr Key<bool> kHalted{"halted"};
constexpr Key<int> kBallOwner{"ball_owner"};  ///< robot id, -1: nobody of ours
constexpr Key<double> kBallSpeed{"ball_speed"};
constexpr Key<int> kReceiver{"pass_receiver"};
constexpr Key<std::uint32_t> kDefenders{"defenders"};  ///< bit i: robot i defends

/// One tick's inputs.
struct Inputs {
  bool halted = false;
  int ball_owner = -1;
  double ball_speed = 0.0;
  int receiver = -1;
  std::uint32_t defenders = 0;
};

std::vector<Inputs> input_schedule() {
  std::vector<Inputs> schedule(256);
  for (std::size_t i = 0; i < schedule.size(); ++i) {
    const int t = static_cast<int>(i);
    schedule[i] = Inputs{t % 64 == 63, (t / 8) % (kRobots + 1) - 1, (t % 10) * 0.4, (t / 5) % kRobots,
                         0b111u << ((t / 16) % (kRobots - 2))};
  }
  return schedule;
}

ConditionFunction is_halted() {
  return [](const LeafContext& leaf) {
    const Result<bool> halted = leaf.get(kHalted);
    return halted && *halted;
  };
}

ConditionFunction has_ball(int id) {
  return [id](const LeafContext& leaf) {
    const Result<int> owner = leaf.get(kBallOwner);
    return owner && *owner == id;
  };
}

ConditionFunction ball_too_fast() {
  return [](const LeafContext& leaf) {
    const Result<double> speed = leaf.get(kBallSpeed);
    return speed && *speed > 3.0;
  };
}

ConditionFunction is_receiver(int id) {
  return [id](const LeafContext& leaf) {
    const Result<int> receiver = leaf.get(kReceiver);
    return receiver && *receiver == id;
  };
}

ConditionFunction is_defender(int id) {
  return [id](const LeafContext& leaf) {
    const Result<std::uint32_t> defenders = leaf.get(kDefenders);
    return defenders && ((*defenders >> id) & 1u) != 0;
  };
}

/// Writes (x, y) to `target` every tick; succeeds on every `ticks`-th tick, runs otherwise.
ActionFunction drive(Key<Point> target, double x, double y, std::uint64_t ticks) {
  return [target, x, y, ticks](LeafContext& leaf) {
    if (!leaf.set(target, Point{x, y})) return NodeStatus::kFailure;
    return leaf.tick_number() % ticks == 0 ? NodeStatus::kSuccess : NodeStatus::kRunning;
  };
}

/// 20 nodes. `target` is this robot's output key; its name must outlive the tree.
NodePtr robot_tree(int id, Key<Point> target) {
  const Ports drives = {writes(target)};
  return reactive_selector("Robot" + std::to_string(id), {
      reactive_sequence("Referee", {
          condition("Halted?", is_halted(), {reads(kHalted)}),
          action("Stop", drive(target, 0.0, 0.0, 1), drives),
      }),
      reactive_sequence("Shoot", {
          condition("HaveBall?", has_ball(id), {reads(kBallOwner)}),
          inverter(condition("BallTooFast?", ball_too_fast(), {reads(kBallSpeed)})),
          timeout(action("Kick", drive(target, 6.0, 0.0, 6), drives), 500ms),
      }),
      sequence("Pass", {
          condition("IsReceiver?", is_receiver(id), {reads(kReceiver)}),
          action("Turn", drive(target, 1.0, 1.0, 3), drives),
          retry_until_successful(action("Receive", drive(target, 2.0, 1.0, 4), drives), 3),
      }),
      selector("Position", {
          sequence("Mark", {
              condition("IsDefender?", is_defender(id), {reads(kDefenders)}),
              action("MarkOpponent", drive(target, -3.0, 0.5, 7), drives),
          }),
          action("GoToOpenSpace", drive(target, 1.5, -2.0, 9), drives),
      }),
  });
}

/// Output key names for the robots; they must outlive the trees that use them.
std::array<std::string, kRobots> target_names() {
  std::array<std::string, kRobots> names;
  for (int id = 0; id < kRobots; ++id) names[id] = "target_" + std::to_string(id);
  return names;
}

void feed(Blackboard& blackboard, const Inputs& inputs) {
  bool ok = blackboard.set(kHalted, inputs.halted).ok();
  ok = blackboard.set(kBallOwner, inputs.ball_owner).ok() && ok;
  ok = blackboard.set(kBallSpeed, inputs.ball_speed).ok() && ok;
  ok = blackboard.set(kReceiver, inputs.receiver).ok() && ok;
  ok = blackboard.set(kDefenders, inputs.defenders).ok() && ok;
  benchmark::DoNotOptimize(ok);
}

/// Every robot's behaviour restarts when it finishes and never fails the team, so every robot subtree is
/// ticked on every tick.
Tree team_tree(const std::array<std::string, kRobots>& names) {
  std::vector<NodePtr> robots;
  for (int id = 0; id < kRobots; ++id) {
    robots.push_back(repeat_forever(succeeder(robot_tree(id, Key<Point>{names[id]}))));
  }
  return Tree(parallel("Team", ParallelPolicy::kSuccessOnAll, std::move(robots)));
}

/// Nodes a tick reaches, on average over one pass of the schedule (ticks `tree` further).
double visited_nodes_per_tick(Tree& tree, const std::vector<Inputs>& schedule) {
  std::vector<NodeSnapshot> rows;
  std::size_t visited = 0;
  for (const Inputs& inputs : schedule) {
    feed(tree.blackboard(), inputs);
    tree.tick(time::Timestamp{});
    tree.snapshot(rows);
    for (const NodeSnapshot& row : rows) visited += row.last_tick == tree.tick_count() ? 1 : 0;
  }
  return static_cast<double>(visited) / static_cast<double>(schedule.size());
}

void BM_TickTeamTree(benchmark::State& state) {
  const auto names = target_names();
  Tree tree = team_tree(names);
  const std::vector<Inputs> schedule = input_schedule();
  std::size_t i = 0;
  time::Timestamp now;
  for (auto _ : state) {
    feed(tree.blackboard(), schedule[i]);
    benchmark::DoNotOptimize(tree.tick(now));
    i = (i + 1) % schedule.size();
    now += 10ms;
  }
  state.counters["nodes"] = static_cast<double>(tree.size());
  state.counters["visited"] = visited_nodes_per_tick(tree, schedule);
}
BENCHMARK(BM_TickTeamTree);

void BM_TickElevenRobotTrees(benchmark::State& state) {
  const auto names = target_names();
  std::vector<Tree> trees;
  for (int id = 0; id < kRobots; ++id) trees.emplace_back(robot_tree(id, Key<Point>{names[id]}));
  const std::vector<Inputs> schedule = input_schedule();
  std::size_t i = 0;
  time::Timestamp now;
  for (auto _ : state) {
    for (Tree& tree : trees) {
      feed(tree.blackboard(), schedule[i]);
      benchmark::DoNotOptimize(tree.tick(now));
    }
    i = (i + 1) % schedule.size();
    now += 10ms;
  }
}
BENCHMARK(BM_TickElevenRobotTrees);

void BM_SnapshotTeamTree(benchmark::State& state) {
  const auto names = target_names();
  Tree tree = team_tree(names);
  feed(tree.blackboard(), Inputs{});
  tree.tick(time::Timestamp{});
  std::vector<NodeSnapshot> rows;
  for (auto _ : state) {
    tree.snapshot(rows);
    benchmark::DoNotOptimize(rows.data());
  }
}
BENCHMARK(BM_SnapshotTeamTree);

}  // namespace
}  // namespace ssl::bt

BENCHMARK_MAIN();
