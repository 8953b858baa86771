#include "cli.hpp"

#include <cmath>
#include <iostream>
#include <sstream>
#include <system_error>

#include "fireswarm/common/output_files.hpp"

namespace fireswarm::app {

namespace po = boost::program_options;

bool ParseCommandLine(const std::string& command_name, const std::string& usage_line,
                      const po::options_description& options,
                      const po::positional_options_description& positional,
                      const std::vector<std::string>& args, po::variables_map& values) {
  po::options_description all(options);
  all.add_options()("help,h", "print this help and exit");
  try {
    po::store(po::command_line_parser(args).options(all).positional(positional).run(), values);
    if (values.count("help") != 0U) {
      std::cout << "usage: fireswarm " << command_name << " " << usage_line << "\n\n"
                << all << "\n";
      return false;
    }
    po::notify(values);
  } catch (const po::error& e) {
    throw UsageError("fireswarm " + command_name + ": " + e.what() + " (see 'fireswarm " +
                     command_name + " --help')");
  }
  return true;
}

void ThrowBadFlag(const std::string& command, const std::string& flag,
                  const std::string& requirement, const std::string& got) {
  throw UsageError("fireswarm " + command + ": --" + flag + " must be " + requirement + ", got '" +
                   got + "'");
}

void CheckOutputFlags(const std::string& command, const std::vector<OutputFlag>& outputs,
                      const std::vector<std::filesystem::path>& inputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const OutputFlag& output = outputs[i];
    if (output.path.empty()) continue;
    const auto fail = [&](const std::string& problem) {
      throw UsageError("fireswarm " + command + ": --" + output.flag + " " + output.path + ": " +
                       problem);
    };
    if (const auto problem = common::OutputPathProblem(output.path, inputs)) fail(*problem);
    for (std::size_t j = 0; j < i; ++j) {
      std::error_code error;
      if (outputs[j].path == output.path ||
          std::filesystem::equivalent(outputs[j].path, output.path, error)) {
        fail("is also --" + outputs[j].flag);
      }
    }
  }
}

void CheckFlagRange(const std::string& command, const std::string& flag, double value,
                    const FlagRange& range) {
  const bool above_min = range.min_open ? value > range.min : value >= range.min;
  if (std::isfinite(value) && above_min && value <= range.max) return;
  ThrowBadFlag(command, flag,
               std::string("in ") + (range.min_open ? "(" : "[") + FlagText(range.min) + ", " +
                   FlagText(range.max) + "]",
               FlagText(value));
}

std::string FlagText(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::optional<common::LatLon> ParseLatLon(const std::string& text) {
  const std::size_t comma = text.find(',');
  if (comma == std::string::npos) return std::nullopt;
  const auto number = [](const std::string& part) -> std::optional<double> {
    std::size_t used = 0;
    try {
      const double value = std::stod(part, &used);
      if (used == part.size() && std::isfinite(value)) return value;
    } catch (const std::exception&) {
    }
    return std::nullopt;
  };
  const std::optional<double> lat = number(text.substr(0, comma));
  const std::optional<double> lon = number(text.substr(comma + 1));
  if (!lat || !lon || !common::IsValidLatLon({*lat, *lon})) return std::nullopt;
  return common::LatLon{*lat, *lon};
}

}  // namespace fireswarm::app
