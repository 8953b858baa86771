// An operator's order to the server (lcmtypes/operator_command_t.lcm's commands).
#pragma once

#include <cstdint>
#include <string>

#include "fireswarm/common/local_frame.hpp"

namespace fireswarm::server {

/// An operator's order (lcmtypes/operator_command_t.lcm's commands).
struct OperatorCommand {
  enum class Kind : std::uint8_t {
    kStart = 1,
    kAbort = 2,
    kReturnAll = 3,
    kInvestigatePoint = 4,
    kRetaskVehicle = 5,
    kHold = 6,
    kResume = 7,
    kReturnVehicle = 8,
    kLand = 9,
    kHoldAll = 10,
    kResumeAll = 11,
  };
  Kind kind = Kind::kStart;
  std::uint8_t vehicle = 0;  ///< kRetaskVehicle (required), kInvestigatePoint (0 = server chooses)
  common::LatLon point;      ///< kInvestigatePoint, kRetaskVehicle
  double radius_m = 0.0;     ///< 0 = the configured radius
  std::string reason;        ///< for the journal
};

}  // namespace fireswarm::server
