// Writing a file so that a crash or a concurrent reader never sees half of it.
// The one way fireswarm writes its output and state files (plans, QGC files,
// vehicle parameters).
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <string_view>

namespace fireswarm::common {

/// Writes `text` to `path` through a temporary sibling (same directory, named per
/// process), flushed to disk, renamed over `path`; then the directory is flushed
/// so the rename itself survives a power cut. A failure leaves the old file, if
/// any, and no temporary. The temporary is created with `mode` (before the
/// umask), so a secret is never readable by others, not even for a moment.
/// One file of OutputFiles (output_files.hpp): a target that is a symbolic
/// link, fifo, device or directory is refused, never replaced.
/// Throws std::runtime_error naming the path and the step that failed.
void WriteFileAtomically(const std::filesystem::path& path, std::string_view text,
                         mode_t mode = 0644);

}  // namespace fireswarm::common
