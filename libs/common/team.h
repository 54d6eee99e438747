// The two team colours of a match, and their names on the command line, in config and in DDS partitions.
#pragma once

#include <optional>
#include <string_view>

namespace ssl {

enum class TeamColor { kBlue, kYellow };

/// "blue" or "yellow": the spelling used by flags (--team), config files and DDS partition names.
constexpr std::string_view to_string(TeamColor team) { return team == TeamColor::kBlue ? "blue" : "yellow"; }

/// Parses "blue" or "yellow" (exact, lower case); nullopt for anything else.
constexpr std::optional<TeamColor> parse_team(std::string_view text) {
  if (text == "blue") return TeamColor::kBlue;
  if (text == "yellow") return TeamColor::kYellow;
  return std::nullopt;
}

/// Which half blue defends until a referee says otherwise: the negative one, as the Game Controller starts a
/// match. The built-in referee, world_model (the team frame) and every config default use this one value.
inline constexpr bool kBlueOnPositiveHalfAtStart = false;

constexpr TeamColor opponent(TeamColor team) {
  return team == TeamColor::kBlue ? TeamColor::kYellow : TeamColor::kBlue;
}

}  // namespace ssl
