// EventLog: a long run counts every event and keeps the latest kKeptWorldEvents,
// never dropping an open near miss, and reading by number misses none.
#include <gtest/gtest.h>

#include <cstdint>

#include "fireswarm/sim2d/events.hpp"

namespace fireswarm::sim2d {
namespace {

WorldEvent Event(EventKind kind, double time_s, bool open = false) {
  WorldEvent event;
  event.kind = kind;
  event.time_s = time_s;
  event.open = open;
  return event;
}

TEST(EventLog, CountsEveryEventAndKeepsTheLatest) {
  EventLog log;
  constexpr std::uint64_t kEvents = 3 * kKeptWorldEvents + 7;
  for (std::uint64_t n = 0; n < kEvents; ++n) {
    const EventKind kind = n % 3 == 0 ? EventKind::kTakeOff : EventKind::kLanding;
    EXPECT_EQ(log.Add(Event(kind, static_cast<double>(n))), n);
    log.Trim();
  }
  EXPECT_EQ(log.total(), kEvents);
  EXPECT_EQ(log.size(), kKeptWorldEvents);
  EXPECT_EQ(log.first(), kEvents - kKeptWorldEvents);
  EXPECT_EQ(log.count(EventKind::kTakeOff), (kEvents + 2) / 3);
  EXPECT_EQ(log.count(EventKind::kTakeOff) + log.count(EventKind::kLanding), kEvents);
  EXPECT_EQ(log.at(kEvents - 1).time_s, static_cast<double>(kEvents - 1));
  EXPECT_EQ(log.at(log.first()).time_s, static_cast<double>(log.first()));
  EXPECT_EQ(log.begin()->time_s, static_cast<double>(log.first()));
}

TEST(EventLog, AnOpenNearMissStaysUntilItCloses) {
  EventLog log;
  const std::uint64_t near_miss = log.Add(Event(EventKind::kNearMiss, 0.0, /*open=*/true));
  for (std::size_t n = 0; n < 2 * kKeptWorldEvents; ++n) log.Add(Event(EventKind::kTakeOff, 1.0));
  log.Trim();
  EXPECT_EQ(log.first(), near_miss) << "nothing behind an open one goes";
  log.at(near_miss).min_separation_m = 3.5;  // the tracker updates it by number
  log.at(near_miss).open = false;
  log.Trim();
  EXPECT_EQ(log.size(), kKeptWorldEvents);
  EXPECT_EQ(log.count(EventKind::kNearMiss), 1U);
}

}  // namespace
}  // namespace fireswarm::sim2d
