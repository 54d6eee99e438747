#include "services/referee_gateway/adapter/builtin_service.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "libs/dds/health.h"
#include "libs/net/multicast.h"
#include "libs/net/udp.h"
#include "proto/ssl_simulation_control.pb.h"
#include "libs/time/periodic_timer.h"
#include "services/referee_gateway/adapter/builtin_input.h"
#include "services/referee_gateway/adapter/convert.h"

namespace ssl::referee {

struct BuiltinRefereeService::Impl {
  Impl(const BuiltinServiceOptions& options_in, net::MulticastSender sender_in,
       dds::Reader<idl::vision::DetectionFrame> vision_in,
       dds::Reader<idl::referee::RefereeOperatorCommand> commands_in, dds::HealthReporter health_in,
       std::optional<net::UdpSocket> simulator_in, std::optional<net::Endpoint> simulator_control_in,
       std::shared_ptr<spdlog::logger> logger_in, time::Clock& wall_in)
      : options(options_in),
        sender(std::move(sender_in)),
        simulator(std::move(simulator_in)),
        simulator_control(simulator_control_in),
        vision_reader(std::move(vision_in)),
        command_reader(std::move(commands_in)),
        health(std::move(health_in)),
        logger(std::move(logger_in)),
        wall(wall_in),
        referee(options_in.profile, options_in.field, options_in.setup) {}

  void run();
  void step();
  void send(time::Timestamp now);
  void teleport_placement();
  void report_health();
  /// Resumes the match of options.state_file when there is a fresh one (see the header).
  void resume_saved_match();
  void save(const std::string& packet, time::Timestamp now);

  BuiltinServiceOptions options;
  net::MulticastSender sender;
  std::optional<net::UdpSocket> simulator;  // with teleport_placement_to
  std::optional<net::Endpoint> simulator_control;
  std::optional<std::uint32_t> teleported_for;  // command counter of the last placement done so
  dds::Reader<idl::vision::DetectionFrame> vision_reader;
  dds::Reader<idl::referee::RefereeOperatorCommand> command_reader;
  dds::HealthReporter health;
  std::shared_ptr<spdlog::logger> logger;
  time::Clock& wall;
  time::MonotonicClock pace;
  BuiltinReferee referee;
  VisionObservation vision;
  std::optional<time::Timestamp> last_sent;   // wall clock
  std::uint32_t last_sent_counter = 0;
  std::optional<time::Timestamp> last_vision;  // wall clock of the newest vision frame received
  std::optional<time::Timestamp> last_saved;  // wall clock
  std::uint32_t last_saved_counter = 0;
  std::uint64_t packets_sent = 0, send_errors = 0, operator_commands = 0, rejected_commands = 0,
                vision_frames = 0, placements_teleported = 0, teleport_errors = 0, state_file_errors = 0;
  std::uint64_t packets_at_last_report = 0;
  std::optional<time::Timestamp> last_report;  // monotonic
};

void BuiltinRefereeService::Impl::run() {
  time::PeriodicTimer steps(pace, options.step_period);
  time::Timestamp next_health = pace.now() + health.period(options.health_period);
  while (steps.wait_next()) {
    step();
    if (pace.now() >= next_health) {
      report_health();
      next_health = pace.now() + health.period(options.health_period);
    }
  }
}

void BuiltinRefereeService::Impl::step() {
  const time::Timestamp now = wall.now();
  for (const auto& sample : vision_reader.take()) {
    vision.add(sample.data);
    ++vision_frames;
    last_vision = now;
  }
  for (const auto& sample : command_reader.take()) {
    const std::optional<OperatorCommand> command = operator_command(sample.data);
    const Status applied = command ? referee.command(command->command, now, command->designated_position)
                                   : Status(Error{"not a league command"});
    if (applied) {
      ++operator_commands;
      logger->info("operator ({}): {}", sample.data.author(), to_string(referee.state().command));
    } else {
      ++rejected_commands;
      logger->warn("operator command from {} rejected: {}", sample.data.author(), applied.error().message);
    }
  }
  referee.step(vision.observe(now, options.vision_max_age), now);
  if (simulator) teleport_placement();
  const bool new_command = referee.state().command_counter != last_sent_counter;
  if (new_command || !last_sent || now - *last_sent >= options.send_period) send(now);
}

void BuiltinRefereeService::Impl::send(time::Timestamp now) {
  const ::Referee packet = to_proto(referee.state());
  std::string bytes;
  if (!packet.SerializeToString(&bytes)) {
    ++send_errors;
    return;
  }
  save(bytes, now);
  const Status sent =
      sender.send({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()});
  if (!sent) {
    if (send_errors++ % 100 == 0) logger->warn("{} (and {} more)", sent.error().message, send_errors - 1);
    return;
  }
  ++packets_sent;
  last_sent = now;
  last_sent_counter = referee.state().command_counter;
}

void BuiltinRefereeService::Impl::resume_saved_match() {
  if (options.state_file.empty()) return;
  std::ifstream in(options.state_file, std::ios::binary);
  if (!in) {
    logger->info("no state file {}: a new match", options.state_file);
    return;
  }
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  ::Referee packet;
  if (!packet.ParseFromString(bytes) || !packet.has_packet_timestamp()) {
    ++state_file_errors;
    logger->warn("state file {} is no Referee packet: a new match", options.state_file);
    return;
  }
  const time::Timestamp now = wall.now();
  const RefereeState saved = from_proto(packet, now, RefereeSource::kBuiltin);
  const double age = time::to_seconds(now - saved.packet_referee);
  if (age > time::to_seconds(options.resume_within) || age < -1) {
    logger->info("state file {} was written {:.0f} s ago (resume_within {:.0f} s): a new match", options.state_file,
                 age, time::to_seconds(options.resume_within));
    return;
  }
  referee.resume(saved, now);
  const RefereeState& state = referee.state();
  logger->info("resumed the match of {} (written {:.1f} s ago): {}, yellow {} : {} blue, {} with {} pending",
               options.state_file, age, to_string(state.stage), state.yellow.score, state.blue.score,
               to_string(state.command), state.next_command ? to_string(*state.next_command) : "nothing");
}

void BuiltinRefereeService::Impl::save(const std::string& packet, time::Timestamp now) {
  if (options.state_file.empty()) return;
  const bool new_command = referee.state().command_counter != last_saved_counter;
  if (!new_command && last_saved && now - *last_saved < options.save_period) return;
  // Written aside and renamed, so that a process killed while writing leaves the previous file whole.
  const std::filesystem::path path(options.state_file);
  const std::filesystem::path written = path.string() + ".tmp";
  std::error_code error;
  {
    std::ofstream out(written, std::ios::binary | std::ios::trunc);
    out.write(packet.data(), static_cast<std::streamsize>(packet.size()));
    if (!out.flush()) error = std::make_error_code(std::errc::io_error);
  }
  if (!error) std::filesystem::rename(written, path, error);
  if (error) {
    if (state_file_errors++ % 100 == 0) {
      logger->warn("state file {}: {} ({} failed writes)", options.state_file, error.message(), state_file_errors);
    }
    return;
  }
  last_saved = now;
  last_saved_counter = referee.state().command_counter;
}

void BuiltinRefereeService::Impl::teleport_placement() {
  const RefereeState& state = referee.state();
  const bool placing = state.command == Command::kBallPlacementYellow || state.command == Command::kBallPlacementBlue;
  if (!placing || !state.designated_position || teleported_for == state.command_counter) return;
  teleported_for = state.command_counter;
  ::SimulatorCommand command;
  ::TeleportBall* ball = command.mutable_control()->mutable_teleport_ball();
  ball->set_x(static_cast<float>(state.designated_position->x()));
  ball->set_y(static_cast<float>(state.designated_position->y()));
  ball->set_z(0);
  ball->set_vx(0);
  ball->set_vy(0);
  ball->set_vz(0);
  ball->set_teleport_safely(true);  // robots touching the placement point are moved off it
  std::string bytes;
  Status sent = command.SerializeToString(&bytes)
                    ? simulator->send_to(*simulator_control,
                                         {reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()})
                    : Status(Error{"SimulatorCommand does not serialise"});
  if (!sent) {
    ++teleport_errors;
    logger->warn("ball placement by the simulator: {}", sent.error().message);
    return;
  }
  ++placements_teleported;
  logger->info("ball placement by the simulator: ball to ({:.2f}, {:.2f})", state.designated_position->x(),
               state.designated_position->y());
}

void BuiltinRefereeService::Impl::report_health() {
  const time::Timestamp now = pace.now();
  const double elapsed = last_report ? time::to_seconds(now - *last_report) : 0;
  const double rate = elapsed > 0 ? static_cast<double>(packets_sent - packets_at_last_report) / elapsed : 0;
  last_report = now;
  packets_at_last_report = packets_sent;
  const bool vision_fresh = last_vision && wall.now() - *last_vision < options.vision_max_age * 10;
  const InputCounters& inputs = referee.counters();
  const RefereeState& state = referee.state();
  const Status published = health.publish(
      {.level = vision_fresh ? dds::HealthLevel::kOk : dds::HealthLevel::kWarn,
       .status = std::string(vision_fresh ? "" : "no vision: the referee sees no ball; ") + "profile " +
                 referee.profile().name + ", " + std::string(to_string(state.command)) + ", " +
                 std::string(to_string(state.stage)) + ", yellow " + std::to_string(state.yellow.score) +
                 " : " + std::to_string(state.blue.score) + " blue",
       .rate_hz = rate,
       .errors = send_errors + teleport_errors + state_file_errors,
       .dropped = rejected_commands + vision.invalid_detections() + inputs.invalid_ball + inputs.invalid_robot +
                  inputs.unknown_robot_id + inputs.duplicate_robot + inputs.rejected_commands,
       .counters = {{"packets_sent", packets_sent},
                    {"send_errors", send_errors},
                    {"operator_commands", operator_commands},
                    {"rejected_operator_commands", rejected_commands},
                    {"vision_frames", vision_frames},
                    {"placements_teleported", placements_teleported},
                    {"teleport_errors", teleport_errors},
                    {"state_file_errors", state_file_errors},
                    {"invalid_detections", vision.invalid_detections()},
                    {"command_counter", state.command_counter},
                    {"observations", inputs.observations},
                    {"missing_ball", inputs.missing_ball},
                    {"invalid_ball", inputs.invalid_ball},
                    {"invalid_robot", inputs.invalid_robot},
                    {"unknown_robot_id", inputs.unknown_robot_id},
                    {"duplicate_robot", inputs.duplicate_robot},
                    {"rejected_commands", inputs.rejected_commands},
                    {"time_went_backwards", inputs.time_went_backwards}}});
  if (!published) logger->warn("health: {}", published.error().message);
}

Result<std::unique_ptr<BuiltinRefereeService>> BuiltinRefereeService::open(
    const BuiltinServiceOptions& options, dds::Participant& participant, std::shared_ptr<spdlog::logger> logger,
    time::Clock& wall) {
  auto sender = net::MulticastSender::open(options.group, options.port, options.interface_address);
  if (!sender) return sender.error();
  auto vision = participant.make_reader(dds::topics::kVisionDetection);
  if (!vision) return vision.error();
  auto commands = participant.make_reader(dds::topics::kRefereeCommand);
  if (!commands) return commands.error();
  auto health = dds::HealthReporter::create(participant, options.health_name);
  if (!health) return health.error();
  health->exit_when_stalled();
  std::optional<net::UdpSocket> simulator;
  std::optional<net::Endpoint> simulator_control;
  if (options.teleport_placement_to) {
    auto endpoint = net::Endpoint::parse(*options.teleport_placement_to);
    if (!endpoint) return Error{"teleport placement: " + endpoint.error().message};
    auto socket = net::UdpSocket::open("0.0.0.0", 0);
    if (!socket) return socket.error();
    simulator.emplace(std::move(*socket));
    simulator_control = *endpoint;
  }
  auto impl = std::make_unique<Impl>(options, std::move(*sender), std::move(*vision), std::move(*commands),
                                     std::move(*health), std::move(simulator), simulator_control, std::move(logger),
                                     wall);
  if (const auto directory = std::filesystem::path(options.state_file).parent_path(); !directory.empty()) {
    std::error_code ignored;  // a directory that cannot be made shows as failed writes (state_file_errors)
    std::filesystem::create_directories(directory, ignored);
  }
  impl->resume_saved_match();
  return std::unique_ptr<BuiltinRefereeService>(new BuiltinRefereeService(std::move(impl)));
}

BuiltinRefereeService::BuiltinRefereeService(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

BuiltinRefereeService::~BuiltinRefereeService() { stop(); }

void BuiltinRefereeService::start() {
  if (!thread_.joinable()) thread_ = std::thread([this] { impl_->run(); });
}

void BuiltinRefereeService::stop() {
  impl_->pace.stop();
  if (thread_.joinable()) thread_.join();
}

}  // namespace ssl::referee
