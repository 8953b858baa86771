// The server's journal reader on any file contents, as `serve --journal` reads it:
// Journal::Open on a file holding the input, each record through JournalEntryOf,
// then Server::Restore. Properties: each step returns or throws
// std::runtime_error (Open's names the file); records come in seq order 1, 2, ...;
// at most the last line is dropped; nothing else escapes.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "fireswarm/server/journal.hpp"
#include "fireswarm/server/journal_format.hpp"
#include "fireswarm/server/server.hpp"
#include "fuzz_check.hpp"

namespace {

namespace server = fireswarm::server;
using fireswarm::fuzz::Check;

// One file per fuzzing process, rewritten for every input.
const std::filesystem::path& JournalPath() {
  static const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                            ("fireswarm_fuzz_journal_" +
                                             std::to_string(::getpid()) + ".jsonl");
  return path;
}

void RestoreFrom(const std::vector<server::JournalEntry>& entries) {
  static const fireswarm::common::LocalFrame frame(fireswarm::common::LatLon{46.5, 6.6});
  try {
    (void)server::Server::Restore(server::ServerConfig{}, frame, entries);
  } catch (const std::runtime_error&) {
    // A journal whose entries do not fit together: refused, as documented.
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path& path = JournalPath();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  std::vector<server::JournalEntry> entries;
  bool entries_ok = true;
  std::uint64_t expected_seq = 1;
  try {
    const server::Journal journal = server::Journal::Open(
        path,
        [&](const server::JournalRecord& record) {
          Check(record.seq == expected_seq++, "journal records out of seq order");
          if (!entries_ok) return;
          try {
            entries.push_back(server::JournalEntryOf(record));
          } catch (const std::runtime_error&) {
            entries_ok = false;  // `serve` refuses the journal; the reader survived
          }
        },
        server::JournalSync::kOnSync);
    Check(journal.recovery().dropped_lines <= 1, "more than the last line dropped");
    Check(journal.recovery().records == expected_seq - 1, "records miscounted");
  } catch (const std::runtime_error& error) {
    Check(std::string_view(error.what()).find(path.string()) != std::string_view::npos,
          "a journal error that does not name the file");
    entries_ok = false;
  }
  if (entries_ok && !entries.empty()) RestoreFrom(entries);
  std::filesystem::remove(path);
  return 0;
}
