#include "fireswarm/server/journal.hpp"

#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <boost/crc.hpp>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace fireswarm::server {
namespace {

using ::testing::HasSubstr;
using ::testing::SizeIs;

namespace fs = std::filesystem;

// A fresh directory per test under gtest's temporary directory, removed at the
// end unless the test failed (kept to look at).
struct ScopedDir {
  ScopedDir() {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    // Parameterised names hold '/': one directory level per test all the same.
    std::string leaf = std::string(info->test_suite_name()) + "." + info->name();
    std::replace(leaf.begin(), leaf.end(), '/', '_');
    path = fs::path(::testing::TempDir()) / ("journal_test_" + std::to_string(::getpid())) / leaf;
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~ScopedDir() {
    if (::testing::Test::HasFailure()) return;
    std::error_code ignored;
    fs::remove_all(path, ignored);
    fs::remove(path.parent_path(), ignored);  // only once empty: the last test's
  }
  ScopedDir(const ScopedDir&) = delete;
  ScopedDir& operator=(const ScopedDir&) = delete;
  fs::path path;
};

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

void WriteFile(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

void AppendToFile(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::app);
  out << bytes;
}

std::vector<JournalRecord> OpenAndRead(const fs::path& path, JournalRecovery* recovery = nullptr) {
  std::vector<JournalRecord> records;
  Journal journal =
      Journal::Open(path, [&](const JournalRecord& record) { records.push_back(record); });
  if (recovery != nullptr) *recovery = journal.recovery();
  return records;
}

// The data of record i in the tests below: sizes vary so lines cross page
// boundaries at different places.
nlohmann::json DataOf(std::uint64_t i) {
  return {{"i", i},
          {"track", {{"lat_deg", 46.5 + 1e-7 * static_cast<double>(i)}}},
          {"pad", std::string(static_cast<std::size_t>(i % 97) * 61, 'x')}};
}

void AppendRecords(Journal& journal, std::uint64_t count) {
  for (std::uint64_t k = 0; k < count; ++k) {
    const std::uint64_t seq = journal.next_seq();
    ASSERT_EQ(journal.Append(0.5 * static_cast<double>(seq), "fire_track", DataOf(seq)), seq);
  }
}

void ExpectRecords(const std::vector<JournalRecord>& records, std::uint64_t count) {
  ASSERT_THAT(records, SizeIs(count));
  for (std::uint64_t seq = 1; seq <= count; ++seq) {
    const JournalRecord& record = records[seq - 1];
    EXPECT_EQ(record.seq, seq);
    EXPECT_EQ(record.t_s, 0.5 * static_cast<double>(seq));
    EXPECT_EQ(record.kind, "fire_track");
    EXPECT_EQ(record.data, DataOf(seq)) << "seq " << seq;
  }
}

TEST(Journal, ReadsBackAppendedRecordsInOrderAfterReopening) {
  const ScopedDir dir;
  const fs::path path = dir.path / "mission.jsonl";
  {
    Journal journal = Journal::Open(path, [](const JournalRecord&) { FAIL() << "new file"; });
    EXPECT_EQ(journal.next_seq(), 1U);
    AppendRecords(journal, 25);
  }
  JournalRecovery recovery;
  ExpectRecords(OpenAndRead(path, &recovery), 25);
  EXPECT_EQ(recovery.records, 25U);
  EXPECT_EQ(recovery.dropped_lines, 0U);
}

TEST(Journal, ContinuesTheSequenceAcrossReopens) {
  const ScopedDir dir;
  const fs::path path = dir.path / "mission.jsonl";
  for (int session = 0; session < 3; ++session) {
    Journal journal = Journal::Open(path, [](const JournalRecord&) {});
    EXPECT_EQ(journal.next_seq(), 1U + 4U * static_cast<std::uint64_t>(session));
    AppendRecords(journal, 4);
  }
  ExpectRecords(OpenAndRead(path), 12);
}

TEST(Journal, KeepsExactValuesOfEveryJsonKind) {
  const ScopedDir dir;
  const fs::path path = dir.path / "mission.jsonl";
  const nlohmann::json data = {{"double", 0.1 + 0.2},
                               {"negative", -1234567890123LL},
                               {"text", "ligne\n\"quoted\" \u00e9\u00e8"},
                               {"null", nullptr},
                               {"list", {1, 2.5, "three"}},
                               {"tiny", 5e-324}};
  {
    Journal journal = Journal::Open(path, [](const JournalRecord&) {});
    journal.Append(12.25, "mission_state", data);
    journal.Append(13.0, "scalar", 42);
  }
  const std::vector<JournalRecord> records = OpenAndRead(path);
  ASSERT_THAT(records, SizeIs(2));
  EXPECT_EQ(records[0], (JournalRecord{1, 12.25, "mission_state", data}));
  EXPECT_EQ(records[1], (JournalRecord{2, 13.0, "scalar", 42}));
  // One record per line: the newline inside the string is escaped.
  const std::string bytes = ReadFile(path);
  EXPECT_EQ(std::count(bytes.begin(), bytes.end(), '\n'), 2);
  // Each line is plain JSON.
  std::istringstream lines(bytes);
  for (std::string line; std::getline(lines, line);) {
    const nlohmann::json object = nlohmann::json::parse(line);
    EXPECT_TRUE(object.contains("crc")) << line;
  }
}

TEST(Journal, RefusesAnEmptyKindANonFiniteTimeAndInvalidUtf8WritingNothing) {
  const ScopedDir dir;
  const fs::path path = dir.path / "mission.jsonl";
  Journal journal = Journal::Open(path, [](const JournalRecord&) {});
  EXPECT_THROW(journal.Append(1.0, "", {}), std::invalid_argument);
  EXPECT_THROW(journal.Append(std::numeric_limits<double>::quiet_NaN(), "k", {}),
               std::invalid_argument);
  EXPECT_THROW(journal.Append(std::numeric_limits<double>::infinity(), "k", {}),
               std::invalid_argument);
  EXPECT_THROW(journal.Append(1.0, "k", std::string("\xff\xfe")), std::invalid_argument);
  EXPECT_EQ(fs::file_size(path), 0U);
  EXPECT_EQ(journal.Append(1.0, "k", {}), 1U);
}

TEST(Journal, DropsATornLastLineAndAppendsCleanlyAfterIt) {
  const ScopedDir dir;
  const fs::path path = dir.path / "mission.jsonl";
  {
    Journal journal = Journal::Open(path, [](const JournalRecord&) {});
    AppendRecords(journal, 3);
  }
  const auto intact_size = fs::file_size(path);
  const std::string torn = R"({"seq":4,"t":2.0,"kind":"fire_tr)";
  AppendToFile(path, torn);
  {
    std::uint64_t replayed = 0;
    Journal journal = Journal::Open(path, [&](const JournalRecord&) { ++replayed; });
    EXPECT_EQ(replayed, 3U);
    EXPECT_EQ(journal.recovery().records, 3U);
    EXPECT_EQ(journal.recovery().dropped_lines, 1U);
    EXPECT_EQ(journal.recovery().dropped_bytes, torn.size());
    EXPECT_EQ(fs::file_size(path), intact_size);  // cut off the file, not only skipped
    EXPECT_EQ(journal.next_seq(), 4U);
    AppendRecords(journal, 2);
  }
  JournalRecovery recovery;
  ExpectRecords(OpenAndRead(path, &recovery), 5);
  EXPECT_EQ(recovery.dropped_lines, 0U);
}

TEST(Journal, DropsADamagedLastLineEvenWithItsNewline) {
  const ScopedDir dir;
  const fs::path path = dir.path / "mission.jsonl";
  {
    Journal journal = Journal::Open(path, [](const JournalRecord&) {});
    AppendRecords(journal, 4);
  }
  std::string bytes = ReadFile(path);
  const std::size_t last_line = bytes.rfind('\n', bytes.size() - 2) + 1;
  bytes[last_line + 10] ^= 0x20;
  WriteFile(path, bytes);
  JournalRecovery recovery;
  ExpectRecords(OpenAndRead(path, &recovery), 3);
  EXPECT_EQ(recovery.dropped_lines, 1U);
  EXPECT_EQ(recovery.dropped_bytes, bytes.size() - last_line);
}

TEST(Journal, DropsZerosLeftByAPowerCutAtTheEnd) {
  const ScopedDir dir;
  const fs::path path = dir.path / "mission.jsonl";
  {
    Journal journal = Journal::Open(path, [](const JournalRecord&) {});
    AppendRecords(journal, 2);
  }
  AppendToFile(path, std::string(4096, '\0'));
  JournalRecovery recovery;
  ExpectRecords(OpenAndRead(path, &recovery), 2);
  EXPECT_EQ(recovery.dropped_bytes, 4096U);
}

std::string OpenError(const fs::path& path) {
  try {
    OpenAndRead(path);
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "no exception";
}

TEST(Journal, RefusesCorruptionBeforeTheLastLineNamingFileAndLine) {
  const ScopedDir dir;
  const fs::path path = dir.path / "mission.jsonl";
  {
    Journal journal = Journal::Open(path, [](const JournalRecord&) {});
    AppendRecords(journal, 5);
  }
  const std::string intact = ReadFile(path);
  const std::size_t line_3 = [&] {
    std::size_t at = 0;
    for (int line = 1; line < 3; ++line) at = intact.find('\n', at) + 1;
    return at;
  }();
  std::string flipped = intact;
  flipped[line_3 + 20] = static_cast<char>(flipped[line_3 + 20] ^ 0x01);
  WriteFile(path, flipped);

  const std::string error = OpenError(path);
  EXPECT_THAT(error, HasSubstr(path.string()));
  EXPECT_THAT(error, HasSubstr("line 3"));
  EXPECT_THAT(error, HasSubstr("checksum"));
  EXPECT_EQ(ReadFile(path), flipped);  // refused, not repaired
}

TEST(Journal, RefusesAMissingRecordNamingTheLine) {
  const ScopedDir dir;
  const fs::path path = dir.path / "mission.jsonl";
  {
    Journal journal = Journal::Open(path, [](const JournalRecord&) {});
    AppendRecords(journal, 4);
  }
  // Delete line 2: every line is intact but seq jumps from 1 to 3.
  std::string bytes = ReadFile(path);
  const std::size_t line_2 = bytes.find('\n') + 1;
  bytes.erase(line_2, bytes.find('\n', line_2) + 1 - line_2);
  WriteFile(path, bytes);
  const std::string error = OpenError(path);
  EXPECT_THAT(error, HasSubstr("line 2"));
  EXPECT_THAT(error, HasSubstr("seq 3 where 2 was expected"));
}

// Issue 19: a corrupt middle line must not strand a mission: kKeepValidPrefix
// replays the records before it, moves the rest aside (named) and appends on.
TEST(Journal, RecoveringKeepsTheValidPrefixAndMovesTheRestAside) {
  const ScopedDir dir;
  const fs::path path = dir.path / "mission.jsonl";
  {
    Journal journal = Journal::Open(path, [](const JournalRecord&) {});
    AppendRecords(journal, 5);
  }
  std::string bytes = ReadFile(path);
  std::size_t line_3 = 0;
  for (int line = 1; line < 3; ++line) line_3 = bytes.find('\n', line_3) + 1;
  bytes[line_3 + 20] = static_cast<char>(bytes[line_3 + 20] ^ 0x01);
  WriteFile(path, bytes);
  EXPECT_THROW(OpenAndRead(path), JournalCorruptError);
  WriteFile(dir.path / "mission.jsonl.corrupt", "an earlier recovery's\n");

  std::vector<JournalRecord> records;
  {
    Journal journal =
        Journal::Open(path, [&](const JournalRecord& r) { records.push_back(r); },
                      JournalSync::kEveryAppend, JournalCorruption::kKeepValidPrefix);
    ExpectRecords(records, 2);
    const JournalRecovery& recovery = journal.recovery();
    EXPECT_EQ(recovery.records, 2U);
    EXPECT_EQ(recovery.dropped_lines, 3U);
    EXPECT_EQ(recovery.dropped_bytes, bytes.size() - line_3);
    EXPECT_EQ(recovery.moved_aside, dir.path / "mission.jsonl.corrupt.2");
    EXPECT_THAT(recovery.corruption, HasSubstr("line 3"));
    EXPECT_EQ(ReadFile(recovery.moved_aside), bytes.substr(line_3));
    EXPECT_EQ(journal.next_seq(), 3U);
    AppendRecords(journal, 3);
  }
  ExpectRecords(OpenAndRead(path), 5);
  EXPECT_EQ(ReadFile(dir.path / "mission.jsonl.corrupt"), "an earlier recovery's\n");
}

TEST(Journal, RefusesASecondWriterOnTheSameFile) {
  const ScopedDir dir;
  const fs::path path = dir.path / "mission.jsonl";
  Journal first = Journal::Open(path, [](const JournalRecord&) {});
  EXPECT_THAT(OpenError(path), HasSubstr("in use by another process"));
  first.Append(1.0, "k", {});
  Journal moved = std::move(first);  // the lock moves with the descriptor
  EXPECT_THAT(OpenError(path), HasSubstr("in use by another process"));
}

// A write cut short (here by the file size limit, as a full disk would) must not
// leave a partial line that later records would follow.
TEST(Journal, AFailedAppendLeavesNoPartialLine) {
  const ScopedDir dir;
  const fs::path path = dir.path / "mission.jsonl";
  {
    Journal journal = Journal::Open(path, [](const JournalRecord&) {});
    AppendRecords(journal, 2);
    const auto size_before = fs::file_size(path);

    rlimit original{};
    ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &original), 0);
    rlimit limited = original;
    limited.rlim_cur = static_cast<rlim_t>(size_before) + 100;  // part of the next line fits
    const sighandler_t previous = ::signal(SIGXFSZ, SIG_IGN);   // EFBIG instead of a signal
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &limited), 0);
    std::string error;
    try {
      journal.Append(99.0, "fire_track", DataOf(96));  // 5.8 kB: beyond the limit
    } catch (const std::runtime_error& failure) {
      error = failure.what();
    }
    ::setrlimit(RLIMIT_FSIZE, &original);
    ::signal(SIGXFSZ, previous);

    EXPECT_THAT(error, HasSubstr(path.string()));
    EXPECT_EQ(fs::file_size(path), size_before);
    EXPECT_EQ(journal.next_seq(), 3U);
    AppendRecords(journal, 2);
  }
  JournalRecovery recovery;
  ExpectRecords(OpenAndRead(path, &recovery), 4);
  EXPECT_EQ(recovery.dropped_lines, 0U);
}

TEST(Journal, SyncFlushesUnderOnSyncPolicy) {
  const ScopedDir dir;
  const fs::path path = dir.path / "mission.jsonl";
  {
    Journal journal = Journal::Open(
        path, [](const JournalRecord&) {}, JournalSync::kOnSync);
    AppendRecords(journal, 3);
    journal.Sync();
  }
  ExpectRecords(OpenAndRead(path), 3);
}

// Reads exactly `size` bytes unless the writer is gone first.
bool ReadExactly(int fd, void* buffer, std::size_t size) {
  auto* bytes = static_cast<char*>(buffer);
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::read(fd, bytes + done, size - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

// The child: appends in a loop and reports each seq once Append has returned.
// Never returns; no gtest macros (they belong to the parent).
[[noreturn]] void AppendUntilKilled(const fs::path& path, JournalSync sync, int ack_fd) {
  try {
    Journal journal = Journal::Open(
        path, [](const JournalRecord&) {}, sync);
    for (;;) {
      const std::uint64_t seq = journal.next_seq();
      journal.Append(0.5 * static_cast<double>(seq), "fire_track", DataOf(seq));
      std::size_t sent = 0;
      while (sent < sizeof seq) {
        const ssize_t n =
            ::write(ack_fd, reinterpret_cast<const char*>(&seq) + sent, sizeof seq - sent);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) ::_exit(3);
        sent += static_cast<std::size_t>(n);
      }
    }
  } catch (...) {
    ::_exit(2);
  }
}

class JournalKill : public ::testing::TestWithParam<JournalSync> {};

// "A server killed mid-mission loses none": every record whose Append returned
// before SIGKILL is in the journal, intact, and at most the one in flight follows.
TEST_P(JournalKill, SigkillLosesNoAcknowledgedRecord) {
  constexpr std::uint64_t kAcksBeforeKill = 200;
  const ScopedDir dir;
  const fs::path path = dir.path / "mission.jsonl";
  int pipe_fds[2];
  ASSERT_EQ(::pipe(pipe_fds), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::close(pipe_fds[0]);
    AppendUntilKilled(path, GetParam(), pipe_fds[1]);
  }
  ::close(pipe_fds[1]);

  std::uint64_t acknowledged = 0;
  std::uint64_t seq = 0;
  while (acknowledged < kAcksBeforeKill && ReadExactly(pipe_fds[0], &seq, sizeof seq)) {
    EXPECT_EQ(seq, acknowledged + 1);
    acknowledged = seq;
  }
  ASSERT_EQ(::kill(child, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL)
      << "child ended on its own, status " << status << " after " << acknowledged << " records";
  // Acknowledgements sent between our last read and the kill count too.
  while (ReadExactly(pipe_fds[0], &seq, sizeof seq)) acknowledged = seq;
  ::close(pipe_fds[0]);
  ASSERT_GE(acknowledged, kAcksBeforeKill);

  JournalRecovery recovery;
  const std::vector<JournalRecord> records = OpenAndRead(path, &recovery);
  ASSERT_GE(records.size(), acknowledged);
  ASSERT_LE(records.size(), acknowledged + 1);
  ExpectRecords(records, records.size());
  // And the journal goes on from there.
  {
    Journal journal = Journal::Open(path, [](const JournalRecord&) {});
    EXPECT_EQ(journal.recovery().dropped_lines, 0U);
    AppendRecords(journal, 3);
  }
  ExpectRecords(OpenAndRead(path), records.size() + 3);
}

INSTANTIATE_TEST_SUITE_P(Journal, JournalKill,
                         ::testing::Values(JournalSync::kEveryAppend, JournalSync::kOnSync),
                         [](const ::testing::TestParamInfo<JournalSync>& param_info) {
                           return param_info.param == JournalSync::kEveryAppend ? "EveryAppend"
                                                                                : "OnSync";
                         });

}  // namespace
}  // namespace fireswarm::server

namespace fireswarm::server {
namespace {

// `body` (a line up to its data, without the closing brace) as a committed line
// with its checksum, as Append writes it.
std::string CommittedLine(const std::string& body) {
  boost::crc_32_type crc;
  crc.process_bytes(body.data(), body.size());
  std::ostringstream hex;
  hex << std::hex << std::setw(8) << std::setfill('0') << crc.checksum();
  return body + ",\"crc\":\"" + hex.str() + "\"}\n";
}

TEST(JournalVersion, EveryLineCarriesTheFormatVersion) {
  const ScopedDir dir;
  const fs::path path = dir.path / "mission.jsonl";
  {
    Journal journal = Journal::Open(path, [](const JournalRecord&) {});
    journal.Append(1.0, "vehicle", {{"id", 1}});
  }
  EXPECT_THAT(ReadFile(path), HasSubstr("{\"seq\":1,\"v\":1,\"t\":1.0,"));
  const std::vector<JournalRecord> records = OpenAndRead(path);
  ASSERT_THAT(records, SizeIs(1));
  EXPECT_EQ(records[0].version, kJournalVersion);
}

TEST(JournalVersion, ALineWithoutAVersionIsReadAsTheFormatBeforeVersions) {
  const ScopedDir dir;
  const fs::path path = dir.path / "mission.jsonl";
  WriteFile(path, CommittedLine(R"({"seq":1,"t":0.5,"kind":"vehicle","data":{"id":1})") +
                      CommittedLine(R"({"seq":2,"t":0.5,"kind":"vehicle","data":{"id":2})"));
  const std::vector<JournalRecord> records = OpenAndRead(path);
  ASSERT_THAT(records, SizeIs(2));
  EXPECT_EQ(records[1].version, 0U);
  EXPECT_EQ(records[1].data, nlohmann::json({{"id", 2}}));
  // Appended after them, a record carries the version again.
  {
    Journal journal = Journal::Open(path, [](const JournalRecord&) {});
    journal.Append(1.0, "vehicle", {{"id", 3}});
  }
  EXPECT_EQ(OpenAndRead(path).back().version, kJournalVersion);
}

TEST(JournalVersion, RefusesANewerFormatNamingTheLineEvenAsTheLast) {
  const ScopedDir dir;
  const fs::path path = dir.path / "mission.jsonl";
  const std::string newer = CommittedLine(R"({"seq":2,"v":99,"t":0.5,"kind":"x","data":{})");
  WriteFile(path, CommittedLine(R"({"seq":1,"v":1,"t":0.5,"kind":"x","data":{})") + newer);
  const std::string error = OpenError(path);
  EXPECT_THAT(error, HasSubstr("line 2"));
  EXPECT_THAT(error, HasSubstr("format version 99 is newer than this build reads (1)"));
  WriteFile(path, CommittedLine(R"({"seq":1,"v":"one","t":0.5,"kind":"x","data":{})") + newer);
  EXPECT_THAT(OpenError(path), HasSubstr("line 1: v (format version) is not an unsigned"));
}

}  // namespace
}  // namespace fireswarm::server
