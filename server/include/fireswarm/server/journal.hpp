// The server's append-only journal: mission state and fire tracks are appended as
// they change, so a server killed and restarted mid-mission replays them and loses
// none.
//
// File format: JSON Lines, one record per line, each line one JSON object
//   {"seq":12,"v":1,"t":431.25,"kind":"fire_track","data":{...},"crc":"89abcdef"}
// seq counts records 1, 2, 3, ... in file order; v is the format version
// (kJournalVersion; a line without it is version 0, the format before versions,
// which had the same fields and data); t is the mission clock (seconds);
// kind names the writer's event ("mission_state", "fire_track", ...) and data is
// any JSON value the writer chose. crc is the CRC-32 (IEEE 802.3, as zlib and
// PNG), in 8 lower-case hex digits, of the line's bytes before `,"crc":"`; the
// line ends right after the crc's closing `}` with one '\n'. Every line is plain
// JSON, so jq and other JSON Lines tools read the journal as it is.
//
// A record is committed when its '\n' is in the file. Each Append writes its line
// with one write(2), so a process killed mid-append leaves at most one torn line,
// the last; Open drops it. A bad line anywhere else is corruption and Open refuses
// the file rather than silently losing what follows, unless asked to recover
// (JournalCorruption::kKeepValidPrefix): then the records before the bad line
// are kept and everything from it on is moved aside to a file of its own.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>

namespace fireswarm::server {

/// The format version Append writes; Open reads it and every version below.
inline constexpr std::uint32_t kJournalVersion = 1;

/// One journal record as written by Append and replayed by Open.
struct JournalRecord {
  std::uint64_t seq = 0;  ///< position in the journal, 1 for the first record
  double t_s = 0.0;       ///< mission clock when appended, seconds
  std::string kind;       ///< the writer's event name, never empty
  nlohmann::json data;    ///< the writer's payload
  /// Format version of its line: 0 for a line written before versions existed.
  std::uint32_t version = kJournalVersion;
  friend bool operator==(const JournalRecord&, const JournalRecord&) = default;
};

/// When appended records reach the disk.
enum class JournalSync : std::uint8_t {
  /// Every Append ends with fdatasync(2): once it returns, the record survives a
  /// process kill and a power cut. Costs a disk flush (milliseconds on disks, less
  /// on SSDs) per record; the default, sized for mission events, not telemetry.
  kEveryAppend,
  /// Append only write(2)s: once it returns the record is in the kernel and
  /// survives the process being killed (even SIGKILL), but a power cut or kernel
  /// crash may lose records appended since the last Sync().
  kOnSync,
};

/// What Open does with a bad line before the last (the last may always be torn).
enum class JournalCorruption {
  /// Throw JournalCorruptError: nothing is replayed and the file is left as it is.
  kRefuse,
  /// Keep the records before the bad line; move the bad line and every line
  /// after it to JournalRecovery::moved_aside, then cut them off the journal.
  kKeepValidPrefix,
};

/// Thrown by Journal::Open for a bad line before the last under
/// JournalCorruption::kRefuse. The message names the file and the 1-based line.
class JournalCorruptError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// What Open found in an existing file.
struct JournalRecovery {
  std::uint64_t records = 0;  ///< intact records replayed
  /// Lines cut off the file: 1 for a torn or corrupt last line (a kill
  /// mid-append, or a power cut under JournalSync::kOnSync); under
  /// kKeepValidPrefix the bad line and every line after it. Else 0.
  std::uint64_t dropped_lines = 0;
  std::uint64_t dropped_bytes = 0;  ///< bytes cut off with them
  /// Under kKeepValidPrefix, where the lines cut off after a corrupt line went
  /// (`<journal>.corrupt`, or `.corrupt.2`, ... when taken); empty otherwise.
  std::filesystem::path moved_aside;
  /// Why the first dropped line was bad, with its 1-based line number (kKeepValidPrefix).
  std::string corruption;
};

/// An open journal file, positioned for appending. Owns the file descriptor and an
/// exclusive flock(2) on it, so a second server on the same journal is refused.
/// Movable, not copyable, not thread-safe.
class Journal {
 public:
  using Visitor = std::function<void(const JournalRecord&)>;

  /// Opens `path`, creating it (and flushing its directory so the new name
  /// survives a power cut) when missing. Every intact record is passed to `visit`
  /// in file order before Open returns. A torn or corrupt last line is cut off the
  /// file and reported in recovery(). Throws std::runtime_error naming the file
  /// (and the 1-based line for corruption) when the file cannot be opened, read or
  /// locked (another process holds it), or any line has a format version above
  /// kJournalVersion; JournalCorruptError when a line other than the last is not
  /// a valid record (bad checksum, bad JSON, missing field, seq not one more than
  /// the line before) and `corruption` is kRefuse (kKeepValidPrefix: see
  /// JournalRecovery). Exceptions thrown by `visit` propagate.
  static Journal Open(const std::filesystem::path& path, const Visitor& visit,
                      JournalSync sync = JournalSync::kEveryAppend,
                      JournalCorruption corruption = JournalCorruption::kRefuse);

  Journal(Journal&& other) noexcept;
  Journal& operator=(Journal&& other) noexcept;
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;
  ~Journal();

  /// Appends one record at mission time `t_s` (seconds) and returns its seq. With
  /// JournalSync::kEveryAppend the record is on disk when this returns; with
  /// kOnSync it is in the kernel (see JournalSync). Throws std::invalid_argument
  /// (writing nothing) when `kind` is empty, `t_s` is not finite or `data` cannot
  /// be serialised (invalid UTF-8); std::runtime_error naming the file when the
  /// write or flush fails, after cutting any partial line back off, so the file
  /// stays valid. After a failure that could not be cut back every later Append
  /// throws.
  std::uint64_t Append(double t_s, std::string_view kind, const nlohmann::json& data);

  /// Flushes appended records to the disk (fdatasync). Throws std::runtime_error
  /// naming the file on failure. Cheap under kEveryAppend: nothing is left to flush.
  void Sync();

  /// seq the next Append will get.
  std::uint64_t next_seq() const { return next_seq_; }
  const JournalRecovery& recovery() const { return recovery_; }
  const std::filesystem::path& path() const { return path_; }

 private:
  Journal(std::filesystem::path path, int fd, JournalSync sync);
  void Close() noexcept;

  std::filesystem::path path_;
  int fd_ = -1;
  JournalSync sync_ = JournalSync::kEveryAppend;
  std::uint64_t next_seq_ = 1;
  std::uint64_t end_offset_ = 0;  // bytes: the end of the last committed record
  bool broken_ = false;           // a failed append left bytes that could not be cut off
  JournalRecovery recovery_;
};

}  // namespace fireswarm::server
