// FrameParser allocates nothing while parsing: this file replaces the global
// operator new/delete of the test program with counting versions (malloc/free
// underneath) and counts only while a parse is running.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <random>
#include <vector>

#include "fireswarm/radio/parser.hpp"

namespace {

std::atomic<bool> g_counting{false};
std::atomic<std::uint64_t> g_allocations{0};

void* CountedAllocate(std::size_t size) {
  if (g_counting.load(std::memory_order_relaxed)) {
    g_allocations.fetch_add(1, std::memory_order_relaxed);
  }
  if (void* memory = std::malloc(size == 0 ? 1 : size)) return memory;
  throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t size) {
  return CountedAllocate(size);
}
void* operator new[](std::size_t size) {
  return CountedAllocate(size);
}
void operator delete(void* memory) noexcept {
  std::free(memory);
}
void operator delete[](void* memory) noexcept {
  std::free(memory);
}
void operator delete(void* memory, std::size_t /*size*/) noexcept {
  std::free(memory);
}
void operator delete[](void* memory, std::size_t /*size*/) noexcept {
  std::free(memory);
}
// The nothrow forms too (std::stable_sort's buffer uses them): replacing only some
// forms would pair another allocator's new with this free, which ASan rejects.
void* operator new(std::size_t size, const std::nothrow_t& /*tag*/) noexcept {
  try {
    return CountedAllocate(size);
  } catch (const std::bad_alloc&) {
    return nullptr;
  }
}
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept {
  return operator new(size, tag);
}
void operator delete(void* memory, const std::nothrow_t& /*tag*/) noexcept {
  std::free(memory);
}
void operator delete[](void* memory, const std::nothrow_t& /*tag*/) noexcept {
  std::free(memory);
}

namespace fireswarm::radio {
namespace {

using Bytes = std::vector<std::uint8_t>;

// About `size` bytes of frames of mixed sizes with random garbage (some of it
// false preambles) between them; returns the number of frames written.
std::size_t MakeMixedStream(std::size_t size, ChecksumMode mode, Bytes& out) {
  std::mt19937_64 rng(12345);
  const auto uniform = [&rng](int low, int high) {
    return std::uniform_int_distribution(low, high)(rng);
  };
  std::size_t frames = 0;
  Bytes data;
  while (out.size() < size) {
    data.resize(static_cast<std::size_t>(uniform(0, 255)));
    for (std::uint8_t& byte : data) byte = static_cast<std::uint8_t>(uniform(0, 255));
    AppendFrame(out, static_cast<std::uint8_t>(uniform(0, 255)), 0x10, data, mode);
    ++frames;
    if (uniform(0, 3) == 0) out.insert(out.end(), {0x70, 0x96, 0xAC, 0x01, 0x10});
    for (int garbage = uniform(0, 20); garbage > 0; --garbage) {
      out.push_back(static_cast<std::uint8_t>(uniform(0, 255)));
    }
  }
  return frames;
}

TEST(FrameParserAllocation, ParsingOneMegabyteAllocatesNothing) {
  for (const ChecksumMode mode : {ChecksumMode::kCrc16, ChecksumMode::kXor}) {
    Bytes stream;
    const std::size_t frames_written = MakeMixedStream(1 << 20, mode, stream);
    std::mt19937_64 rng(7);
    std::vector<std::size_t> chunk_sizes;
    for (std::size_t total = 0; total < stream.size();) {
      chunk_sizes.push_back(std::uniform_int_distribution<std::size_t>(1, 6000)(rng));
      total += chunk_sizes.back();
    }

    std::uint64_t frames = 0;
    std::uint64_t data_bytes = 0;
    const auto on_frame = [&](const FrameView& frame) {
      ++frames;
      data_bytes += frame.data.size();
    };
    g_allocations = 0;
    g_counting = true;
    {
      FrameParser parser(mode);
      std::span<const std::uint8_t> rest(stream);
      for (const std::size_t chunk : chunk_sizes) {
        const std::size_t size = std::min(chunk, rest.size());
        parser.Feed(rest.first(size), on_frame);
        rest = rest.subspan(size);
      }
      parser.Finish(on_frame);
    }
    g_counting = false;

    EXPECT_EQ(g_allocations.load(), 0U) << ToString(mode);
    EXPECT_GT(data_bytes, 0U);
    // XOR lets about 1 in 256 false candidates through; CRC-16 loses no frame here.
    if (mode == ChecksumMode::kCrc16) {
      EXPECT_EQ(frames, frames_written);
    }
  }
}

}  // namespace
}  // namespace fireswarm::radio
