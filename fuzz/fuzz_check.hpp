// What every fuzz target shares: its entry point's declaration and a property
// check that aborts (a finding for libFuzzer, a failed ctest for the replay).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

/// libFuzzer's entry point; every fuzz/<name>_fuzz.cpp defines it.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace fireswarm::fuzz {

/// Aborts with `property` on stderr when `holds` is false.
inline void Check(bool holds, const char* property) {
  if (holds) return;
  std::fprintf(stderr, "fuzz property violated: %s\n", property);
  std::abort();
}

}  // namespace fireswarm::fuzz
