// placeholder: filled in by the radio-link work (issue 2)
#include "cli.hpp"
#include "commands.hpp"
namespace fireswarm::app {
int RunRadioDecode(const std::vector<std::string>& /*args*/) { throw UsageError("not built yet"); }
}  // namespace fireswarm::app
