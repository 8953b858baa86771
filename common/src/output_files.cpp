#include "fireswarm/common/output_files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <set>
#include <stdexcept>
#include <system_error>

namespace fireswarm::common {
namespace {

namespace fs = std::filesystem;

fs::path DirectoryOf(const fs::path& target) {
  return target.has_parent_path() ? target.parent_path() : fs::path(".");
}

std::string KindOf(fs::file_type type) {
  switch (type) {
    case fs::file_type::directory:
      return "a directory";
    case fs::file_type::symlink:
      return "a symbolic link";
    case fs::file_type::fifo:
      return "a fifo";
    case fs::file_type::block:
    case fs::file_type::character:
      return "a device";
    case fs::file_type::socket:
      return "a socket";
    default:
      return "not a regular file";
  }
}

[[noreturn]] void Fail(const fs::path& target, const std::string& problem) {
  throw std::runtime_error(target.string() + ": " + problem);
}

void WriteAll(const fs::path& target, const fs::path& temporary, std::string_view text,
              mode_t mode) {
  const auto fail = [&](const std::string& step) {
    const std::string reason = std::strerror(errno);
    ::unlink(temporary.c_str());
    Fail(target, step + " " + temporary.string() + ": " + reason);
  };
  // O_EXCL: a temporary left by a crashed process of the same ID was removed by
  // Add(); ours is created fresh so `mode` holds from the first byte.
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, mode);
  if (fd < 0) fail("cannot create");
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ::close(fd);
      fail("cannot write");
    }
    written += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) {
    ::close(fd);
    fail("cannot flush");
  }
  if (::close(fd) != 0) fail("cannot close");
}

}  // namespace

std::optional<std::string> OutputPathProblem(const fs::path& target,
                                             const std::vector<fs::path>& inputs) {
  if (target.empty()) return "is an empty file name";
  const fs::path directory = DirectoryOf(target);
  std::error_code error;
  if (!fs::is_directory(directory, error)) {
    return "the directory " + directory.string() + " does not exist";
  }
  if (::access(directory.c_str(), W_OK | X_OK) != 0) {
    return "the directory " + directory.string() + " is not writable: " + std::strerror(errno);
  }
  const fs::file_status status = fs::symlink_status(target, error);
  if (status.type() == fs::file_type::not_found) return std::nullopt;
  if (error) return "cannot be examined: " + error.message();
  if (status.type() != fs::file_type::regular) {
    return "is " + KindOf(status.type()) + "; only a regular file may be replaced";
  }
  for (const fs::path& input : inputs) {
    if (input.empty()) continue;
    std::error_code same_error;
    if (fs::equivalent(target, input, same_error)) {
      return "is the input " + input.string() + "; it would be overwritten";
    }
  }
  return std::nullopt;
}

OutputFiles::~OutputFiles() {
  for (const Entry& entry : entries_) ::unlink(entry.temporary.c_str());
}

fs::path OutputFiles::Add(const fs::path& target) {
  if (const auto problem = OutputPathProblem(target)) Fail(target, *problem);
  for (const Entry& entry : entries_) {
    std::error_code error;
    if (entry.target == target || fs::equivalent(entry.target, target, error)) {
      Fail(target, "is named twice as an output");
    }
  }
  // Same directory, so the rename is atomic; per process, so two writers of one
  // file do not share a temporary.
  fs::path temporary = target;
  temporary += ".partial." + std::to_string(::getpid());
  ::unlink(temporary.c_str());
  entries_.push_back({target, temporary});
  return temporary;
}

void OutputFiles::Stage(const fs::path& target, std::string_view text, mode_t mode) {
  const fs::path temporary = Add(target);
  try {
    WriteAll(target, temporary, text, mode);
  } catch (...) {
    entries_.pop_back();
    throw;
  }
}

fs::path OutputFiles::Reserve(const fs::path& target) { return Add(target); }

void OutputFiles::Commit() {
  std::set<fs::path> directories;
  while (!entries_.empty()) {
    const Entry entry = entries_.front();
    if (std::rename(entry.temporary.c_str(), entry.target.c_str()) != 0) {
      const std::string reason = std::strerror(errno);
      Fail(entry.target, "cannot rename " + entry.temporary.string() + " into place: " + reason);
    }
    entries_.erase(entries_.begin());
    directories.insert(DirectoryOf(entry.target));
  }
  // The data is safe; a directory that cannot be flushed only risks the renames.
  for (const fs::path& directory : directories) {
    const int fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd >= 0) {
      ::fsync(fd);
      ::close(fd);
    }
  }
}

}  // namespace fireswarm::common
