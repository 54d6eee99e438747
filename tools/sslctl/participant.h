// The participant of an sslctl command (internal to the commands library).
#pragma once

#include <string>

#include "libs/common/result.h"
#include "libs/dds/participant.h"

namespace ssl::sslctl {

/// This command's participant on `domain_id`, found by the others as the site says (libs/service/setup.h).
Result<dds::Participant> open_participant(int domain_id, const std::string& site, std::string name);

}  // namespace ssl::sslctl
