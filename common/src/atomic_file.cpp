#include "fireswarm/common/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

namespace fireswarm::common {

void WriteFileAtomically(const std::filesystem::path& path, std::string_view text, mode_t mode) {
  // Same directory, so the rename is atomic; per process, so two writers of one
  // file do not share a temporary.
  std::filesystem::path temporary = path;
  temporary += ".partial." + std::to_string(::getpid());
  const auto fail = [&](const std::string& step) {
    const std::string message = path.string() + ": " + step + ": " + std::strerror(errno);
    ::unlink(temporary.c_str());
    throw std::runtime_error(message);
  };
  // A temporary left by a crashed process of the same ID may have other
  // permissions: remove it, and create ours fresh (O_EXCL) so `mode` holds.
  ::unlink(temporary.c_str());
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, mode);
  if (fd < 0) fail("cannot create " + temporary.string());
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ::close(fd);
      fail("cannot write " + temporary.string());
    }
    written += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) {
    ::close(fd);
    fail("cannot flush " + temporary.string());
  }
  if (::close(fd) != 0) fail("cannot close " + temporary.string());
  if (std::rename(temporary.c_str(), path.c_str()) != 0) fail("cannot rename into place");
  // The data is safe; a directory that cannot be flushed only risks the rename.
  const std::filesystem::path directory =
      path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  const int dir_fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd >= 0) {
    ::fsync(dir_fd);
    ::close(dir_fd);
  }
}

}  // namespace fireswarm::common
