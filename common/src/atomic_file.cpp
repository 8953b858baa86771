#include "fireswarm/common/atomic_file.hpp"

#include "fireswarm/common/output_files.hpp"

namespace fireswarm::common {

void WriteFileAtomically(const std::filesystem::path& path, std::string_view text, mode_t mode) {
  OutputFiles output;
  output.Stage(path, text, mode);
  output.Commit();
}

}  // namespace fireswarm::common
