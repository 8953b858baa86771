// Child processes run a few at a time, each with its own output file and an
// optional wall-clock limit, for `fireswarm sweep`. A child lives in its own
// process group (a terminal's Ctrl-C reaches only the parent, which then stops
// them all) and dies with the parent (PR_SET_PDEATHSIG), so a sweep killed
// outright leaves no run writing behind it.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace fireswarm::app {

struct ChildJob {
  std::vector<std::string> argv;  ///< argv[0] is the executable's path
  std::filesystem::path output;   ///< stdout and stderr go here (truncated)
};

/// How a child ended.
struct ChildEnd {
  bool timed_out = false;        ///< killed by the pool over its limit
  std::optional<int> exit_code;  ///< when it exited
  std::optional<int> signal;     ///< when a signal ended it
  double wall_s = 0.0;
};

struct ChildPoolCallbacks {
  std::function<void(std::size_t job, pid_t pid)> started;  ///< may be empty
  std::function<void(std::size_t job, const ChildEnd&)> ended;
  std::function<void()> tick;  ///< about every 200 ms and after each end; may be empty
};

/// Runs `jobs` in order, at most `parallel` at once, killing (SIGKILL) a child
/// that runs longer than `timeout_s`. Returns true when every job ended; false
/// when SIGINT or SIGTERM arrived: the children still running are killed and
/// reaped without `ended`, and no further job starts. Throws
/// std::runtime_error when a child cannot be started.
bool RunChildren(const std::vector<ChildJob>& jobs, int parallel, std::optional<double> timeout_s,
                 const ChildPoolCallbacks& callbacks);

}  // namespace fireswarm::app
