// Shared plumbing for the `fireswarm` subcommands: option parsing with --help,
// and the exit-code convention (0 ok, 1 a check failed, 2 bad input).
#pragma once

#include <boost/program_options.hpp>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "fireswarm/common/local_frame.hpp"

namespace fireswarm::app {

inline constexpr int kExitOk = 0;
inline constexpr int kExitCheckFailed = 1;
inline constexpr int kExitBadInput = 2;

/// Thrown for bad command-line input or input files; main() prints it and exits 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One subcommand: `fireswarm <name> [args...]`.
struct Command {
  const char* name;
  const char* summary;
  /// Runs the subcommand; `args` excludes the program and subcommand names.
  /// Returns the process exit code; throws UsageError on bad input.
  int (*run)(const std::vector<std::string>& args);
};

/// Parses `args` against `options` (plus --help) and the positional spec.
/// Returns false when --help was given (usage already printed to stdout).
/// Throws UsageError naming the offending flag or value.
bool ParseCommandLine(const std::string& command_name, const std::string& usage_line,
                      const boost::program_options::options_description& options,
                      const boost::program_options::positional_options_description& positional,
                      const std::vector<std::string>& args,
                      boost::program_options::variables_map& values);

/// Throws UsageError "fireswarm <command>: --<flag> must be <requirement>, got '<got>'".
[[noreturn]] void ThrowBadFlag(const std::string& command, const std::string& flag,
                               const std::string& requirement, const std::string& got);

/// One output of a command: its flag (without "--") and the path given; an
/// empty path means the output was not asked for.
struct OutputFlag {
  std::string flag;
  std::string path;
};

/// Checks every output before the command reads or computes anything
/// (common::OutputPathProblem against `inputs`), and that no two flags name the
/// same file. Throws UsageError "fireswarm <command>: --<flag> <path>: <problem>".
void CheckOutputFlags(const std::string& command, const std::vector<OutputFlag>& outputs,
                      const std::vector<std::filesystem::path>& inputs);

/// A numeric flag's documented range (docs/limits.md): [min, max], or (min, max]
/// when `min_open`.
struct FlagRange {
  double min = 0.0;
  double max = 0.0;
  bool min_open = false;
};

/// Throws UsageError "fireswarm <command>: --<flag> must be in [min, max], got
/// '<value>'" when `value` is outside `range` or not finite.
void CheckFlagRange(const std::string& command, const std::string& flag, double value,
                    const FlagRange& range);

/// The longest wall-clock or simulated --duration-s a command takes, s (30 days).
inline constexpr double kMaxCommandDurationS = 30.0 * 86'400.0;

/// A number as flag messages show it (as an ostream prints it: 0.5, 1e+06).
std::string FlagText(double value);

/// "lat,lon" in WGS84 degrees (as --launch and --fire take it); nullopt when it is
/// not two numbers or lies outside [-90, 90] x [-180, 180].
std::optional<common::LatLon> ParseLatLon(const std::string& text);

}  // namespace fireswarm::app
