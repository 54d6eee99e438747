// The built-in referee's inputs at the adapter edge, converted once:
//  * VisionObservation: the newest vision.detection frame of each camera (IDL, metres, SSL-Vision global
//    frame) merged into the core's Observation: every robot seen by a fresh camera (several cameras: the
//    mean of their detections), the ball of the most confident fresh detection. A camera whose newest
//    frame is older than `max_age` (receive time, this host's wall clock) is left out; non-finite values
//    are dropped here and counted.
//  * operator_command(): a referee.command sample -> the core's command and target (nullopt for a value
//    outside the league's Command enum).
//
//   VisionObservation vision;
//   for (const auto& s : reader.take()) vision.add(s.data);
//   referee.step(vision.observe(wall.now(), 100ms), wall.now());
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <utility>

#include "idl/referee.h"
#include "idl/vision.h"
#include "libs/time/time.h"
#include "services/referee_gateway/builtin/builtin_referee.h"

namespace ssl::referee {

class VisionObservation {
 public:
  /// Keeps `frame` as its camera's newest (a frame captured before the kept one is ignored).
  void add(const idl::vision::DetectionFrame& frame);

  /// The merged observation of the cameras whose newest frame arrived at most `max_age` before `now`
  /// (both this host's wall clock).
  Observation observe(time::Timestamp now, time::Duration max_age) const;

  /// Detections dropped for non-finite coordinates, since construction.
  std::uint64_t invalid_detections() const { return invalid_; }

 private:
  std::map<std::uint32_t, idl::vision::DetectionFrame> newest_;  // by camera id
  mutable std::uint64_t invalid_ = 0;
};

struct OperatorCommand {
  Command command = Command::kHalt;
  std::optional<Vec2> designated_position;  // m, vision frame
};

/// A referee.command sample in core terms; nullopt when its command is not a league command.
std::optional<OperatorCommand> operator_command(const idl::referee::RefereeOperatorCommand& sample);

}  // namespace ssl::referee
