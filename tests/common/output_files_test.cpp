#include "fireswarm/common/output_files.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace fireswarm::common {
namespace {

namespace fs = std::filesystem;

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

int CountEntries(const fs::path& dir) {
  int entries = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++entries;
  return entries;
}

class OutputFilesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("fireswarm_output_files_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(OutputFilesTest, AcceptsNewAndRegularFilesInAWritableDirectory) {
  EXPECT_EQ(OutputPathProblem(dir_ / "new.json"), std::nullopt);
  std::ofstream(dir_ / "old.json") << "old";
  EXPECT_EQ(OutputPathProblem(dir_ / "old.json"), std::nullopt);
}

TEST_F(OutputFilesTest, RefusesFifoSymlinkDeviceDirectoryAndMissingDirectory) {
  ASSERT_EQ(::mkfifo((dir_ / "fifo").c_str(), 0600), 0);
  std::ofstream(dir_ / "real.json") << "keep";
  fs::create_symlink(dir_ / "real.json", dir_ / "link.json");
  fs::create_directories(dir_ / "sub");
  const auto problem = [](const fs::path& p) { return OutputPathProblem(p).value_or("ok"); };
  EXPECT_NE(problem(dir_ / "fifo").find("is a fifo"), std::string::npos);
  EXPECT_NE(problem(dir_ / "link.json").find("is a symbolic link"), std::string::npos);
  EXPECT_NE(problem("/dev/null").find("is a device"), std::string::npos);
  EXPECT_NE(problem(dir_ / "sub").find("is a directory"), std::string::npos);
  EXPECT_NE(problem(dir_ / "none" / "x.json").find("does not exist"), std::string::npos);
  // The refused file itself is left alone.
  EXPECT_TRUE(fs::is_symlink(dir_ / "link.json"));
  EXPECT_EQ(ReadText(dir_ / "real.json"), "keep");
}

TEST_F(OutputFilesTest, RefusesAnInputEvenUnderAnotherName) {
  std::ofstream(dir_ / "scenario.yaml") << "name: x\n";
  fs::create_directories(dir_ / "sub");
  const fs::path other_name = dir_ / "sub" / ".." / "scenario.yaml";
  const auto problem = OutputPathProblem(other_name, {dir_ / "scenario.yaml"});
  ASSERT_TRUE(problem.has_value());
  EXPECT_NE(problem->find("is the input"), std::string::npos) << *problem;
  EXPECT_EQ(OutputPathProblem(dir_ / "report.json", {dir_ / "scenario.yaml"}), std::nullopt);
}

TEST_F(OutputFilesTest, CommitWritesAllAndDestructionWithoutCommitWritesNone) {
  {
    OutputFiles output;
    output.Stage(dir_ / "a.txt", "a");
    output.Stage(dir_ / "b.txt", "b");
  }
  EXPECT_EQ(CountEntries(dir_), 0);  // neither target nor temporary
  OutputFiles output;
  output.Stage(dir_ / "a.txt", "a");
  std::ofstream(output.Reserve(dir_ / "log.bin")) << "log";
  EXPECT_THROW(output.Stage(dir_ / "a.txt", "again"), std::runtime_error);
  output.Commit();
  EXPECT_EQ(ReadText(dir_ / "a.txt"), "a");
  EXPECT_EQ(ReadText(dir_ / "log.bin"), "log");
  EXPECT_EQ(CountEntries(dir_), 2);
}

TEST_F(OutputFilesTest, StagingARefusedTargetThrowsNamingIt) {
  ASSERT_EQ(::mkfifo((dir_ / "fifo").c_str(), 0600), 0);
  OutputFiles output;
  try {
    output.Stage(dir_ / "fifo", "x");
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find((dir_ / "fifo").string() + ": is a fifo"),
              std::string::npos)
        << error.what();
  }
  struct stat info {};
  ASSERT_EQ(::lstat((dir_ / "fifo").c_str(), &info), 0);
  EXPECT_TRUE(S_ISFIFO(info.st_mode));
}

}  // namespace
}  // namespace fireswarm::common
