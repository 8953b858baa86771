#include "child_pool.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/signalfd.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <map>
#include <stdexcept>

namespace fireswarm::app {
namespace {

using Clock = std::chrono::steady_clock;
constexpr std::chrono::milliseconds kTickPeriod{200};
/// What the child exits with when it cannot set itself up or exec (as a shell's 127).
constexpr int kExecFailed = 127;

struct Running {
  std::size_t job = 0;
  Clock::time_point start;
  std::optional<Clock::time_point> deadline;
  bool killed_for_time = false;
};

// The signals the loop takes through a signalfd instead of handlers: blocked for
// the pool's lifetime, the previous mask restored after.
class SignalFd {
 public:
  SignalFd() {
    sigemptyset(&set_);
    for (const int signal : {SIGCHLD, SIGINT, SIGTERM}) sigaddset(&set_, signal);
    if (::sigprocmask(SIG_BLOCK, &set_, &previous_) != 0) {
      throw std::runtime_error(std::string("sigprocmask: ") + std::strerror(errno));
    }
    fd_ = ::signalfd(-1, &set_, SFD_CLOEXEC | SFD_NONBLOCK);
    if (fd_ < 0) {
      ::sigprocmask(SIG_SETMASK, &previous_, nullptr);
      throw std::runtime_error(std::string("signalfd: ") + std::strerror(errno));
    }
  }
  ~SignalFd() {
    ::close(fd_);
    ::sigprocmask(SIG_SETMASK, &previous_, nullptr);
  }
  SignalFd(const SignalFd&) = delete;
  SignalFd& operator=(const SignalFd&) = delete;

  int fd() const { return fd_; }
  const sigset_t& previous() const { return previous_; }

  /// Drains the pending signals; true when SIGINT or SIGTERM was among them.
  bool DrainStop() const {
    bool stop = false;
    signalfd_siginfo info{};
    while (::read(fd_, &info, sizeof info) == static_cast<ssize_t>(sizeof info)) {
      if (info.ssi_signo == SIGINT || info.ssi_signo == SIGTERM) stop = true;
    }
    return stop;
  }

 private:
  sigset_t set_{};
  sigset_t previous_{};
  int fd_ = -1;
};

// Between fork and exec only async-signal-safe calls.
[[noreturn]] void BecomeChild(char* const* argv, const char* output, const sigset_t& mask,
                              pid_t parent) {
  ::setpgid(0, 0);
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(kExecFailed);  // the parent died before prctl
  const int out = ::open(output, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  const int null = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  if (out < 0 || null < 0) ::_exit(kExecFailed);
  ::dup2(null, STDIN_FILENO);
  ::dup2(out, STDOUT_FILENO);
  ::dup2(out, STDERR_FILENO);
  ::sigprocmask(SIG_SETMASK, &mask, nullptr);
  ::execv(argv[0], argv);
  ::_exit(kExecFailed);
}

pid_t Start(const ChildJob& job, const sigset_t& mask) {
  std::vector<std::string> strings = job.argv;
  std::vector<char*> argv;
  for (std::string& arg : strings) argv.push_back(arg.data());
  argv.push_back(nullptr);
  const std::string output = job.output.string();
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) BecomeChild(argv.data(), output.c_str(), mask, parent);
  return pid;
}

ChildEnd Ended(const Running& child, int status) {
  ChildEnd end;
  end.timed_out = child.killed_for_time;
  if (WIFEXITED(status)) end.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) end.signal = WTERMSIG(status);
  end.wall_s = std::chrono::duration<double>(Clock::now() - child.start).count();
  return end;
}

}  // namespace

bool RunChildren(const std::vector<ChildJob>& jobs, int parallel, std::optional<double> timeout_s,
                 const ChildPoolCallbacks& callbacks) {
  const SignalFd signals;
  std::map<pid_t, Running> running;
  std::size_t next = 0;
  bool stop = false;
  while (!stop && (next < jobs.size() || !running.empty())) {
    while (running.size() < static_cast<std::size_t>(parallel) && next < jobs.size()) {
      Running child{next, Clock::now(), std::nullopt, false};
      if (timeout_s) {
        child.deadline = child.start + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(*timeout_s));
      }
      const pid_t pid = Start(jobs[next], signals.previous());
      running.emplace(pid, child);
      if (callbacks.started) callbacks.started(next, pid);
      ++next;
    }
    // Wait for a signal, the nearest deadline or the next tick.
    auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(kTickPeriod);
    for (const auto& [pid, child] : running) {
      if (!child.deadline || child.killed_for_time) continue;
      const auto left =
          std::chrono::ceil<std::chrono::milliseconds>(*child.deadline - Clock::now());
      wait = std::max(std::chrono::milliseconds(0), std::min(wait, left));
    }
    pollfd readable{signals.fd(), POLLIN, 0};
    ::poll(&readable, 1, static_cast<int>(wait.count()));
    stop = signals.DrainStop();
    int status = 0;
    pid_t pid = 0;
    while ((pid = ::waitpid(-1, &status, WNOHANG)) > 0) {
      const auto found = running.find(pid);
      if (found == running.end()) continue;
      const ChildEnd end = Ended(found->second, status);
      const std::size_t job = found->second.job;
      running.erase(found);
      callbacks.ended(job, end);
    }
    const Clock::time_point now = Clock::now();
    for (auto& [child_pid, child] : running) {
      if (child.deadline && !child.killed_for_time && now >= *child.deadline) {
        ::kill(child_pid, SIGKILL);
        child.killed_for_time = true;
      }
    }
    if (callbacks.tick) callbacks.tick();
  }
  if (!stop || (running.empty() && next >= jobs.size())) return true;
  for (const auto& [pid, child] : running) ::kill(pid, SIGKILL);
  for (const auto& [pid, child] : running) ::waitpid(pid, nullptr, 0);
  return false;
}

}  // namespace fireswarm::app
