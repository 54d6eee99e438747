// sslctl: inspect and drive a running stack from the command line.
//   sslctl topic list | echo TOPIC | hz TOPIC | pub TOPIC JSON
//   sslctl estop on|off
//   sslctl health
//   sslctl latency                                        (per-stage latency from the vision stamps)
//   sslctl param list [TARGET] | get TARGET KEY | set TARGET KEY=VALUE... [--save]   (run-time parameters)
//   sslctl log record FILE | replay FILE | info FILE     (the league's SSL log files)
// Every DDS command takes --domain D (and --team blue|yellow for team-scoped topics).
#include <CLI/CLI.hpp>
#include <iostream>

#include "tools/sslctl/commands.h"

namespace {

void add_dds_flags(CLI::App& command, ssl::sslctl::DdsOptions& options, std::string& team) {
  command.add_option("--domain", options.domain_id, "DDS domain id")->check(CLI::Range(0, 232));
  command.add_option("--site", options.site, "site whose DDS discovery to use: sim, field or a directory (default $SSL_SITE)");
  command.add_option("--team", team, "team partition for team-scoped topics")
      ->check(CLI::IsMember({"blue", "yellow"}));
}

/// The multicast ports and interface shared by `log record` and `log replay`.
void add_log_stream_flags(CLI::App& command, ssl::sslctl::LogStreamPorts& ports,
                          std::string& interface_address) {
  const auto port_range = CLI::Range(1, 65535);
  command.add_option("--vision-port", ports.vision, "SSL-Vision port, group 224.5.23.2")
      ->check(port_range)
      ->capture_default_str();
  command.add_option("--legacy-vision-port", ports.legacy_vision, "legacy SSL-Vision port, group 224.5.23.2")
      ->check(port_range)
      ->capture_default_str();
  command.add_option("--referee-port", ports.referee, "game controller port, group 224.5.23.1")
      ->check(port_range)
      ->capture_default_str();
  command.add_option("--tracker-port", ports.tracker, "tracked vision port, group 224.5.23.2")
      ->check(port_range)
      ->capture_default_str();
  command.add_option("--interface", interface_address, "IPv4 address of the network card to use")
      ->capture_default_str();
}

void apply_team(ssl::sslctl::DdsOptions& options, const std::string& team) {
  if (!team.empty()) options.team = ssl::parse_team(team);
}

}  // namespace

int main(int argc, char** argv) {
  ssl::ShutdownSignal shutdown;  // before any DDS thread exists
  CLI::App app{"sslctl: inspect and drive the SSL stack (topics, e-stop, health, latency, log files)", "sslctl"};
  app.require_subcommand(1);

  auto* topic = app.add_subcommand("topic", "DDS topics of the stack");
  topic->require_subcommand(1);

  bool list_json = false;
  auto* list = topic->add_subcommand("list", "every topic with its type, scope and QoS profiles");
  list->add_flag("--json", list_json, "one JSON object per line");

  ssl::sslctl::EchoOptions echo;
  std::string echo_team;
  auto* echo_cmd = topic->add_subcommand("echo", "print samples as JSON, one object per line");
  echo_cmd->add_option("topic", echo.topic, "topic name (see `sslctl topic list`)")->required();
  echo_cmd->add_option("--count", echo.count, "exit after this many samples (0: run until Ctrl-C)");
  echo_cmd->add_option("--timeout", echo.timeout_s, "fail when --count samples did not arrive within S seconds")
      ->check(CLI::NonNegativeNumber);
  echo_cmd->add_flag("--with-meta", echo.with_meta, "wrap samples with their DDS time stamps");
  add_dds_flags(*echo_cmd, echo.dds, echo_team);

  ssl::sslctl::HzOptions hz;
  std::string hz_team;
  auto* hz_cmd = topic->add_subcommand("hz", "measure a topic's rate");
  hz_cmd->add_option("topic", hz.topic, "topic name")->required();
  hz_cmd->add_option("--window", hz.window_s, "report period and averaging window, s")
      ->check(CLI::PositiveNumber);
  hz_cmd->add_option("--duration", hz.duration_s, "stop after S seconds (0: run until Ctrl-C)")
      ->check(CLI::NonNegativeNumber);
  add_dds_flags(*hz_cmd, hz.dds, hz_team);

  ssl::sslctl::PubOptions pub;
  std::string pub_team;
  auto* pub_cmd = topic->add_subcommand("pub", "publish a sample written as JSON (missing fields keep defaults)");
  pub_cmd->add_option("topic", pub.topic, "topic name")->required();
  pub_cmd->add_option("json", pub.samples, "samples as JSON objects, e.g. '{\"engaged\": true}'")->required();
  pub_cmd->add_option("--repeat", pub.repeat, "write the samples N times")->check(CLI::Range(1, 1000000000));
  pub_cmd->add_option("--rate", pub.rate_hz, "write rate when repeating, Hz")->check(CLI::PositiveNumber);
  pub_cmd->add_option("--wait-readers", pub.wait_readers, "first wait until N readers matched");
  pub_cmd->add_option("--wait-timeout", pub.wait_timeout_s, "give up waiting for readers after S seconds")
      ->check(CLI::PositiveNumber);
  pub_cmd->add_option("--linger", pub.linger_s,
                      "keep the writer alive S seconds afterwards for late joiners (-1: until Ctrl-C)");
  add_dds_flags(*pub_cmd, pub.dds, pub_team);

  ssl::sslctl::DdsOptions estop_dds;
  std::string estop_team;
  std::string estop_state;
  std::string estop_reason = "operator";
  double estop_linger = -1;
  auto* estop_cmd = app.add_subcommand(
      "estop", "engage (on) or release (off) the emergency stop of --team, or of every team without it");
  estop_cmd->add_option("state", estop_state, "on or off")->required()->check(CLI::IsMember({"on", "off"}));
  estop_cmd->add_option("--reason", estop_reason, "why, shown to every service");
  estop_cmd->add_option("--linger", estop_linger,
                        "keep asserting for S seconds (-1, the default: until Ctrl-C)");
  add_dds_flags(*estop_cmd, estop_dds, estop_team);

  ssl::sslctl::DdsOptions health_dds;
  std::string health_team;
  double health_listen = 2.0;
  bool health_json = false;
  auto* health_cmd = app.add_subcommand("health", "rate, latency and error counters of every service");
  health_cmd->add_option("--listen", health_listen, "listen this many seconds")->check(CLI::PositiveNumber);
  health_cmd->add_flag("--json", health_json, "one JSON object per service");
  add_dds_flags(*health_cmd, health_dds, health_team);

  ssl::sslctl::LatencyOptions latency;
  auto* latency_cmd = app.add_subcommand(
      "latency", "pipeline latency per stage from the vision stamps (vision_gateway receive -> each topic, and -> "
      "command out of robot_link)");
  latency_cmd->add_option("--listen", latency.listen_s, "collect this many seconds")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  latency_cmd->add_flag("--json", latency.json, "one JSON object per stage");
  latency_cmd->add_option("--domain", latency.domain_id, "DDS domain id")->check(CLI::Range(0, 232));
  latency_cmd->add_option("--site", latency.site, "site whose DDS discovery to use (default $SSL_SITE)");

  auto* param = app.add_subcommand("param", "run-time parameters of the services (planner, world_model, robot_link)");
  param->require_subcommand(1);
  ssl::sslctl::ParamOptions param_options;
  std::string param_team;
  auto* param_list_cmd = param->add_subcommand("list", "every instance's run-time parameters with type, limits and meaning");
  param_list_cmd->add_option("target", param_options.target, "only this instance, e.g. planner/blue");
  param_list_cmd->add_flag("--json", param_options.json, "one JSON object per instance");
  auto* param_get_cmd = param->add_subcommand("get", "one parameter's value");
  param_get_cmd->add_option("target", param_options.target, "instance, e.g. planner/blue")->required();
  param_get_cmd->add_option("key", param_options.key, "dotted key, e.g. planner.limits.max_speed")->required();
  auto* param_set_cmd = param->add_subcommand("set", "change parameters (all or none), wait for the answer");
  param_set_cmd->add_option("target", param_options.target, "instance, e.g. planner/blue")->required();
  param_set_cmd->add_option("assignments", param_options.assignments, "key=value ...");
  param_set_cmd->add_flag("--save", param_options.save,
                          "then save the instance's run-time parameters (loaded at its next start)");
  for (CLI::App* command : {param_list_cmd, param_get_cmd, param_set_cmd}) {
    command->add_option("--timeout", param_options.timeout_s, "wait this many seconds for the instance")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    add_dds_flags(*command, param_options.dds, param_team);
  }

  auto* log = app.add_subcommand("log", "SSL log files in the league's format (.log, .log.gz)");
  log->require_subcommand(1);

  ssl::sslctl::LogRecordOptions record;
  bool record_no_legacy = false;
  auto* record_cmd = log->add_subcommand(
      "record", "record vision, legacy vision, referee and tracker multicast to FILE until Ctrl-C");
  record_cmd->add_option("file", record.file, "log file to write; a .gz suffix compresses it")->required();
  add_log_stream_flags(*record_cmd, record.ports, record.interface_address);
  record_cmd->add_option("--duration", record.duration_s, "stop after S seconds (0: run until Ctrl-C)")
      ->check(CLI::NonNegativeNumber);
  record_cmd->add_flag("--no-legacy", record_no_legacy, "do not record the legacy vision stream");

  ssl::sslctl::LogReplayOptions replay;
  auto* replay_cmd =
      log->add_subcommand("replay", "send a log's records to their multicast groups, timed as recorded");
  replay_cmd->add_option("file", replay.file, "log file to replay (.log or .log.gz)")->required();
  replay_cmd->add_option("--speed", replay.speed, "time factor (2: twice as fast)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  replay_cmd->add_flag("--loop", replay.loop, "start over at the end until Ctrl-C");
  add_log_stream_flags(*replay_cmd, replay.ports, replay.interface_address);

  std::string info_file;
  bool info_json = false;
  auto* info_cmd = log->add_subcommand("info", "counts, duration, cameras and referee commands of a log");
  info_cmd->add_option("file", info_file, "log file (.log or .log.gz)")->required();
  info_cmd->add_flag("--json", info_json, "one JSON object");

  auto* match = app.add_subcommand("match", "the match as the league's streams show it");
  match->require_subcommand(1);
  ssl::sslctl::MatchReportOptions report;
  auto* report_cmd = match->add_subcommand(
      "report", "score, goals, time in play, game events, stalls, robot contacts: live from the referee (and "
                "vision) multicast, or from an SSL log file");
  report_cmd->add_option("file", report.file, "SSL log file (.log or .log.gz); without one: live");
  report_cmd->add_option("--referee-port", report.referee_port, "Referee multicast port (group 224.5.23.1)")
      ->capture_default_str();
  report_cmd->add_option("--vision-port", report.vision_port, "SSL-Vision multicast port (group 224.5.23.2)")
      ->capture_default_str();
  report_cmd->add_option("--interface", report.interface_address, "address of the interface the groups are joined on")
      ->capture_default_str();
  report_cmd->add_option("--duration", report.duration_s, "live: stop after this many seconds (0: until Ctrl-C)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  report_cmd->add_flag("--until-final-whistle", report.until_final_whistle, "live: stop at POST_GAME");
  report_cmd->add_flag("--json", report.json, "one JSON object");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  }

  if (list->parsed()) return ssl::sslctl::topic_list(list_json, std::cout);
  if (echo_cmd->parsed()) {
    apply_team(echo.dds, echo_team);
    return ssl::sslctl::topic_echo(echo, shutdown, std::cout, std::cerr);
  }
  if (hz_cmd->parsed()) {
    apply_team(hz.dds, hz_team);
    return ssl::sslctl::topic_hz(hz, shutdown, std::cout, std::cerr);
  }
  if (pub_cmd->parsed()) {
    apply_team(pub.dds, pub_team);
    return ssl::sslctl::topic_pub(pub, shutdown, std::cout, std::cerr);
  }
  if (estop_cmd->parsed()) {
    apply_team(estop_dds, estop_team);
    return ssl::sslctl::estop(estop_state == "on", estop_reason, estop_dds, estop_linger, shutdown, std::cout,
                              std::cerr);
  }
  if (health_cmd->parsed()) {
    apply_team(health_dds, health_team);
    return ssl::sslctl::health(health_dds, health_listen, health_json, shutdown, std::cout, std::cerr);
  }
  if (latency_cmd->parsed()) return ssl::sslctl::latency(latency, shutdown, std::cout, std::cerr);
  apply_team(param_options.dds, param_team);
  if (param_list_cmd->parsed()) return ssl::sslctl::param_list(param_options, shutdown, std::cout, std::cerr);
  if (param_get_cmd->parsed()) return ssl::sslctl::param_get(param_options, shutdown, std::cout, std::cerr);
  if (param_set_cmd->parsed()) return ssl::sslctl::param_set(param_options, shutdown, std::cout, std::cerr);
  if (record_cmd->parsed()) {
    record.legacy = !record_no_legacy;
    return ssl::sslctl::log_record(record, shutdown, std::cout, std::cerr);
  }
  if (replay_cmd->parsed()) return ssl::sslctl::log_replay(replay, shutdown, std::cout, std::cerr);
  if (info_cmd->parsed()) return ssl::sslctl::log_info(info_file, info_json, std::cout, std::cerr);
  if (report_cmd->parsed()) return ssl::sslctl::match_report(report, shutdown, std::cout, std::cerr);
  return 2;
}
