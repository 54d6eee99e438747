// The built-in referee's small vocabulary of commands by team, shared by its translation units
// (builtin_referee.cpp, builtin_referee_fouls.cpp). Not part of the referee's interface.
#pragma once

#include "libs/common/team.h"
#include "services/referee_gateway/core/types.h"

namespace ssl::referee::builtin {

inline Team to_team(TeamColor color) { return color == TeamColor::kYellow ? Team::kYellow : Team::kBlue; }

inline Command kickoff(TeamColor team) {
  return team == TeamColor::kYellow ? Command::kPrepareKickoffYellow : Command::kPrepareKickoffBlue;
}
inline Command penalty(TeamColor team) {
  return team == TeamColor::kYellow ? Command::kPreparePenaltyYellow : Command::kPreparePenaltyBlue;
}
inline Command direct_free(TeamColor team) {
  return team == TeamColor::kYellow ? Command::kDirectFreeYellow : Command::kDirectFreeBlue;
}
inline Command ball_placement(TeamColor team) {
  return team == TeamColor::kYellow ? Command::kBallPlacementYellow : Command::kBallPlacementBlue;
}

}  // namespace ssl::referee::builtin
