#include "fireswarm/common/atomic_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace fireswarm::common {
namespace {

std::string Read(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

class WriteFileAtomicallyTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("fireswarm_atomic_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(WriteFileAtomicallyTest, WritesAndReplacesLeavingNoTemporary) {
  const std::filesystem::path file = dir_ / "plan.json";
  WriteFileAtomically(file, "first\n");
  EXPECT_EQ(Read(file), "first\n");
  WriteFileAtomically(file, "second\n");
  EXPECT_EQ(Read(file), "second\n");
  int entries = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir_)) ++entries;
  EXPECT_EQ(entries, 1);
}

TEST_F(WriteFileAtomicallyTest, AFailureNamesThePathAndLeavesNothingBehind) {
  try {
    WriteFileAtomically(dir_ / "missing" / "x.json", "{}");
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find((dir_ / "missing" / "x.json").string()),
              std::string::npos)
        << error.what();
  }
  // Renaming over a directory fails after the temporary was written: it is removed.
  const std::filesystem::path directory = dir_ / "taken";
  std::filesystem::create_directories(directory);
  EXPECT_THROW(WriteFileAtomically(directory, "{}"), std::runtime_error);
  int entries = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir_)) ++entries;
  EXPECT_EQ(entries, 1);  // only "taken"
  EXPECT_TRUE(std::filesystem::is_directory(directory));
}

}  // namespace
}  // namespace fireswarm::common
