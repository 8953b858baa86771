#include "cli.hpp"

#include <iostream>

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

}  // namespace fireswarm::app
