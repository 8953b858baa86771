// The names of the payloads' enum values, one function beside each enum
// (messages.hpp): what reports, logs, JSON lines and the LCM bridge print.
#include <string_view>

#include "fireswarm/radio/messages.hpp"

namespace fireswarm::radio {

std::string_view ToString(ReplyKind kind) {
  switch (kind) {
    case ReplyKind::kTelemetry:
      return "telemetry";
    case ReplyKind::kFireReport:
      return "fire_report";
    case ReplyKind::kAck:
      return "ack";
  }
  return "unknown";
}

std::string_view ToString(FlightMode mode) {
  switch (mode) {
    case FlightMode::kIdle:
      return "idle";
    case FlightMode::kTakeoff:
      return "takeoff";
    case FlightMode::kSearch:
      return "search";
    case FlightMode::kInvestigate:
      return "investigate";
    case FlightMode::kReturnToLaunch:
      return "return_to_launch";
    case FlightMode::kLand:
      return "land";
    case FlightMode::kLanded:
      return "landed";
    case FlightMode::kHold:
      return "hold";
  }
  return "unknown";
}

std::string_view ToString(MissionAckStatus status) {
  switch (status) {
    case MissionAckStatus::kAccepted:
      return "accepted";
    case MissionAckStatus::kComplete:
      return "complete";
    case MissionAckStatus::kRejected:
      return "rejected";
  }
  return "unknown";
}

std::string_view ToString(CommandType type) {
  switch (type) {
    case CommandType::kStartMission:
      return "start_mission";
    case CommandType::kHold:
      return "hold";
    case CommandType::kResume:
      return "resume";
    case CommandType::kReturnToLaunch:
      return "return_to_launch";
    case CommandType::kLand:
      return "land";
    case CommandType::kInvestigate:
      return "investigate";
    case CommandType::kAbort:
      return "abort";
    case CommandType::kAvoid:
      return "avoid";
  }
  return "unknown";
}

std::string_view ToString(CommandResult result) {
  switch (result) {
    case CommandResult::kAccepted:
      return "accepted";
    case CommandResult::kRejected:
      return "rejected";
    case CommandResult::kUnsupported:
      return "unsupported";
  }
  return "unknown";
}

std::string_view ToString(ParamStatus status) {
  switch (status) {
    case ParamStatus::kOk:
      return "ok";
    case ParamStatus::kUnknownParam:
      return "unknown_param";
    case ParamStatus::kReadOnly:
      return "read_only";
    case ParamStatus::kOutOfRange:
      return "out_of_range";
  }
  return "unknown";
}

}  // namespace fireswarm::radio
