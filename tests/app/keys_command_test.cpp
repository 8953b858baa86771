// `fireswarm keys`: the fleet key store's layout, modes and refusals, through the
// real executable.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <string>

#include "app/run_fireswarm.hpp"
#include "fireswarm/common/secret_key.hpp"

namespace fireswarm::app {
namespace {

namespace fs = std::filesystem;

unsigned ModeOf(const fs::path& path) {
  struct stat info {};
  EXPECT_EQ(::stat(path.c_str(), &info), 0) << path;
  return info.st_mode & 0777U;
}

bool Mentions(const RunResult& run, const std::string& text) {
  for (const std::string& line : run.lines) {
    if (line.find(text) != std::string::npos) return true;
  }
  return false;
}

class KeysCommand : public CommandTest {
 protected:
  void SetUp() override {
    CommandTest::SetUp();
    store_ = PathOf("fleet_keys");
    ASSERT_EQ(RunFireswarm("keys init " + store_).exit_code, 0);
  }
  RunResult Keys(const std::string& args) const { return RunFireswarm("keys " + args); }
  std::string store_;
};

TEST_F(KeysCommand, InitAndAddWriteTheLayoutOwnerOnly) {
  ASSERT_EQ(Keys("add-vehicle " + store_ + " --id 1 --id 2").exit_code, 0);
  ASSERT_EQ(Keys("add-operator " + store_ + " --name alice").exit_code, 0);
  EXPECT_EQ(ModeOf(store_), 0700U);
  EXPECT_EQ(ModeOf(fs::path(store_) / "vehicles"), 0700U);
  for (const char* file :
       {"broadcast.key", "vehicles/1.key", "vehicles/2.key", "operators/alice.key"}) {
    EXPECT_EQ(ModeOf(fs::path(store_) / file), 0600U) << file;
    common::ReadSecretKeyFile(fs::path(store_) / file);  // a valid key
  }
  EXPECT_NE(common::ReadSecretKeyFile(fs::path(store_) / "vehicles/1.key"),
            common::ReadSecretKeyFile(fs::path(store_) / "vehicles/2.key"));
}

TEST_F(KeysCommand, RefusesToOverwriteABadNameOrANonStore) {
  ASSERT_EQ(Keys("add-vehicle " + store_ + " --id 1").exit_code, 0);
  const RunResult again = Keys("add-vehicle " + store_ + " --id 1");
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_TRUE(Mentions(again, "rotate"));
  EXPECT_EQ(Keys("add-operator " + store_ + " --name ../x").exit_code, 2);
  EXPECT_EQ(Keys("add-vehicle " + store_ + " --id 255").exit_code, 2);
  EXPECT_EQ(Keys("add-vehicle " + PathOf("nowhere") + " --id 1").exit_code, 2);
  EXPECT_EQ(Keys("shred " + store_).exit_code, 2);
}

TEST_F(KeysCommand, ProvisionRotateAndRetireAVehicle) {
  ASSERT_EQ(Keys("add-vehicle " + store_ + " --id 3").exit_code, 0);
  const std::string params = PathOf("vehicle3.json");
  ASSERT_EQ(Keys("provision " + store_ + " --id 3 --param-file " + params).exit_code, 0);
  const common::SecretKey first = common::ReadSecretKeyFile(params + ".key");
  EXPECT_EQ(first, common::ReadSecretKeyFile(fs::path(store_) / "vehicles/3.key"));
  EXPECT_EQ(common::ReadSecretKeyFile(params + ".broadcast.key"),
            common::ReadSecretKeyFile(fs::path(store_) / "broadcast.key"));
  EXPECT_EQ(ModeOf(params + ".key"), 0600U);

  ASSERT_EQ(Keys("rotate " + store_ + " --id 3").exit_code, 0);
  EXPECT_EQ(common::ReadSecretKeyFile(fs::path(store_) / "vehicles/3.previous.key"), first);
  EXPECT_NE(common::ReadSecretKeyFile(fs::path(store_) / "vehicles/3.key"), first);
  EXPECT_EQ(Keys("rotate " + store_ + " --id 3").exit_code, 2) << "one rotation at a time";

  ASSERT_EQ(Keys("provision " + store_ + " --id 3 --param-file " + params).exit_code, 0);
  EXPECT_EQ(common::ReadSecretKeyFile(params + ".previous.key"), first);
  ASSERT_EQ(Keys("retire " + store_ + " --id 3").exit_code, 0);
  EXPECT_FALSE(fs::exists(fs::path(store_) / "vehicles/3.previous.key"));
  ASSERT_EQ(Keys("provision " + store_ + " --id 3 --param-file " + params).exit_code, 0);
  EXPECT_FALSE(fs::exists(params + ".previous.key"));
}

TEST_F(KeysCommand, KeyFileOpenToOthersIsRefusedNamingIt) {
  ASSERT_EQ(Keys("add-vehicle " + store_ + " --id 4").exit_code, 0);
  const fs::path key = fs::path(store_) / "vehicles/4.key";
  fs::permissions(key, fs::perms::others_read, fs::perm_options::add);
  const RunResult run =
      Keys("provision " + store_ + " --id 4 --param-file " + PathOf("vehicle4.json"));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_TRUE(Mentions(run, key.string()));
  EXPECT_FALSE(fs::exists(PathOf("vehicle4.json.key")));
}

}  // namespace
}  // namespace fireswarm::app
