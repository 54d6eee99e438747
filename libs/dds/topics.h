// Every DDS topic of the stack, in one place: its name, its IDL type and whether it is team-scoped.
//
// A topic's QoS comes only from the XML profiles "<name>.writer" and "<name>.reader" in
// deploy/qos/profiles.xml. Team-scoped topics live in the DDS partition named after the team ("blue",
// "yellow") so that two team stacks share one domain; shared topics (vision, referee, system) use the
// default partition. A team-addressed topic (system.estop) is written to one team's partition or to every
// team's, and read in one team's (robot_link) or every team's (console): so that DDS Security's
// permissions can let only a team's own operators release its e-stop (deploy/dds-certs.sh).
//
//   auto writer = participant.make_writer(ssl::dds::topics::kWorldState, ssl::TeamColor::kBlue);
#pragma once

#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "idl/plannerPubSubTypes.h"
#include "idl/refereePubSubTypes.h"
#include "idl/robotPubSubTypes.h"
#include "idl/systemPubSubTypes.h"
#include "idl/visionPubSubTypes.h"
#include "idl/worldPubSubTypes.h"

namespace ssl::dds {

enum class TopicScope {
  kShared,         // default partition: both teams
  kTeam,           // the team's partition only
  kTeamAddressed,  // the partition of one team, or with no team given, of every team
};

/// A topic: `Sample` is the generated IDL class, `Support` its generated TopicDataType.
template <typename SampleT, typename SupportT>
struct TopicSpec {
  using Sample = SampleT;
  using Support = SupportT;

  std::string_view name;         // DDS topic name, also the prefix of its QoS profile names
  TopicScope scope;
  std::string_view description;  // one line for `sslctl topic list`

  std::string writer_profile() const { return std::string(name) + ".writer"; }
  std::string reader_profile() const { return std::string(name) + ".reader"; }
};

namespace topics {

namespace idl = ::ssl::idl;

inline constexpr TopicSpec<idl::vision::DetectionFrame, idl::vision::DetectionFramePubSubType>
    kVisionDetection{"vision.detection", TopicScope::kShared,
                     "SSL-Vision detections per camera, metres, vision frame"};
inline constexpr TopicSpec<idl::vision::Geometry, idl::vision::GeometryPubSubType> kVisionGeometry{
    "vision.geometry", TopicScope::kShared, "field geometry and camera calibration"};
inline constexpr TopicSpec<idl::referee::RefereeState, idl::referee::RefereeStatePubSubType> kRefereeState{
    "referee.state", TopicScope::kShared, "the whole referee state"};
inline constexpr TopicSpec<idl::referee::RefereeEvent, idl::referee::RefereeEventPubSubType> kRefereeEvent{
    "referee.event", TopicScope::kShared, "game events as they happen"};
inline constexpr TopicSpec<idl::referee::RefereeOperatorCommand, idl::referee::RefereeOperatorCommandPubSubType>
    kRefereeCommand{"referee.command", TopicScope::kShared, "operator commands for the built-in referee"};
inline constexpr TopicSpec<idl::world::WorldState, idl::world::WorldStatePubSubType> kWorldState{
    "world.state", TopicScope::kTeam, "filtered ball and robots, team frame"};
inline constexpr TopicSpec<idl::robot::RobotCommands, idl::robot::RobotCommandsPubSubType> kRobotCommands{
    "robot.commands", TopicScope::kTeam, "every robot's command, one sample per planner tick"};
inline constexpr TopicSpec<idl::robot::CommandsSent, idl::robot::CommandsSentPubSubType> kRobotSent{
    "robot.sent", TopicScope::kTeam, "per command packet robot_link sent: its robot.commands sample and send time"};
inline constexpr TopicSpec<idl::robot::RobotFeedback, idl::robot::RobotFeedbackPubSubType> kRobotFeedback{
    "robot.feedback", TopicScope::kTeam, "per-robot feedback: dribbler contact, battery, kicker"};
inline constexpr TopicSpec<idl::planner::PlannerDebug, idl::planner::PlannerDebugPubSubType> kPlannerDebug{
    "planner.debug", TopicScope::kTeam, "play, roles, tree status and planned paths"};
inline constexpr TopicSpec<idl::system::ParameterSet, idl::system::ParameterSetPubSubType> kSystemParams{
    "system.params", TopicScope::kShared, "dynamic parameters per service instance"};
inline constexpr TopicSpec<idl::system::ParameterState, idl::system::ParameterStatePubSubType> kSystemParamState{
    "system.param_state", TopicScope::kShared, "each service instance's run-time parameters and last answer"};
inline constexpr TopicSpec<idl::system::Estop, idl::system::EstopPubSubType> kSystemEstop{
    "system.estop", TopicScope::kTeamAddressed, "emergency stop, of one team or of every team"};
inline constexpr TopicSpec<idl::system::Health, idl::system::HealthPubSubType> kSystemHealth{
    "system.health", TopicScope::kShared, "per-service rate, latency and error counters"};

/// All topics, for tools that work on any topic by name.
inline constexpr auto kAll = std::make_tuple(kVisionDetection, kVisionGeometry, kRefereeState, kRefereeEvent,
                                             kRefereeCommand, kWorldState, kRobotCommands, kRobotSent, kRobotFeedback, kPlannerDebug,
                                             kSystemParams, kSystemParamState, kSystemEstop, kSystemHealth);

}  // namespace topics

/// Calls `visitor(spec)` with the TopicSpec named `name`; returns false when no topic has that name.
template <typename Visitor>
bool visit_topic(std::string_view name, Visitor&& visitor) {
  return std::apply(
      [&](const auto&... spec) {
        bool found = false;
        ((!found && spec.name == name ? (visitor(spec), found = true) : false), ...);
        return found;
      },
      topics::kAll);
}

/// Name, IDL type name and scope of one topic, for listings.
struct TopicInfo {
  std::string name;
  std::string type_name;
  TopicScope scope;
  std::string writer_profile;
  std::string reader_profile;
  std::string description;
};

/// Every topic of the design, in the order of the design's topic table.
std::vector<TopicInfo> all_topics();

}  // namespace ssl::dds
