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
    kHold = 6,           ///< `vehicle` holds where it is
    kResume = 7,         ///< `vehicle` resumes what the hold (or an investigation) interrupted
    kReturnVehicle = 8,  ///< `vehicle` returns to launch
    kLand = 9,           ///< `vehicle` lands where it is
    kHoldAll = 10,       ///< every registered vehicle holds
    kResumeAll = 11,     ///< every registered vehicle resumes
  };
  Kind kind = Kind::kStart;
  /// Receiver ID: required by kRetaskVehicle, kHold, kResume, kReturnVehicle and
  /// kLand; kInvestigatePoint: 0 = the server chooses; others: unused (0).
  std::uint8_t vehicle = 0;
  common::LatLon point;   ///< kInvestigatePoint, kRetaskVehicle
  double radius_m = 0.0;  ///< 0 = the configured radius
  std::string reason;     ///< for the journal
};

/// The command's name in the journal and the command-center API: "start", "abort",
/// "return_all", "investigate", "retask", "hold", "resume", "return", "land",
/// "hold_all", "resume_all"; "unknown" outside the enum.
const char* ToString(OperatorCommand::Kind kind);
/// True for the commands to one vehicle that `vehicle` must name (kRetaskVehicle,
/// kHold, kResume, kReturnVehicle, kLand).
bool NeedsVehicle(OperatorCommand::Kind kind);

}  // namespace fireswarm::server
