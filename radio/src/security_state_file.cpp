#include "fireswarm/radio/security_state_file.hpp"

#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "fireswarm/common/atomic_file.hpp"

namespace fireswarm::radio {
namespace {

constexpr const char* kMagic = "fireswarm-radio-security";
constexpr int kVersion = 1;
constexpr mode_t kStateFileMode = 0600;

[[noreturn]] void Malformed(const std::filesystem::path& path, int line, const std::string& what) {
  throw std::runtime_error(path.string() + ":" + std::to_string(line) + ": " + what);
}

}  // namespace

SecurityState ReadSecurityStateFile(const std::filesystem::path& path) {
  SecurityState state;
  std::ifstream in(path);
  if (!in) {
    if (!std::filesystem::exists(path)) return state;
    throw std::runtime_error(path.string() + ": cannot be read");
  }
  std::string text;
  int line_number = 0;
  bool header_seen = false;
  while (std::getline(in, text)) {
    ++line_number;
    if (text.empty()) continue;
    std::istringstream line(text);
    std::string key;
    line >> key;
    if (!header_seen) {
      int version = 0;
      if (key != kMagic || !(line >> version) || version != kVersion) {
        Malformed(path, line_number, "expected '" + std::string(kMagic) + " 1'");
      }
      header_seen = true;
    } else if (key == "next_counter") {
      if (!(line >> state.next_counter))
        Malformed(path, line_number, "next_counter needs a number");
    } else if (key == "floor") {
      unsigned key_id = 0;
      std::uint64_t floor = 0;
      if (!(line >> key_id >> floor) || key_id > std::numeric_limits<std::uint8_t>::max() ||
          floor > std::numeric_limits<std::uint32_t>::max()) {
        Malformed(path, line_number, "floor needs a key ID 0..255 and a counter 0..4294967295");
      }
      state.floors[static_cast<std::uint8_t>(key_id)] = static_cast<std::uint32_t>(floor);
    } else {
      Malformed(path, line_number, "unknown entry '" + key + "'");
    }
  }
  if (!header_seen) Malformed(path, 1, "empty file");
  return state;
}

void WriteSecurityStateFile(const std::filesystem::path& path, const SecurityState& state) {
  std::ostringstream out;
  out << kMagic << ' ' << kVersion << '\n' << "next_counter " << state.next_counter << '\n';
  for (const auto& [key_id, floor] : state.floors) {
    out << "floor " << static_cast<unsigned>(key_id) << ' ' << floor << '\n';
  }
  common::WriteFileAtomically(path, out.str(), kStateFileMode);
}

PersistSecurityState PersistToFile(std::filesystem::path path) {
  return [path = std::move(path)](const SecurityState& state) {
    try {
      WriteSecurityStateFile(path, state);
      return true;
    } catch (const std::exception&) {
      return false;  // runs in a radio callback: the caller counts it
    }
  };
}

}  // namespace fireswarm::radio
