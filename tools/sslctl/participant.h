// The participant of an sslctl command (internal to the commands library).
#pragma once

#include <optional>
#include <string>

#include "libs/common/result.h"
#include "libs/common/team.h"
#include "libs/dds/participant.h"

namespace ssl::sslctl {

/// This command's participant on `domain_id`, found by the others as the site says (libs/service/setup.h);
/// with the site's DDS security on, as the operator of `team`, or of every team without one.
Result<dds::Participant> open_participant(int domain_id, const std::string& site, std::optional<TeamColor> team,
                                          std::string name);

}  // namespace ssl::sslctl
