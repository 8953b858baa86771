// The file a side keeps its secure-mode state in (frame_security.hpp): the vehicle
// next to its parameter file, the server in its state directory next to its
// journal. Text, one fact per line, written atomically with mode 0600:
//   fireswarm-radio-security 1
//   next_counter 2048
//   floor 3 1177          (key ID, lowest counter still accepted)
#pragma once

#include <filesystem>

#include "fireswarm/radio/frame_security.hpp"

namespace fireswarm::radio {

/// The state in `path`; a first start (all zero) when the file does not exist.
/// Throws std::runtime_error naming the path and line when it is malformed.
SecurityState ReadSecurityStateFile(const std::filesystem::path& path);

/// Writes `state` atomically with mode 0600. Throws std::runtime_error naming the path.
void WriteSecurityStateFile(const std::filesystem::path& path, const SecurityState& state);

/// A PersistSecurityState that writes to `path` and reports failure as false.
PersistSecurityState PersistToFile(std::filesystem::path path);

}  // namespace fireswarm::radio
