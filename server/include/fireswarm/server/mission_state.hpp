// Where the whole mission is, as the server sees it.
#pragma once

#include <cstdint>

namespace fireswarm::server {

enum class MissionState : std::int8_t {  // mission_status_t's STATE_* values
  kIdle = 0,
  kUploading = 1,
  kRunning = 2,
  kReturning = 3,
  kComplete = 4,
  kAborted = 5,
};
const char* ToString(MissionState state);

}  // namespace fireswarm::server
