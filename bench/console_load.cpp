// The console under the load of an 11 v 11 match with three viewers (budgets: the console's share of a core,
// the page's redraws per second; bench/budget_table.cpp).
//
// This process publishes what a full match puts on the bus: vision.detection from 4 cameras at 75 Hz (22
// robots and the ball each), each team's world.state after every camera frame (300 Hz, 22 robots),
// each team's planner.debug at 100 Hz (a tree of 60 nodes, 11 roles, 11 paths of 30 points) and
// referee.state at 10 Hz. It starts build/bin/console on a private domain and port and opens three viewers:
// two event streams read here and the real page in headless chromium (bench/console_page.mjs; not
// measured, and said so, when node, playwright-core or chromium is missing). Over --seconds it prints the
// console's CPU as a share of one core (/proc/<pid>/stat), the frames per second and bytes per frame each
// viewer received, and the page's redraws per second.
//
//   build/bench/console_load [--seconds 20] [--domain 205] [--port 25290]
#include <httplib.h>
#include <nlohmann/json.hpp>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "libs/dds/participant.h"
#include "libs/dds/topics.h"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;
namespace topics = ssl::dds::topics;
namespace idl = ssl::idl;

constexpr int kCameras = 4;
constexpr double kCameraRate = 75;   // Hz per camera
constexpr double kPlannerRate = 100; // Hz per team
constexpr int kRobots = 11;          // per team

struct Options {
  double seconds = 20;
  int domain = 205;
  int port = 25290;
};

fs::path exe_dir() { return fs::canonical("/proc/self/exe").parent_path(); }

/// utime + stime of `pid` in seconds.
double cpu_seconds(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
  const auto close = text.rfind(')');
  if (close == std::string::npos) return 0;
  std::istringstream fields(text.substr(close + 2));
  std::string field;
  double utime = 0;
  double stime = 0;
  for (int i = 3; fields >> field; ++i) {
    if (i == 14) utime = std::stod(field);
    if (i == 15) {
      stime = std::stod(field);
      break;
    }
  }
  return (utime + stime) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

pid_t spawn(const std::vector<std::string>& argv, const std::string& output = "/dev/null") {
  const pid_t pid = fork();
  if (pid == 0) {
    std::vector<char*> args;
    for (const std::string& arg : argv) args.push_back(const_cast<char*>(arg.c_str()));
    args.push_back(nullptr);
    std::freopen(output.c_str(), "w", stdout);
    std::freopen("/dev/null", "w", stderr);
    execvp(args[0], args.data());
    _exit(127);
  }
  return pid;
}

/// Moves robots on circles so that every sample differs (t in s).
void place(double t, std::uint32_t id, bool blue, double& x, double& y, double& heading) {
  const double phase = t * 0.8 + id * 0.57 + (blue ? 0 : 3.1);
  x = (blue ? -2.5 : 2.5) + 1.5 * std::cos(phase);
  y = -3.0 + id * 0.55 + 0.3 * std::sin(phase);
  heading = phase;
}

idl::vision::DetectionFrame detection(std::uint32_t camera, std::uint32_t number, double t) {
  idl::vision::DetectionFrame frame;
  frame.camera_id(camera);
  frame.frame_number(number);
  frame.balls().resize(1);
  frame.balls()[0].x(std::cos(t));
  frame.balls()[0].y(std::sin(t));
  frame.balls()[0].confidence(0.9F);
  for (bool blue : {true, false}) {
    auto& robots = blue ? frame.robots_blue() : frame.robots_yellow();
    robots.resize(kRobots);
    for (std::uint32_t id = 0; id < kRobots; ++id) {
      double x = 0;
      double y = 0;
      double heading = 0;
      place(t, id, blue, x, y, heading);
      robots[id].robot_id(id);
      robots[id].x(x);
      robots[id].y(y);
      robots[id].orientation(heading);
      robots[id].has_orientation(true);
      robots[id].confidence(0.9F);
    }
  }
  return frame;
}

idl::world::WorldState world(bool blue, std::uint64_t sequence, double t) {
  idl::world::WorldState out;
  out.team(blue ? idl::common::TEAM_COLOR_BLUE : idl::common::TEAM_COLOR_YELLOW);
  out.sequence_number(sequence);
  out.has_ball(true);
  idl::world::BallState ball;
  idl::common::Vec3 position;
  position.x(std::cos(t));
  position.y(std::sin(t));
  ball.position(position);
  ball.visible(true);
  out.ball(ball);
  for (bool ours : {true, false}) {
    std::vector<idl::world::RobotState> robots(kRobots);
    for (std::uint32_t id = 0; id < kRobots; ++id) {
      double x = 0;
      double y = 0;
      double heading = 0;
      place(t, id, ours == blue, x, y, heading);
      idl::common::Pose2 pose;
      pose.x(x);
      pose.y(y);
      pose.theta(heading);
      robots[id].id(id);
      robots[id].pose(pose);
      robots[id].visible(true);
    }
    if (ours) {
      out.friendly(std::move(robots));
    } else {
      out.enemy(std::move(robots));
    }
  }
  return out;
}

idl::planner::PlannerDebug debug(bool blue, std::uint64_t tick, double t) {
  idl::planner::PlannerDebug out;
  out.team(blue ? idl::common::TEAM_COLOR_BLUE : idl::common::TEAM_COLOR_YELLOW);
  out.tick(tick);
  out.play("normal_play");
  out.game_tactic("attack");
  std::vector<idl::planner::TreeNode> tree(60);
  for (std::size_t i = 0; i < tree.size(); ++i) {
    tree[i].name("Root/Strategy/Node" + std::to_string(i));
    tree[i].depth(static_cast<std::uint16_t>(i % 6));
    tree[i].status(static_cast<idl::planner::NodeStatus>((tick + i) % 4));
  }
  out.tree(std::move(tree));
  std::vector<idl::planner::RoleAssignment> roles(kRobots);
  std::vector<idl::planner::PlannedPath> paths(kRobots);
  for (std::uint32_t id = 0; id < kRobots; ++id) {
    roles[id].robot_id(id);
    roles[id].role(id == 0 ? "goalkeeper" : "support");
    roles[id].tactic("attack");
    roles[id].skill("move_to");
    paths[id].robot_id(id);
    std::vector<idl::common::Vec2> points(30);
    for (std::size_t k = 0; k < points.size(); ++k) {
      points[k].x(-3 + 0.1 * static_cast<double>(k) + 0.01 * std::sin(t));
      points[k].y(-3 + id * 0.55);
    }
    paths[id].points(std::move(points));
  }
  out.roles(std::move(roles));
  out.paths(std::move(paths));
  out.tick_duration(0.0004);
  return out;
}

/// Reads /events until `stop`; counts frames and their bytes.
struct Viewer {
  std::atomic<std::uint64_t> frames{0};
  std::atomic<std::uint64_t> frame_bytes{0};
  std::thread thread;

  void start(int port, const std::atomic<bool>& stop) {
    thread = std::thread([this, port, &stop] {
      httplib::Client client("127.0.0.1", port);
      client.set_read_timeout(5, 0);
      std::string pending;
      client.Get("/events", [&](const char* data, std::size_t size) {
        pending.append(data, size);
        for (std::size_t end; (end = pending.find("\n\n")) != std::string::npos;) {
          if (pending.compare(0, 12, "event: frame") == 0) {
            ++frames;
            frame_bytes += end;
          }
          pending.erase(0, end + 2);
        }
        return !stop.load();
      });
    });
  }
};

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (argc > 1 && std::string(argv[1]) == "--help") {
    std::printf("console_load [--seconds 20] [--domain 205] [--port 25290]: the console's CPU and frame rates\n");
    return 0;
  }
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--seconds") options.seconds = std::atof(argv[i + 1]);
    else if (flag == "--domain") options.domain = std::atoi(argv[i + 1]);
    else if (flag == "--port") options.port = std::atoi(argv[i + 1]);
    else {
      std::fprintf(stderr, "console_load: unknown flag %s (--seconds S, --domain D, --port P)\n", argv[i]);
      return 2;
    }
  }
  const fs::path build = exe_dir().parent_path();
  const fs::path source = fs::path(SSL_SOURCE_DIR);

  auto participant = ssl::dds::Participant::create({.domain_id = options.domain, .name = "console_load"});
  if (!participant) {
    std::fprintf(stderr, "console_load: %s\n", participant.error().message.c_str());
    return 1;
  }
  auto detections = participant->make_writer(topics::kVisionDetection);
  auto blue_world = participant->make_writer(topics::kWorldState, ssl::TeamColor::kBlue);
  auto yellow_world = participant->make_writer(topics::kWorldState, ssl::TeamColor::kYellow);
  auto blue_debug = participant->make_writer(topics::kPlannerDebug, ssl::TeamColor::kBlue);
  auto yellow_debug = participant->make_writer(topics::kPlannerDebug, ssl::TeamColor::kYellow);
  auto referee = participant->make_writer(topics::kRefereeState);
  if (!detections || !blue_world || !yellow_world || !blue_debug || !yellow_debug || !referee) {
    std::fprintf(stderr, "console_load: cannot create the writers\n");
    return 1;
  }

  const pid_t console = spawn({(build / "bin" / "console").string(), "--domain", std::to_string(options.domain),
                               "--http-port", std::to_string(options.port)});
  // The console listens once its HTTP server is up.
  httplib::Client probe("127.0.0.1", options.port);
  bool up = false;
  for (int i = 0; i < 100 && !up; ++i) {
    up = static_cast<bool>(probe.Get("/api/state"));
    if (!up) std::this_thread::sleep_for(100ms);
  }
  if (!up) {
    std::fprintf(stderr, "console_load: the console did not start\n");
    kill(console, SIGKILL);
    return 1;
  }

  std::atomic<bool> stop{false};
  std::thread publisher([&] {
    const auto start = Clock::now();
    const auto camera_period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / (kCameraRate * kCameras)));
    auto next = start;
    std::uint64_t n = 0;
    while (!stop.load()) {
      const double t = std::chrono::duration<double>(Clock::now() - start).count();
      (void)detections->write(detection(static_cast<std::uint32_t>(n % kCameras), static_cast<std::uint32_t>(n / kCameras), t));
      (void)blue_world->write(world(true, n, t));
      (void)yellow_world->write(world(false, n, t));
      if (n % 3 == 0) {  // 100 Hz of 300
        (void)blue_debug->write(debug(true, n, t));
        (void)yellow_debug->write(debug(false, n, t));
      }
      if (n % 30 == 0) {
        idl::referee::RefereeState state;
        state.command(idl::referee::COMMAND_FORCE_START);
        state.stage(idl::referee::STAGE_NORMAL_FIRST_HALF);
        state.stage_time_left(300 - t);
        (void)referee->write(state);
      }
      ++n;
      next += camera_period;
      std::this_thread::sleep_until(next);
    }
  });

  std::vector<std::unique_ptr<Viewer>> viewers;
  for (int i = 0; i < 2; ++i) {
    viewers.push_back(std::make_unique<Viewer>());
    viewers.back()->start(options.port, stop);
  }
  // The third viewer: the page in chromium, or a third stream.
  const fs::path page_output = fs::temp_directory_path() / ("console_load_page_" + std::to_string(getpid()) + ".json");
  const pid_t page = spawn({"node", (source / "bench" / "console_page.mjs").string(),
                            "http://127.0.0.1:" + std::to_string(options.port) + "/",
                            std::to_string(options.seconds)},
                           page_output.string());
  std::this_thread::sleep_for(4s);  // the page is loaded and streaming

  const double cpu_start = cpu_seconds(console);
  std::vector<std::uint64_t> frames_start;
  for (const auto& viewer : viewers) frames_start.push_back(viewer->frames.load());
  const auto measure_start = Clock::now();
  std::this_thread::sleep_for(std::chrono::duration<double>(options.seconds));
  const double elapsed = std::chrono::duration<double>(Clock::now() - measure_start).count();
  const double cpu = (cpu_seconds(console) - cpu_start) / elapsed;

  int page_status = 0;
  waitpid(page, &page_status, 0);
  std::string page_json;
  {
    std::ifstream in(page_output);
    std::getline(in, page_json);
  }
  fs::remove(page_output);
  stop = true;
  publisher.join();
  kill(console, SIGTERM);
  for (const auto& viewer : viewers) viewer->thread.join();
  waitpid(console, nullptr, 0);

  std::printf("console_load: 11 v 11 bus (4 cameras x 75 Hz, world.state 2 x 300 Hz, planner.debug 2 x 100 Hz), "
              "%.0f s\n", elapsed);
  std::printf("  console CPU: %.1f %% of one core\nBUDGET console_cpu_pct %.1f\n", cpu * 100, cpu * 100);
  for (std::size_t i = 0; i < viewers.size(); ++i) {
    const std::uint64_t frames = viewers[i]->frames.load() - frames_start[i];
    const double bytes = viewers[i]->frames.load() > 0
                             ? static_cast<double>(viewers[i]->frame_bytes.load()) / viewers[i]->frames.load()
                             : 0;
    std::printf("  stream viewer %zu: %.1f frames/s, %.1f kB per frame\n", i + 1, frames / elapsed, bytes / 1000);
  }
  if (WIFEXITED(page_status) && WEXITSTATUS(page_status) == 0 && !page_json.empty()) {
    std::printf("  page viewer (chromium): %s\n", page_json.c_str());
    const auto page_figures = nlohmann::json::parse(page_json, nullptr, /*allow_exceptions=*/false);
    if (page_figures.is_object() && page_figures.contains("draws_per_s") && page_figures["draws_per_s"].is_number()) {
      std::printf("BUDGET console_page_draws_per_s %.1f\n", page_figures["draws_per_s"].get<double>());
    }
  } else {
    std::printf("  page viewer: not measured (node, playwright-core in tests/browser or chromium missing)\n");
  }
  return 0;
}
