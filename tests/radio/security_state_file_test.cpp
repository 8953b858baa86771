#include "fireswarm/radio/security_state_file.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>
#include <stdexcept>

namespace fireswarm::radio {
namespace {

class SecurityStateFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("fireswarm_security_state_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(SecurityStateFileTest, RoundTripsAndIsWrittenOwnerOnly) {
  const std::filesystem::path path = dir_ / "radio_security.state";
  EXPECT_EQ(ReadSecurityStateFile(path), SecurityState{}) << "a missing file is a first start";
  SecurityState state;
  state.next_counter = 4096;
  state.floors = {{3, 1177}, {255, 9}};
  WriteSecurityStateFile(path, state);
  EXPECT_EQ(ReadSecurityStateFile(path), state);
  struct stat info {};
  ASSERT_EQ(::stat(path.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0600U);
}

TEST_F(SecurityStateFileTest, MalformedFileIsRefusedNamingPathAndLine) {
  const std::filesystem::path path = dir_ / "bad.state";
  std::ofstream(path) << "fireswarm-radio-security 1\nnext_counter lots\n";
  try {
    ReadSecurityStateFile(path);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.state:2"), std::string::npos) << e.what();
  }
}

TEST_F(SecurityStateFileTest, PersistToFileReportsAFailedWriteAsFalse) {
  EXPECT_FALSE(PersistToFile(dir_ / "missing_dir" / "x.state")(SecurityState{}));
  EXPECT_TRUE(PersistToFile(dir_ / "x.state")(SecurityState{}));
}

}  // namespace
}  // namespace fireswarm::radio
