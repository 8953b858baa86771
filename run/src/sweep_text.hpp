// Number and XML text for the sweep's summary files. Private to the run library.
#pragma once

#include <array>
#include <charconv>
#include <string>

namespace fireswarm::run::internal {

/// The shortest text that reads back to the same double ("0.1", "1500", "1e-05").
inline std::string NumberText(double value) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return {buffer.data(), result.ptr};
}

}  // namespace fireswarm::run::internal
