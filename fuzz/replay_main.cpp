// Runs a fuzz target's entry function on every file of the directories (or files)
// given, as libFuzzer would on a corpus, without libFuzzer: the seed corpora and
// crash reproducers are ordinary tests in the g++ build.
//   build/bin/<name>_replay fuzz/corpus/<name> [more dirs or files]
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <vector>

#include "fuzz_check.hpp"

namespace {

std::vector<std::filesystem::path> CorpusFiles(const std::filesystem::path& path) {
  if (!std::filesystem::is_directory(path)) return {path};
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(path)) {
    if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t inputs = 0;
  for (int i = 1; i < argc; ++i) {
    if (!std::filesystem::exists(argv[i])) {
      std::cerr << argv[i] << ": no such corpus\n";
      return 1;
    }
    for (const std::filesystem::path& file : CorpusFiles(argv[i])) {
      std::ifstream in(file, std::ios::binary);
      const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                            std::istreambuf_iterator<char>());
      std::cerr << "replaying " << file.string() << " (" << bytes.size() << " bytes)\n";
      LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
      ++inputs;
    }
  }
  if (inputs == 0) {
    std::cerr << "no corpus files given\n";
    return 1;
  }
  std::cerr << inputs << " inputs replayed\n";
  return 0;
}
