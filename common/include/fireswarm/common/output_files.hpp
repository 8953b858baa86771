// A command's output files, checked before any work and written all or none.
// The one way fireswarm writes its outputs (reports, maps, plans, logs):
//  1. CheckOutputPath() on every target before anything is read or computed;
//  2. OutputFiles::Stage() (text) or Reserve() (a writer of its own) puts each
//     output in a temporary beside its target;
//  3. OutputFiles::Commit() renames every temporary into place, or the
//     destructor removes them all when the work failed.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fireswarm::common {

/// Why `target` cannot be an output, or nullopt when it can: its directory must
/// exist and be writable; an existing target must be a regular file (not a
/// symbolic link, fifo, device, socket or directory) and must not be the same
/// file as any of `inputs` (std::filesystem::equivalent; inputs that do not
/// exist are skipped). The text names no path: the caller says which flag it is.
std::optional<std::string> OutputPathProblem(const std::filesystem::path& target,
                                             const std::vector<std::filesystem::path>& inputs = {});

/// Temporaries beside their targets, renamed into place together.
class OutputFiles {
 public:
  OutputFiles() = default;
  /// Removes every temporary not yet committed.
  ~OutputFiles();
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;

  /// Writes `text` to a fresh temporary beside `target`, created with `mode`
  /// (before the umask) and flushed to disk. Throws std::runtime_error naming
  /// the target when it fails OutputPathProblem() or the temporary cannot be
  /// written, or when `target` was already staged.
  void Stage(const std::filesystem::path& target, std::string_view text, mode_t mode = 0644);

  /// A temporary path beside `target` for a writer of its own (an LCM log), to
  /// be filled before Commit(). Same checks and throws as Stage().
  std::filesystem::path Reserve(const std::filesystem::path& target);

  /// Renames every temporary over its target and flushes the directories.
  /// Throws std::runtime_error naming the target whose rename failed; the
  /// temporaries not yet renamed are removed.
  void Commit();

 private:
  struct Entry {
    std::filesystem::path target;
    std::filesystem::path temporary;
  };
  std::filesystem::path Add(const std::filesystem::path& target);
  std::vector<Entry> entries_;
};

}  // namespace fireswarm::common
