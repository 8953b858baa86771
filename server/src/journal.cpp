#include "fireswarm/server/journal.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <boost/crc.hpp>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "fireswarm/common/atomic_file.hpp"

namespace fireswarm::server {
namespace {

// The line's tail after the checksummed body: ,"crc":"89abcdef"}
constexpr std::string_view kCrcKey = ",\"crc\":\"";
constexpr std::string_view kCrcEnd = "\"}";
constexpr std::size_t kCrcHexDigits = 8;
constexpr std::size_t kCrcTailSize = kCrcKey.size() + kCrcHexDigits + kCrcEnd.size();
constexpr std::string_view kHexDigits = "0123456789abcdef";
constexpr std::size_t kReadChunkBytes = 1 << 16;

std::uint32_t Crc32(std::string_view bytes) {
  boost::crc_32_type crc;
  crc.process_bytes(bytes.data(), bytes.size());
  return static_cast<std::uint32_t>(crc.checksum());
}

std::string Hex8(std::uint32_t value) {
  std::string out(kCrcHexDigits, '0');
  for (std::size_t i = kCrcHexDigits; i-- > 0; value >>= 4U) out[i] = kHexDigits[value & 0xFU];
  return out;
}

std::optional<std::uint32_t> ParseHex8(std::string_view text) {
  if (text.size() != kCrcHexDigits) return std::nullopt;
  std::uint32_t value = 0;
  for (const char c : text) {
    const std::size_t digit = kHexDigits.find(c);
    if (digit == std::string_view::npos) return std::nullopt;
    value = (value << 4U) | static_cast<std::uint32_t>(digit);
  }
  return value;
}

std::string SystemError(const std::filesystem::path& path, std::string_view step, int error) {
  return path.string() + ": " + std::string(step) + ": " + std::strerror(error);
}

// One record as one line, '\n' included. Throws nlohmann::json::exception when the
// kind or data hold invalid UTF-8.
std::string EncodeLine(std::uint64_t seq, double t_s, std::string_view kind,
                       const nlohmann::json& data) {
  std::string line = "{\"seq\":" + std::to_string(seq) +
                     ",\"v\":" + std::to_string(kJournalVersion) +
                     ",\"t\":" + nlohmann::json(t_s).dump() +
                     ",\"kind\":" + nlohmann::json(kind).dump() + ",\"data\":" + data.dump();
  const std::uint32_t crc = Crc32(line);
  line += kCrcKey;
  line += Hex8(crc);
  line += kCrcEnd;
  line += '\n';
  return line;
}

// Decodes one line ('\n' excluded). Returns the record, or nullopt with `why` set.
std::optional<JournalRecord> DecodeLine(std::string_view line, std::string& why) {
  if (line.size() <= kCrcTailSize || !line.ends_with(kCrcEnd) ||
      line.substr(line.size() - kCrcTailSize, kCrcKey.size()) != kCrcKey) {
    why = "no checksum at the end of the line";
    return std::nullopt;
  }
  const std::string_view body = line.substr(0, line.size() - kCrcTailSize);
  const std::optional<std::uint32_t> crc =
      ParseHex8(line.substr(line.size() - kCrcHexDigits - kCrcEnd.size(), kCrcHexDigits));
  if (!crc || *crc != Crc32(body)) {
    why = "checksum mismatch";
    return std::nullopt;
  }
  // The checksum matched, so these bytes are what Append wrote; what follows only
  // guards against a file written by something else.
  const nlohmann::json object =
      nlohmann::json::parse(std::string(body) + "}", nullptr, /*allow_exceptions=*/false);
  if (object.is_discarded() || !object.is_object()) {
    why = "not a JSON object";
    return std::nullopt;
  }
  const auto seq = object.find("seq");
  const auto t = object.find("t");
  const auto kind = object.find("kind");
  const auto data = object.find("data");
  if (seq == object.end() || !seq->is_number_unsigned() || t == object.end() || !t->is_number() ||
      kind == object.end() || !kind->is_string() || kind->get_ref<const std::string&>().empty() ||
      data == object.end()) {
    why = "a field of seq (unsigned), t (number), kind (non-empty string), data is missing";
    return std::nullopt;
  }
  const auto version = object.find("v");
  if (version != object.end() &&
      (!version->is_number_unsigned() ||
       version->get<std::uint64_t>() > std::numeric_limits<std::uint32_t>::max())) {
    why = "v (format version) is not an unsigned 32-bit number";
    return std::nullopt;
  }
  JournalRecord record;
  record.seq = seq->get<std::uint64_t>();
  // No version: a line of the format before versions (0), read as it was.
  record.version = version == object.end() ? 0 : version->get<std::uint32_t>();
  record.t_s = t->get<double>();
  record.kind = kind->get<std::string>();
  record.data = *data;
  return record;
}

std::string ReadAll(const std::filesystem::path& path, int fd) {
  std::string bytes;
  std::vector<char> chunk(kReadChunkBytes);
  for (;;) {
    const ssize_t n = ::read(fd, chunk.data(), chunk.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw std::runtime_error(SystemError(path, "cannot read journal", errno));
    if (n == 0) return bytes;
    bytes.append(chunk.data(), static_cast<std::size_t>(n));
  }
}

// The intact records of `bytes`, and the end of the last one. A bad last line is
// left out (the caller cuts it off); a bad line before it throws.
struct Replay {
  std::vector<JournalRecord> records;
  std::size_t valid_end = 0;
  std::string corruption;  // set when a bad line before the last ended the replay (recovering)
};

Replay Parse(const std::filesystem::path& path, const std::string& bytes, bool keep_valid_prefix) {
  Replay replay;
  std::size_t begin = 0;
  for (std::uint64_t line_number = 1; begin < bytes.size(); ++line_number) {
    const std::size_t newline = bytes.find('\n', begin);
    // No '\n': the append was cut short; its record was never committed.
    if (newline == std::string::npos) break;
    const bool last = newline + 1 == bytes.size();
    std::string why;
    std::optional<JournalRecord> record =
        DecodeLine(std::string_view(bytes).substr(begin, newline - begin), why);
    if (!record && last) break;  // torn or damaged in its last write: drop it
    bool corrupt = false;
    const auto fail = [&](const std::string& reason) {
      if (keep_valid_prefix) {
        replay.corruption = "line " + std::to_string(line_number) + ": " + reason;
        corrupt = true;
        return;
      }
      throw JournalCorruptError(path.string() + ": line " + std::to_string(line_number) + ": " +
                                reason + " (journal corrupt before its last line)");
    };
    if (!record) fail(why);
    if (corrupt) break;
    // A checksummed line of a newer format was not torn either: refused wherever it is.
    if (record->version > kJournalVersion) {
      throw std::runtime_error(path.string() + ": line " + std::to_string(line_number) +
                               ": format version " + std::to_string(record->version) +
                               " is newer than this build reads (" +
                               std::to_string(kJournalVersion) + ")");
    }
    // A checksummed line with the wrong seq was not torn: lines were lost or files
    // mixed, which dropping it would hide, wherever it is.
    const std::uint64_t expected = replay.records.empty() ? 1 : replay.records.back().seq + 1;
    if (record->seq != expected) {
      fail("seq " + std::to_string(record->seq) + " where " + std::to_string(expected) +
           " was expected");
      break;
    }
    replay.records.push_back(std::move(*record));
    begin = newline + 1;
    replay.valid_end = begin;
  }
  return replay;
}

// Where the lines after a corrupt one go: `<journal>.corrupt`, or the first of
// `.corrupt.2`, `.corrupt.3`, ... not taken (an earlier recovery's stays).
std::filesystem::path AsideName(const std::filesystem::path& journal) {
  std::filesystem::path aside = journal;
  aside += ".corrupt";
  std::error_code ignored;
  for (int n = 2; std::filesystem::exists(std::filesystem::symlink_status(aside, ignored)); ++n) {
    aside = journal;
    aside += ".corrupt." + std::to_string(n);
  }
  return aside;
}

// Makes a newly created file's name survive a power cut.
void SyncDirectoryOf(const std::filesystem::path& path) {
  const std::filesystem::path directory =
      path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  const int fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error(SystemError(directory, "cannot open directory", errno));
  const int result = ::fsync(fd);
  const int error = errno;
  ::close(fd);
  if (result != 0)
    throw std::runtime_error(SystemError(directory, "cannot flush directory", error));
}

}  // namespace

Journal::Journal(std::filesystem::path path, int fd, JournalSync sync)
    : path_(std::move(path)), fd_(fd), sync_(sync) {}

Journal::Journal(Journal&& other) noexcept
    : path_(std::move(other.path_)),
      fd_(std::exchange(other.fd_, -1)),
      sync_(other.sync_),
      next_seq_(other.next_seq_),
      end_offset_(other.end_offset_),
      broken_(other.broken_),
      recovery_(std::move(other.recovery_)) {}

Journal& Journal::operator=(Journal&& other) noexcept {
  if (this != &other) {
    Close();
    path_ = std::move(other.path_);
    fd_ = std::exchange(other.fd_, -1);
    sync_ = other.sync_;
    next_seq_ = other.next_seq_;
    end_offset_ = other.end_offset_;
    broken_ = other.broken_;
    recovery_ = std::move(other.recovery_);
  }
  return *this;
}

Journal::~Journal() {
  Close();
}

void Journal::Close() noexcept {
  // Closing releases the flock.
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

Journal Journal::Open(const std::filesystem::path& path, const Visitor& visit, JournalSync sync,
                      JournalCorruption corruption) {
  std::error_code ignored;
  const bool created = !std::filesystem::exists(path, ignored);
  // O_APPEND: every write lands at the end, even after a truncation.
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error(SystemError(path, "cannot open journal", errno));
  Journal journal(path, fd, sync);  // owns fd from here: closed on any throw
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    if (errno == EWOULDBLOCK) {
      throw std::runtime_error(path.string() + ": journal is in use by another process");
    }
    throw std::runtime_error(SystemError(path, "cannot lock journal", errno));
  }
  if (created) SyncDirectoryOf(path);

  const std::string bytes = ReadAll(path, fd);
  Replay replay = Parse(path, bytes, corruption == JournalCorruption::kKeepValidPrefix);
  if (!replay.corruption.empty()) {
    // The lines from the corrupt one on are kept, beside the journal, before
    // they are cut off it: an operator may still want to read them.
    const std::string_view rest = std::string_view(bytes).substr(replay.valid_end);
    journal.recovery_.moved_aside = AsideName(path);
    common::WriteFileAtomically(journal.recovery_.moved_aside, rest);
    journal.recovery_.corruption = replay.corruption;
    journal.recovery_.dropped_lines =
        static_cast<std::uint64_t>(std::count(rest.begin(), rest.end(), '\n')) +
        (rest.empty() || rest.back() == '\n' ? 0U : 1U);
  }
  if (replay.valid_end < bytes.size()) {
    if (::ftruncate(fd, static_cast<off_t>(replay.valid_end)) != 0 || ::fdatasync(fd) != 0) {
      throw std::runtime_error(SystemError(path, "cannot cut off the torn last line", errno));
    }
    if (replay.corruption.empty()) journal.recovery_.dropped_lines = 1;
    journal.recovery_.dropped_bytes = bytes.size() - replay.valid_end;
  }
  journal.recovery_.records = replay.records.size();
  journal.end_offset_ = replay.valid_end;
  journal.next_seq_ = replay.records.empty() ? 1 : replay.records.back().seq + 1;
  for (const JournalRecord& record : replay.records) visit(record);
  return journal;
}

std::uint64_t Journal::Append(double t_s, std::string_view kind, const nlohmann::json& data) {
  if (kind.empty()) throw std::invalid_argument(path_.string() + ": journal record kind is empty");
  if (!std::isfinite(t_s)) {
    throw std::invalid_argument(path_.string() + ": journal record time is not finite");
  }
  std::string line;
  try {
    line = EncodeLine(next_seq_, t_s, kind, data);
  } catch (const nlohmann::json::exception& error) {
    throw std::invalid_argument(path_.string() + ": journal record of kind '" + std::string(kind) +
                                "' cannot be written: " + error.what());
  }
  if (broken_ || fd_ < 0) {
    throw std::runtime_error(path_.string() +
                             ": journal unusable after a failed append that could not be undone");
  }
  // Undo a partial line so later records do not follow a torn one (which the next
  // Open would take for corruption), then report the failure.
  const auto fail = [&](std::string_view step, int error) {
    if (::ftruncate(fd_, static_cast<off_t>(end_offset_)) != 0) broken_ = true;
    throw std::runtime_error(SystemError(path_, step, error));
  };
  std::size_t written = 0;
  while (written < line.size()) {
    // One call writes the whole line unless the disk fills or a signal cuts it short.
    const ssize_t n = ::write(fd_, line.data() + written, line.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail("cannot append to journal", errno);
    if (n == 0) fail("cannot append to journal", ENOSPC);
    written += static_cast<std::size_t>(n);
  }
  // After a failed flush Linux may drop the dirty pages: the record's fate is
  // unknown, so it is cut back off and reported as not written.
  if (sync_ == JournalSync::kEveryAppend && ::fdatasync(fd_) != 0) {
    fail("cannot flush journal", errno);
  }
  end_offset_ += line.size();
  return next_seq_++;
}

void Journal::Sync() {
  if (fd_ < 0) throw std::runtime_error(path_.string() + ": journal is closed");
  if (::fdatasync(fd_) != 0)
    throw std::runtime_error(SystemError(path_, "cannot flush journal", errno));
}

}  // namespace fireswarm::server
