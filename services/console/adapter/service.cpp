#include "services/console/adapter/service.h"

#include <httplib.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <thread>

#include "libs/dds/health.h"
#include "libs/dds/topics.h"
#include "libs/domain/idl_convert.h"
#include "libs/net/endpoint.h"
#include "libs/net/udp.h"
#include "libs/time/clock.h"
#include "services/console/adapter/convert.h"
#include "services/console/adapter/stream_hub.h"
#include "services/console/adapter/web_assets.h"
#include "services/console/core/actions.h"
#include "services/referee_gateway/adapter/convert.h"

namespace ssl::console {
namespace {

using nlohmann::json;
namespace topics = dds::topics;

constexpr std::size_t kMaxBody = 64 * 1024;
constexpr auto kStreamPing = std::chrono::milliseconds(1000);  // an idle stream writes a comment this often
constexpr std::string_view kTokenHeader = "X-Console-Token";
constexpr auto kParameterAnswerTimeout = std::chrono::seconds(3);


template <typename T>
struct TeamReaders {
  std::optional<dds::Reader<T>> blue;
  std::optional<dds::Reader<T>> yellow;
  dds::Reader<T>& of(TeamColor team) { return team == TeamColor::kBlue ? *blue : *yellow; }
};

void reply(httplib::Response& res, int status, const json& body) {
  res.status = status;
  res.set_content(body.dump(), "application/json");
}

void reply_error(httplib::Response& res, int status, const std::string& why) {
  reply(res, status, {{"ok", false}, {"error", why}});
}

std::string token_of(const httplib::Request& req) {
  if (req.has_header(std::string(kTokenHeader).c_str())) return req.get_header_value(std::string(kTokenHeader).c_str());
  if (req.has_param("token")) return req.get_param_value("token");
  return {};
}

}  // namespace

struct ConsoleService::Impl {
  ServiceOptions options;
  std::shared_ptr<spdlog::logger> logger;
  AccessPolicy access;
  time::RealClock wall;

  // DDS: readers polled by the loop; writers used by HTTP threads (Fast DDS writers are thread-safe).
  std::optional<dds::Reader<idl::vision::DetectionFrame>> vision;
  std::optional<dds::Reader<idl::vision::Geometry>> geometry;
  std::optional<dds::Reader<idl::referee::RefereeState>> referee;
  std::optional<dds::Reader<idl::referee::RefereeEvent>> referee_events;
  std::optional<dds::Reader<idl::system::Health>> health;
  std::optional<dds::Reader<idl::system::Estop>> estop;
  std::optional<dds::Reader<idl::system::ParameterState>> parameter_states;
  TeamReaders<idl::world::WorldState> worlds;
  TeamReaders<idl::planner::PlannerDebug> debugs;
  TeamReaders<idl::robot::RobotFeedback> feedbacks;
  std::optional<dds::Writer<idl::referee::RefereeOperatorCommand>> referee_commands;
  std::optional<dds::Writer<idl::system::ParameterSet>> parameter_requests;
  std::optional<dds::Participant> estop_participant;
  std::optional<dds::Writer<idl::system::Estop>> estop_writer;
  std::optional<dds::HealthReporter> reporter;

  std::optional<net::UdpSocket> simulator;
  std::optional<net::Endpoint> simulator_control;

  std::mutex mutex;  // guards state and field
  ConsoleState state;
  FieldGeometry field = FieldGeometry::division_b();

  StreamHub hub;
  httplib::Server server;
  std::thread http_thread;
  int port = 0;

  std::atomic<std::uint64_t> frames_built{0};
  std::atomic<std::uint64_t> actions_done{0};
  std::atomic<std::uint64_t> actions_refused{0};
  std::atomic<std::uint64_t> action_errors{0};
  std::atomic<std::uint64_t> streams_opened{0};

  explicit Impl(const ServiceOptions& options_in, std::shared_ptr<spdlog::logger> logger_in)
      : options(options_in),
        logger(std::move(logger_in)),
        access(options.bind, options.token),
        state(options.state),
        hub(options.max_streams) {
    if (options.profile) state.set_profile(*options.profile);
  }

  void routes();
  void poll(time::Timestamp now, bool report_health, bool send_report);
  void stream(const httplib::Request& req, httplib::Response& res);
  /// Runs `act` for an operator's POST when the request may act; answers 403 otherwise.
  template <typename Act>
  void operator_action(const httplib::Request& req, httplib::Response& res, Act act);
  void log_operator(const std::string& text);
  /// Sends a parameter request and waits for its target's answer; replies to the page.
  void parameter_request(const idl::system::ParameterSet& request, const httplib::Request& req, httplib::Response& res);
  std::string who(const httplib::Request& req) const { return "console (" + req.remote_addr + ")"; }
};

void ConsoleService::Impl::log_operator(const std::string& text) {
  std::lock_guard lock(mutex);
  state.on_operator(text, wall.now());
}

template <typename Act>
void ConsoleService::Impl::operator_action(const httplib::Request& req, httplib::Response& res, Act act) {
  if (!access.allows(token_of(req))) {
    ++actions_refused;
    reply_error(res, 403,
                access.operator_possible() ? "operator actions need the console's token (open the page with ?token=...)"
                                           : "this console is read-only: it listens on " + options.bind +
                                                 " without a token (start it with --token)");
    log_operator("refused " + req.path + " from " + req.remote_addr + ": no valid token");
    return;
  }
  act();
}

void ConsoleService::Impl::parameter_request(const idl::system::ParameterSet& request, const httplib::Request& req,
                                             httplib::Response& res) {
  {
    std::lock_guard lock(mutex);
    if (!state.parameters(request.target())) {
      return reply_error(res, 503, "no service '" + request.target() + "' reports run-time parameters");
    }
  }
  if (Status written = parameter_requests->write(request); !written) {
    ++action_errors;
    return reply_error(res, 503, written.error().message);
  }
  // The console loop takes the answer from system.param_state; wait for ours.
  const auto deadline = std::chrono::steady_clock::now() + kParameterAnswerTimeout;
  while (std::chrono::steady_clock::now() < deadline) {
    {
      std::lock_guard lock(mutex);
      const ParameterStateView* answer = state.parameters(request.target());
      if (answer && answer->revision == request.revision()) {
        ++(answer->accepted ? actions_done : action_errors);
        std::string what = request.save() ? "saved " + request.target() + " parameters"
                                          : "set " + request.target() + " " + request.values().front().key() + "=" +
                                                request.values().front().value();
        state.on_operator(what + (answer->accepted ? "" : " refused: " + answer->reason) + " by " + who(req),
                          wall.now());
        return reply(res, 200, {{"ok", answer->accepted},
                                {"status", answer->accepted ? "ok" : "rejected"},
                                {"reason", answer->reason},
                                {"file", answer->saved_file}});
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ++action_errors;
  reply_error(res, 503, request.target() + " did not answer within 3 s");
}

void ConsoleService::Impl::stream(const httplib::Request& req, httplib::Response& res) {
  std::shared_ptr<StreamClient> client = hub.open();
  if (!client) {
    reply_error(res, 503, "too many viewers (" + std::to_string(options.max_streams) + ")");
    return;
  }
  ++streams_opened;
  {
    std::lock_guard lock(mutex);
    const time::Timestamp now = wall.now();
    client->push(std::make_shared<const std::string>("retry: 1000\n\n"));
    client->push(sse_message("hello", state.hello_json(access.allows(token_of(req)), simulator.has_value()).dump()));
    client->push(sse_message("geometry", state.geometry_json().dump()));
    if (state.referee()) client->push(sse_message("referee", state.referee_json().dump()));
    client->push(sse_message("log", state.log_json().dump()));
    client->push(sse_message("params", state.params_json().dump()));
    client->push(sse_message("health", state.health_json(now).dump()));
    client->push(sse_message("report", state.report_json().dump()));
  }
  res.set_header("Cache-Control", "no-cache");
  res.set_chunked_content_provider(
      "text/event-stream",
      [client](std::size_t, httplib::DataSink& sink) {
        const std::vector<Message> messages = client->wait(kStreamPing);
        if (client->closed()) return false;
        if (messages.empty()) {
          static constexpr std::string_view kPing = ": ping\n\n";
          return sink.write(kPing.data(), kPing.size());
        }
        for (const Message& message : messages) {
          if (!sink.write(message->data(), message->size())) return false;
        }
        return true;
      },
      [this, client](bool) { hub.remove(client); });
}

void ConsoleService::Impl::routes() {
  for (const WebAsset& asset : web_assets()) {
    const std::string path = asset.path == "/index.html" ? "/" : std::string(asset.path);
    server.Get(path, [asset](const httplib::Request&, httplib::Response& res) {
      res.set_header("Cache-Control", "no-cache");
      res.set_content(asset.body.data(), asset.body.size(), std::string(asset.content_type).c_str());
    });
  }
  server.Get("/events", [this](const httplib::Request& req, httplib::Response& res) { stream(req, res); });
  server.Get("/api/state", [this](const httplib::Request& req, httplib::Response& res) {
    std::lock_guard lock(mutex);
    const time::Timestamp now = wall.now();
    reply(res, 200,
          {{"hello", state.hello_json(access.allows(token_of(req)), simulator.has_value())},
           {"geometry", state.geometry_json()},
           {"frame", state.frame_json(now)},
           {"referee", state.referee_json()},
           {"log", state.log_json()},
           {"health", state.health_json(now)},
           {"report", state.report_json()},
           {"params", state.params_json()},
           {"viewers", hub.size()}});
  });

  server.Post("/api/referee", [this](const httplib::Request& req, httplib::Response& res) {
    operator_action(req, res, [&] {
      FieldGeometry bounds;
      {
        std::lock_guard lock(mutex);
        bounds = field;
      }
      auto action = parse_referee_action(req.body, bounds);
      if (!action) return reply_error(res, 400, action.error().message);
      const Status written = referee_commands->write(to_idl(*action, who(req), wall.now().nanoseconds()));
      if (!written) {
        ++action_errors;
        return reply_error(res, 503, written.error().message);
      }
      ++actions_done;
      log_operator(std::string(referee::to_string(action->command)) + " by " + who(req));
      reply(res, 200, {{"ok", true}});
    });
  });

  server.Post("/api/estop", [this](const httplib::Request& req, httplib::Response& res) {
    operator_action(req, res, [&] {
      auto action = parse_estop_action(req.body);
      if (!action) return reply_error(res, 400, action.error().message);
      const Status written = estop_writer->write(to_idl(*action, who(req), wall.now().nanoseconds()));
      if (!written) {
        ++action_errors;
        return reply_error(res, 503, written.error().message);
      }
      ++actions_done;
      logger->warn("e-stop {} by {}", action->engaged ? "ENGAGED" : "released", who(req));
      reply(res, 200, {{"ok", true}});
    });
  });

  server.Post("/api/place", [this](const httplib::Request& req, httplib::Response& res) {
    operator_action(req, res, [&] {
      if (!simulator) return reply_error(res, 503, "no simulator: this console has no simulator_control");
      FieldGeometry bounds;
      double heading = 0;
      std::optional<PlaceAction> action;
      {
        std::lock_guard lock(mutex);
        bounds = field;
      }
      auto parsed = parse_place_action(req.body, bounds);
      if (!parsed) return reply_error(res, 400, parsed.error().message);
      action = *parsed;
      if (action->object == PlaceObject::kRobot) {
        std::lock_guard lock(mutex);
        const std::optional<RobotView> seen = state.vision_robot(action->team, action->id);
        heading = action->heading.value_or(seen ? seen->heading : 0.0);
      }
      const std::string bytes = simulator_command(*action, heading);
      const Status sent =
          simulator->send_to(*simulator_control, {reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()});
      if (!sent) {
        ++action_errors;
        return reply_error(res, 503, "simulator: " + sent.error().message);
      }
      ++actions_done;
      char where[64];
      std::snprintf(where, sizeof where, " to (%.2f, %.2f)", action->position.x(), action->position.y());
      log_operator((action->object == PlaceObject::kBall
                        ? std::string("ball placed")
                        : std::string(to_string(action->team)) + " " + std::to_string(action->id) + " placed") +
                   where + " by " + who(req));
      reply(res, 200, {{"ok", true}});
    });
  });

  server.Post("/api/params", [this](const httplib::Request& req, httplib::Response& res) {
    operator_action(req, res, [&] {
      auto action = parse_param_action(req.body);
      if (!action) return reply_error(res, 400, action.error().message);
      const std::int64_t now = wall.now().nanoseconds();
      parameter_request(to_idl(*action, static_cast<std::uint64_t>(now), who(req), now), req, res);
    });
  });

  server.Post("/api/params/save", [this](const httplib::Request& req, httplib::Response& res) {
    operator_action(req, res, [&] {
      auto action = parse_param_save_action(req.body);
      if (!action) return reply_error(res, 400, action.error().message);
      const std::int64_t now = wall.now().nanoseconds();
      parameter_request(save_request(*action, static_cast<std::uint64_t>(now), who(req), now), req, res);
    });
  });

  server.set_error_handler([](const httplib::Request&, httplib::Response& res) {
    if (res.body.empty()) reply_error(res, res.status, "no such page");
  });
}

void ConsoleService::Impl::poll(time::Timestamp now, bool report_health, bool send_report) {
  std::lock_guard lock(mutex);
  for (const auto& sample : vision->take()) state.on_vision(from_idl(sample.data), now);
  if (auto latest = geometry->take_latest()) {
    if (auto converted = field_from_idl(latest->data)) {
      field = *converted;
      state.on_geometry(field);
      hub.push(sse_message("geometry", state.geometry_json().dump()));
    } else {
      logger->warn("vision.geometry dropped: {}", converted.error().message);
    }
  }
  bool referee_changed = false;
  for (const auto& sample : referee->take()) referee_changed |= state.on_referee(referee::from_idl(sample.data), now);
  for (const auto& sample : referee_events->take()) state.on_referee_event(referee::from_idl(sample.data), now);
  for (const auto& sample : health->take()) state.on_health(from_idl(sample.data), now);
  for (const auto& sample : estop->take()) state.on_estop(from_idl(sample.data), now);
  bool parameters_changed = false;
  for (const auto& sample : parameter_states->take()) parameters_changed |= state.on_parameters(from_idl(sample.data));
  if (parameters_changed) hub.push(sse_message("params", state.params_json().dump()));
  for (TeamColor team : {TeamColor::kBlue, TeamColor::kYellow}) {
    if (auto world = worlds.of(team).take_latest()) state.on_world(team, from_idl(world->data), now);
    if (auto debug = debugs.of(team).take_latest()) state.on_debug(team, from_idl(debug->data));
    for (const auto& sample : feedbacks.of(team).take()) state.on_feedback(from_idl(sample.data, team), now);
  }
  if (referee_changed) hub.push(sse_message("referee", state.referee_json().dump()));
  for (const LogEntry& entry : state.take_new_entries()) {
    hub.push(sse_message("event", json{{"t", entry.at.nanoseconds()},
                                       {"kind", to_string(entry.kind)},
                                       {"text", entry.text},
                                       {"team", entry.team ? json(to_string(*entry.team)) : json(nullptr)}}
                                      .dump()));
  }
  if (hub.size() > 0) {
    hub.push_frame(sse_message("frame", state.frame_json(now).dump()));
    ++frames_built;
  }
  if (report_health) {
    hub.push(sse_message("health", state.health_json(now).dump()));
    if (state.referee()) hub.push(sse_message("referee", state.referee_json().dump()));
  }
  if (send_report) hub.push(sse_message("report", state.report_json().dump()));
}

ConsoleService::ConsoleService(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

ConsoleService::~ConsoleService() {
  if (impl_->http_thread.joinable()) {
    impl_->hub.close_all();
    impl_->server.stop();
    impl_->http_thread.join();
  }
}

Result<std::unique_ptr<ConsoleService>> ConsoleService::create(const ServiceOptions& options,
                                                               dds::Participant& participant,
                                                               std::shared_ptr<spdlog::logger> logger) {
  auto impl = std::make_unique<Impl>(options, logger);
  Impl& s = *impl;
  auto open = [&](auto& slot, const auto& spec, std::optional<TeamColor> team = std::nullopt) -> Status {
    auto reader = participant.make_reader(spec, team);
    if (!reader) return reader.error();
    slot.emplace(std::move(*reader));
    return {};
  };
  for (Status opened : {open(s.vision, topics::kVisionDetection), open(s.geometry, topics::kVisionGeometry),
                        open(s.referee, topics::kRefereeState), open(s.referee_events, topics::kRefereeEvent),
                        open(s.health, topics::kSystemHealth), open(s.estop, topics::kSystemEstop),
                        open(s.parameter_states, topics::kSystemParamState),
                        open(s.worlds.blue, topics::kWorldState, TeamColor::kBlue),
                        open(s.worlds.yellow, topics::kWorldState, TeamColor::kYellow),
                        open(s.debugs.blue, topics::kPlannerDebug, TeamColor::kBlue),
                        open(s.debugs.yellow, topics::kPlannerDebug, TeamColor::kYellow),
                        open(s.feedbacks.blue, topics::kRobotFeedback, TeamColor::kBlue),
                        open(s.feedbacks.yellow, topics::kRobotFeedback, TeamColor::kYellow)}) {
    if (!opened) return opened.error();
  }
  auto commands = participant.make_writer(topics::kRefereeCommand);
  if (!commands) return commands.error();
  s.referee_commands.emplace(std::move(*commands));
  auto parameter_requests = participant.make_writer(topics::kSystemParams);
  if (!parameter_requests) return parameter_requests.error();
  s.parameter_requests.emplace(std::move(*parameter_requests));
  auto estop_participant = dds::Participant::create(options.estop_participant);
  if (!estop_participant) return estop_participant.error();
  s.estop_participant.emplace(std::move(*estop_participant));
  auto estop_writer = s.estop_participant->make_writer(topics::kSystemEstop);
  if (!estop_writer) return estop_writer.error();
  s.estop_writer.emplace(std::move(*estop_writer));
  // One health instance per console: a match may have several (the coach box's, a laptop's).
  auto reporter = dds::HealthReporter::create(participant, "console/" + std::to_string(options.http_port));
  if (!reporter) return reporter.error();
  reporter->exit_when_stalled();
  s.reporter.emplace(std::move(*reporter));

  if (!options.simulator_control.empty()) {
    auto endpoint = net::Endpoint::parse(options.simulator_control);
    if (!endpoint) return Error{"simulator_control: " + endpoint.error().message};
    auto socket = net::UdpSocket::open("0.0.0.0", 0);
    if (!socket) return socket.error();
    s.simulator.emplace(std::move(*socket));
    s.simulator_control = *endpoint;
  }

  const std::size_t threads = options.max_streams + 8;  // every open stream holds one
  s.server.new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  s.server.set_payload_max_length(kMaxBody);
  s.server.set_keep_alive_max_count(1000);
  s.routes();
  if (options.http_port == 0) {
    s.port = s.server.bind_to_any_port(options.bind);
    if (s.port <= 0) return Error{"cannot listen on " + options.bind + " (any port)"};
  } else {
    if (!s.server.bind_to_port(options.bind, options.http_port)) {
      return Error{"cannot listen on " + options.bind + ":" + std::to_string(options.http_port) +
                   " (in use by another console? --http-port P)"};
    }
    s.port = options.http_port;
  }
  if (!s.access.operator_possible()) {
    logger->warn("listening on {} without a token: the page is read-only (give --token to allow operator actions)",
                 options.bind);
  }
  return std::unique_ptr<ConsoleService>(new ConsoleService(std::move(impl)));
}

int ConsoleService::port() const { return impl_->port; }

void ConsoleService::run(ShutdownSignal& shutdown) {
  Impl& s = *impl_;
  s.http_thread = std::thread([&s] { s.server.listen_after_bind(); });
  const auto period = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::duration<double>(1.0 / s.options.frame_rate));
  time::MonotonicClock monotonic;
  time::Timestamp next_health = monotonic.now();
  time::Timestamp next_report = monotonic.now();
  std::uint64_t frames_at_last_report = 0;
  // A fixed grid of frame times (not a sleep after each frame), so that viewers get frame_rate frames a
  // second; a late tick is not made up.
  time::Timestamp next_frame = monotonic.now() + period;
  while (!shutdown.wait_for(std::max(next_frame - monotonic.now(), std::chrono::nanoseconds(0)))) {
    const time::Timestamp tick = monotonic.now();
    next_frame = std::max(next_frame + period, tick);
    const bool report_health = tick >= next_health;
    const bool send_report = tick >= next_report;
    s.poll(s.wall.now(), report_health, send_report);
    if (send_report) next_report = tick + std::chrono::seconds(5);
    if (!report_health) continue;
    next_health = tick + std::chrono::seconds(1);
    const std::uint64_t frames = s.frames_built.load();
    dds::HealthReport report{.level = dds::HealthLevel::kOk,
                             .status = std::to_string(s.hub.size()) + " viewer(s) on " + s.options.bind + ":" +
                                       std::to_string(s.port),
                             .rate_hz = static_cast<double>(frames - frames_at_last_report),
                             .errors = s.action_errors.load(),
                             .dropped = s.hub.dropped(),
                             .counters = {{"viewers", s.hub.size()},
                                          {"streams_opened", s.streams_opened.load()},
                                          {"frames_built", frames},
                                          {"frames_dropped_for_slow_viewers", s.hub.dropped()},
                                          {"actions_done", s.actions_done.load()},
                                          {"actions_refused", s.actions_refused.load()}}};
    frames_at_last_report = frames;
    if (Status published = s.reporter->publish(report); !published) {
      s.logger->warn("system.health: {}", published.error().message);
    }
  }
  s.hub.close_all();
  s.server.stop();
  s.http_thread.join();
}

}  // namespace ssl::console
