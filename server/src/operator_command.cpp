#include "fireswarm/server/operator_command.hpp"

namespace fireswarm::server {

const char* ToString(OperatorCommand::Kind kind) {
  using Kind = OperatorCommand::Kind;
  switch (kind) {
    case Kind::kStart:
      return "start";
    case Kind::kAbort:
      return "abort";
    case Kind::kReturnAll:
      return "return_all";
    case Kind::kInvestigatePoint:
      return "investigate";
    case Kind::kRetaskVehicle:
      return "retask";
    case Kind::kHold:
      return "hold";
    case Kind::kResume:
      return "resume";
    case Kind::kReturnVehicle:
      return "return";
    case Kind::kLand:
      return "land";
    case Kind::kHoldAll:
      return "hold_all";
    case Kind::kResumeAll:
      return "resume_all";
  }
  return "unknown";
}

bool NeedsVehicle(OperatorCommand::Kind kind) {
  using Kind = OperatorCommand::Kind;
  return kind == Kind::kRetaskVehicle || kind == Kind::kHold || kind == Kind::kResume ||
         kind == Kind::kReturnVehicle || kind == Kind::kLand;
}

}  // namespace fireswarm::server
