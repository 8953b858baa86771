// A `fireswarm` child process for the end-to-end tests in tests/app/: its stdout
// read line by line with deadlines (poll()), never with sleeps; killed and reaped
// when the object goes. The binary comes from env FIRESWARM_BIN (ctest sets it).
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "app/run_fireswarm.hpp"

namespace fireswarm::app {

/// `fireswarm <args>` as a child process whose stdout the test reads line by line.
class FireswarmProcess {
 public:
  explicit FireswarmProcess(const std::vector<std::string>& args) {
    const char* binary = std::getenv("FIRESWARM_BIN");
    if (binary == nullptr) {
      ADD_FAILURE() << "FIRESWARM_BIN is not set (ctest sets it)";
      return;
    }
    int pipe_fds[2];
    if (::pipe2(pipe_fds, O_CLOEXEC) != 0) {
      ADD_FAILURE() << "pipe failed";
      return;
    }
    std::vector<std::string> argv_strings{binary};
    argv_strings.insert(argv_strings.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& arg : argv_strings) argv.push_back(arg.data());
    argv.push_back(nullptr);
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(pipe_fds[1], STDOUT_FILENO);
      ::close(pipe_fds[0]);
      ::close(pipe_fds[1]);
      ::execv(binary, argv.data());
      ::_exit(127);
    }
    ::close(pipe_fds[1]);
    stdout_ = pipe_fds[0];
    if (pid_ < 0) ADD_FAILURE() << "fork failed";
  }
  ~FireswarmProcess() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    if (stdout_ >= 0) ::close(stdout_);
  }
  FireswarmProcess(const FireswarmProcess&) = delete;
  FireswarmProcess& operator=(const FireswarmProcess&) = delete;

  /// The next stdout line, or nullopt at end of file or once `deadline` passed.
  std::optional<std::string> ReadLine(std::chrono::steady_clock::time_point deadline) {
    while (true) {
      const auto newline = buffer_.find('\n');
      if (newline != std::string::npos) {
        std::string line = buffer_.substr(0, newline);
        buffer_.erase(0, newline + 1);
        return line;
      }
      if (stdout_ < 0 || eof_) return std::nullopt;
      const auto left =
          std::chrono::ceil<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
      if (left.count() <= 0) return std::nullopt;
      pollfd readable{stdout_, POLLIN, 0};
      if (::poll(&readable, 1, static_cast<int>(left.count())) <= 0) continue;
      char chunk[256];
      const ssize_t got = ::read(stdout_, chunk, sizeof chunk);
      if (got <= 0) {
        eof_ = true;
      } else {
        buffer_.append(chunk, static_cast<std::size_t>(got));
      }
    }
  }

  /// Reads stdout up to the "http: listening on http://127.0.0.1:PORT/" line that
  /// --http prints once the page is served; its port, or nullopt if the line did not
  /// come before `deadline` (the lines before it are dropped).
  std::optional<std::uint16_t> ReadListeningPort(std::chrono::steady_clock::time_point deadline) {
    constexpr std::string_view kPrefix = "http: listening on http://127.0.0.1:";
    while (auto line = ReadLine(deadline)) {
      if (!line->starts_with(kPrefix) || !line->ends_with('/')) continue;
      const std::string digits = line->substr(kPrefix.size(), line->size() - kPrefix.size() - 1);
      if (digits.empty() || digits.size() > 5 ||
          digits.find_first_not_of("0123456789") != std::string::npos) {
        continue;
      }
      return static_cast<std::uint16_t>(std::stoi(digits));
    }
    return std::nullopt;
  }

  void Signal(int signal) const { ::kill(pid_, signal); }
  pid_t pid() const { return pid_; }

  /// Kills the process with SIGKILL and reaps it (no summary, nothing flushed).
  void Kill() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }

  /// Reads stdout to its end, then reaps the process. Returns its exit code (-1 if it
  /// did not exit normally or stdout stayed open past `deadline`) and its lines.
  RunResult Finish(std::chrono::steady_clock::time_point deadline) {
    RunResult result;
    while (auto line = ReadLine(deadline)) result.lines.push_back(*line);
    if (!eof_ || pid_ <= 0) return result;
    int status = 0;
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
  }

 private:
  pid_t pid_ = -1;
  int stdout_ = -1;
  std::string buffer_;
  bool eof_ = false;
};

}  // namespace fireswarm::app
