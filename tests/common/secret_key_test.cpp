#include "fireswarm/common/secret_key.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace fireswarm::common {
namespace {

class SecretKeyFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("fireswarm_key_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string ErrorReading(const std::filesystem::path& path) {
    try {
      ReadSecretKeyFile(path);
    } catch (const std::runtime_error& error) {
      return error.what();
    }
    return "";
  }

  std::filesystem::path dir_;
};

TEST_F(SecretKeyFileTest, RoundTripsAKeyInAFileOnlyItsOwnerMayRead) {
  const SecretKey key = GenerateSecretKey();
  const std::filesystem::path file = dir_ / "vehicle_3.key";
  WriteSecretKeyFile(file, key);
  struct stat status {};
  ASSERT_EQ(::stat(file.c_str(), &status), 0);
  EXPECT_EQ(status.st_mode & 0777, 0600u);
  EXPECT_EQ(ReadSecretKeyFile(file), key);
}

TEST_F(SecretKeyFileTest, ReplacingAnOpenFileLeavesItOwnerOnly) {
  const std::filesystem::path file = dir_ / "operator.key";
  { std::ofstream(file) << "old\n"; }
  ::chmod(file.c_str(), 0644);
  WriteSecretKeyFile(file, GenerateSecretKey());
  struct stat status {};
  ASSERT_EQ(::stat(file.c_str(), &status), 0);
  EXPECT_EQ(status.st_mode & 0777, 0600u);
}

TEST_F(SecretKeyFileTest, TwoKeysDrawnDiffer) {
  EXPECT_NE(GenerateSecretKey(), GenerateSecretKey());
}

TEST_F(SecretKeyFileTest, RefusesAKeyOthersMayRead) {
  const std::filesystem::path file = dir_ / "open.key";
  WriteSecretKeyFile(file, GenerateSecretKey());
  ::chmod(file.c_str(), 0640);
  const std::string error = ErrorReading(file);
  EXPECT_NE(error.find("open.key"), std::string::npos) << error;
  EXPECT_NE(error.find("0640"), std::string::npos) << error;
}

TEST_F(SecretKeyFileTest, RefusesMissingShortAndNonHexFilesNamingThem) {
  EXPECT_NE(ErrorReading(dir_ / "absent.key").find("absent.key"), std::string::npos);
  const std::filesystem::path short_file = dir_ / "short.key";
  { std::ofstream(short_file) << "abcd\n"; }
  ::chmod(short_file.c_str(), 0600);
  EXPECT_NE(ErrorReading(short_file).find("4 characters"), std::string::npos);
  const std::filesystem::path bad = dir_ / "bad.key";
  { std::ofstream(bad) << std::string(63, 'a') << "z\n"; }
  ::chmod(bad.c_str(), 0600);
  EXPECT_NE(ErrorReading(bad).find("character 64"), std::string::npos) << ErrorReading(bad);
  EXPECT_NE(ErrorReading(dir_).find("regular file"), std::string::npos);
}

}  // namespace
}  // namespace fireswarm::common
