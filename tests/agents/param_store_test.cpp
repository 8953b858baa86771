#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fireswarm/agents/params.hpp"
#include "radio/sim_net.hpp"

namespace fireswarm::agents {
namespace {

namespace fs = std::filesystem;
using radio::ParamStatus;

std::uint16_t Wire(ParamId id) {
  return static_cast<std::uint16_t>(id);
}

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void WriteFile(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// --- values in memory

TEST(ParamStore, StartsAtTheDefaults) {
  const ParamStore store;
  for (const ParamSpec& spec : ParamTable()) {
    EXPECT_EQ(store.Get(spec.id), spec.default_value) << spec.name;
    const radio::ParamValue read = store.Read(Wire(spec.id));
    EXPECT_EQ(read.status, ParamStatus::kOk) << spec.name;
    EXPECT_EQ(read.param_id, Wire(spec.id));
    EXPECT_EQ(read.value, spec.default_value) << spec.name;
  }
  EXPECT_EQ(store.Get(ParamId::kRollKp), 1.0F);
  EXPECT_EQ(store.Get(ParamId::kHeadingOutLimit), 1.5F);
  EXPECT_EQ(store.Get(ParamId::kNavMode), 1.0F);
  EXPECT_EQ(store.Get(ParamId::kCameraPitchDeg), -90.0F);
  EXPECT_EQ(store.Get(ParamId::kFirmwareVersion), 1.0F);
}

TEST(ParamStore, WritesWithinRangeIncludingTheBounds) {
  ParamStore store;
  for (const ParamSpec& spec : ParamTable()) {
    if (spec.read_only) continue;
    for (const float value : {spec.min, spec.max}) {
      const radio::ParamValue reply = store.Write(Wire(spec.id), value);
      EXPECT_EQ(reply.status, ParamStatus::kOk) << spec.name;
      EXPECT_EQ(reply.value, value) << spec.name;
      EXPECT_EQ(store.Get(spec.id), value) << spec.name;
    }
  }
  EXPECT_EQ(store.persist_errors(), 0U);  // nothing to persist to
}

TEST(ParamStore, RejectsEveryValueOutsideItsRangeAndKeepsTheOldOne) {
  ParamStore store;
  constexpr float kInfinity = std::numeric_limits<float>::infinity();
  for (const ParamSpec& spec : ParamTable()) {
    if (spec.read_only) continue;
    for (const float bad :
         {std::nextafter(spec.max, kInfinity), std::nextafter(spec.min, -kInfinity),
          std::numeric_limits<float>::quiet_NaN(), kInfinity, -kInfinity}) {
      const radio::ParamValue reply = store.Write(Wire(spec.id), bad);
      EXPECT_EQ(reply.status, ParamStatus::kOutOfRange) << spec.name << " = " << bad;
      EXPECT_EQ(reply.value, spec.default_value) << spec.name;
      EXPECT_EQ(reply.param_id, Wire(spec.id));
      EXPECT_EQ(store.Get(spec.id), spec.default_value) << spec.name;
    }
  }
}

TEST(ParamStore, RefusesReadOnlyAndUnknownParameters) {
  ParamStore store;
  const radio::ParamValue read_only = store.Write(Wire(ParamId::kFirmwareVersion), 2.0F);
  EXPECT_EQ(read_only.status, ParamStatus::kReadOnly);
  EXPECT_EQ(read_only.value, 1.0F);
  EXPECT_EQ(store.Get(ParamId::kFirmwareVersion), 1.0F);
  for (const std::uint16_t unknown : std::vector<std::uint16_t>{0, 7, 57, 101, 65535}) {
    EXPECT_EQ(store.Write(unknown, 1.0F).status, ParamStatus::kUnknownParam) << unknown;
    const radio::ParamValue read = store.Read(unknown);
    EXPECT_EQ(read.status, ParamStatus::kUnknownParam) << unknown;
    EXPECT_EQ(read.param_id, unknown);
  }
}

// --- the file

const std::string kHeader = R"("format": "fireswarm-params", "version": 1, "vehicle": 7)";

class ParamStoreFile : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("fireswarm_params_" + std::string(test->name()) + "_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    file_ = dir_ / "vehicle_7.json";
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::vector<fs::path> DirectoryEntries() const {
    std::vector<fs::path> entries;
    for (const auto& entry : fs::directory_iterator(dir_)) entries.push_back(entry.path());
    return entries;
  }

  static std::string FileWith(const std::string& params) {
    return "{" + kHeader + R"(, "params": {)" + params + "}}";
  }

  fs::path dir_;
  fs::path file_;
};

TEST_F(ParamStoreFile, MissingFileMeansDefaultsAndIsWrittenAtTheFirstChange) {
  ParamStore store(file_, 7);
  EXPECT_EQ(store.Get(ParamId::kRollKp), 1.0F);
  EXPECT_FALSE(fs::exists(file_));
  ASSERT_EQ(store.Write(Wire(ParamId::kRollKp), 2.5F).status, ParamStatus::kOk);
  EXPECT_TRUE(fs::exists(file_));
  const std::string text = ReadFile(file_);
  EXPECT_NE(text.find(R"("format": "fireswarm-params")"), std::string::npos) << text;
  EXPECT_NE(text.find(R"("vehicle": 7)"), std::string::npos) << text;
  EXPECT_NE(text.find(R"("pid.roll.kp": 2.5)"), std::string::npos) << text;
  // Shortest round-trip decimals, not float noise; read-only values stay out.
  EXPECT_NE(text.find(R"("pid.roll.i_limit": 0.1,)"), std::string::npos) << text;
  EXPECT_EQ(text.find("sys.firmware_version"), std::string::npos) << text;
}

TEST_F(ParamStoreFile, ValuesSurviveARestart) {
  {
    ParamStore store(file_, 7);
    store.Write(Wire(ParamId::kRollKp), 2.5F);
    store.Write(Wire(ParamId::kCrossTrackKi), 0.0123F);
    store.Write(Wire(ParamId::kCameraPitchDeg), -45.0F);
    store.Write(Wire(ParamId::kMaxTiltDeg), 99.0F);  // refused: not persisted
  }
  const ParamStore reloaded(file_, 7);
  EXPECT_EQ(reloaded.Get(ParamId::kRollKp), 2.5F);
  EXPECT_EQ(reloaded.Get(ParamId::kCrossTrackKi), 0.0123F);  // bit for bit
  EXPECT_EQ(reloaded.Get(ParamId::kCameraPitchDeg), -45.0F);
  EXPECT_EQ(reloaded.Get(ParamId::kMaxTiltDeg), 25.0F);
  EXPECT_EQ(reloaded.Get(ParamId::kPitchKp), 1.0F);
}

TEST_F(ParamStoreFile, NamesMissingFromTheFileTakeTheirDefaults) {
  WriteFile(file_, FileWith(R"("nav.mode": 0)"));
  const ParamStore store(file_, 7);
  EXPECT_EQ(store.Get(ParamId::kNavMode), 0.0F);
  EXPECT_EQ(store.Get(ParamId::kRollKp), 1.0F);
}

TEST_F(ParamStoreFile, UnknownNamesAreKeptAndWrittenBack) {
  WriteFile(file_, FileWith(R"("pid.yaw.kp": 0.3, "future.table": [1, 2], "nav.mode": 0)"));
  ParamStore store(file_, 7);
  EXPECT_EQ(store.unknown_names(), 2U);
  ASSERT_EQ(store.Write(Wire(ParamId::kRollKp), 2.0F).status, ParamStatus::kOk);
  const std::string text = ReadFile(file_);
  EXPECT_NE(text.find(R"("pid.yaw.kp": 0.3)"), std::string::npos) << text;
  EXPECT_NE(text.find(R"("future.table")"), std::string::npos) << text;
  const ParamStore reloaded(file_, 7);
  EXPECT_EQ(reloaded.Get(ParamId::kNavMode), 0.0F);
  EXPECT_EQ(reloaded.Get(ParamId::kRollKp), 2.0F);
}

TEST_F(ParamStoreFile, ReadOnlyValuesInTheFileAreIgnored) {
  WriteFile(file_, FileWith(R"("sys.firmware_version": 42)"));
  EXPECT_EQ(ParamStore(file_, 7).Get(ParamId::kFirmwareVersion), 1.0F);
}

TEST_F(ParamStoreFile, VehicleZeroAcceptsAnyFileAndKeepsItsVehicle) {
  WriteFile(file_, FileWith(R"("nav.mode": 0)"));
  ParamStore store(file_);
  EXPECT_EQ(store.Get(ParamId::kNavMode), 0.0F);
  store.Write(Wire(ParamId::kRollKp), 2.0F);
  EXPECT_NE(ReadFile(file_).find(R"("vehicle": 7)"), std::string::npos);
}

struct CorruptCase {
  std::string name;
  std::string text;
  std::string key;  // the message must name it
};

class ParamStoreCorruptFile : public ParamStoreFile,
                              public ::testing::WithParamInterface<CorruptCase> {};

TEST_P(ParamStoreCorruptFile, ThrowsNamingTheFileAndKeyAndLeavesTheFile) {
  WriteFile(file_, GetParam().text);
  try {
    const ParamStore store(file_, 7);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(file_.string()), std::string::npos) << message;
    EXPECT_NE(message.find(GetParam().key), std::string::npos) << message;
  }
  EXPECT_EQ(ReadFile(file_), GetParam().text);
  EXPECT_EQ(DirectoryEntries().size(), 1U);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, ParamStoreCorruptFile,
    ::testing::Values(
        CorruptCase{"NotJson", R"({"format": "fireswarm-params", "params": {"pid.roll.kp": 1.)",
                    "not JSON"},
        CorruptCase{"Empty", "", "not JSON"},
        CorruptCase{"NotAnObject", "[1, 2]", "not a JSON object"},
        CorruptCase{"WrongFormat",
                    R"({"format": "qgc-params", "version": 1, "vehicle": 7, "params": {}})",
                    "\"format\""},
        CorruptCase{"WrongVersion",
                    R"({"format": "fireswarm-params", "version": 2, "vehicle": 7, "params": {}})",
                    "\"version\""},
        CorruptCase{"AnotherVehicle",
                    R"({"format": "fireswarm-params", "version": 1, "vehicle": 8, "params": {}})",
                    "\"vehicle\""},
        CorruptCase{"ParamsNotAnObject", "{" + kHeader + R"(, "params": [1]})", "\"params\""},
        CorruptCase{"ValueNotANumber", "{" + kHeader + R"(, "params": {"pid.roll.kp": "1.0"}})",
                    "\"params.pid.roll.kp\""},
        CorruptCase{"ValueOutOfRange",
                    "{" + kHeader + R"(, "params": {"nav.mode": 1, "limit.max_tilt_deg": 80}})",
                    "\"params.limit.max_tilt_deg\""},
        CorruptCase{"ValueBeyondFloat", "{" + kHeader + R"(, "params": {"pid.speed.kp": 1e300}})",
                    "\"params.pid.speed.kp\""}),
    [](const auto& param_info) { return param_info.param.name; });

TEST_F(ParamStoreFile, WritesLeaveNoTemporaryFileBehind) {
  ParamStore store(file_, 7);
  for (int i = 0; i < 5; ++i) {
    ASSERT_EQ(store.Write(Wire(ParamId::kAcceptanceRadiusM), 10.0F + static_cast<float>(i)).status,
              ParamStatus::kOk);
  }
  EXPECT_EQ(DirectoryEntries(), std::vector<fs::path>{file_});
  EXPECT_EQ(store.persist_errors(), 0U);
  EXPECT_EQ(ParamStore(file_, 7).Get(ParamId::kAcceptanceRadiusM), 14.0F);
}

TEST_F(ParamStoreFile, PersistFailureIsCountedNotThrownAndRetriedAtTheNextWrite) {
  ParamStore store(file_, 7);
  fs::remove_all(dir_);  // the storage went away under the running vehicle
  radio::ParamValue reply;
  EXPECT_NO_THROW(reply = store.Write(Wire(ParamId::kRollKp), 2.0F));
  EXPECT_EQ(reply.status, ParamStatus::kOk);  // held and used, just not saved
  EXPECT_EQ(store.Get(ParamId::kRollKp), 2.0F);
  EXPECT_EQ(store.persist_errors(), 1U);
  EXPECT_NE(store.last_persist_error().find(file_.string()), std::string::npos)
      << store.last_persist_error();

  fs::create_directories(dir_);
  EXPECT_EQ(store.Write(Wire(ParamId::kPitchKp), 3.0F).status, ParamStatus::kOk);
  EXPECT_EQ(store.persist_errors(), 1U);
  const ParamStore reloaded(file_, 7);
  EXPECT_EQ(reloaded.Get(ParamId::kRollKp), 2.0F);  // the whole table went out
  EXPECT_EQ(reloaded.Get(ParamId::kPitchKp), 3.0F);
}

// --- over the radio: server -> shared channel -> vehicle endpoint -> ParamStore

class ParamHandler final : public radio::VehicleRequestHandler {
 public:
  explicit ParamHandler(ParamStore& store) : store_(store) {}
  radio::CommandResult OnCommand(const radio::Command& /*command*/) override {
    return radio::CommandResult::kUnsupported;
  }
  radio::MissionAckStatus OnMissionChunk(const radio::MissionChunk& /*chunk*/) override {
    return radio::MissionAckStatus::kRejected;
  }
  radio::ParamValue OnParamRead(const radio::ParamRead& read) override {
    return store_.Read(read.param_id);
  }
  radio::ParamValue OnParamWrite(const radio::ParamWrite& write) override {
    return store_.Write(write.param_id, write.value);
  }

 private:
  ParamStore& store_;
};

radio::ParamValue AckOf(const radio::RequestFinished& finished) {
  EXPECT_EQ(finished.status, radio::RequestStatus::kCompleted);
  EXPECT_TRUE(finished.ack.has_value());
  return std::get<radio::ParamValue>(finished.ack.value());
}

TEST_F(ParamStoreFile, ReadAndWriteOverTheRadio) {
  using radio::sim_test::SimNet;
  ParamStore store(file_, 1);
  ParamHandler handler(store);
  std::vector<radio::VehicleRequestHandler*> handlers{&handler};
  SimNet net(radio::sim_test::ServerConfig(radio::LinkMode::kSlots), 1, 0.0, handlers);
  net.server().AddVehicle(1);
  const radio::RequestId write = net.server().WriteParam(1, Wire(ParamId::kHeadingKp), 2.25F);
  const radio::RequestId bad = net.server().WriteParam(1, Wire(ParamId::kMaxTiltDeg), 50.0F);
  const radio::RequestId read = net.server().ReadParam(1, Wire(ParamId::kHeadingKp));
  const radio::RequestId unknown = net.server().ReadParam(1, 999);
  net.RunUntil(std::chrono::seconds(5));

  const auto finished = net.EventsOf<radio::RequestFinished>();
  ASSERT_EQ(finished.size(), 4U);
  EXPECT_EQ(finished[0].id, write);
  const radio::ParamValue written = AckOf(finished[0]);
  EXPECT_EQ(written.status, ParamStatus::kOk);
  EXPECT_EQ(written.param_id, Wire(ParamId::kHeadingKp));
  EXPECT_EQ(written.value, 2.25F);
  EXPECT_EQ(finished[1].id, bad);
  EXPECT_EQ(AckOf(finished[1]).status, ParamStatus::kOutOfRange);
  EXPECT_EQ(AckOf(finished[1]).value, 25.0F);  // the value still held
  EXPECT_EQ(finished[2].id, read);
  EXPECT_EQ(AckOf(finished[2]).value, 2.25F);
  EXPECT_EQ(finished[3].id, unknown);
  EXPECT_EQ(AckOf(finished[3]).status, ParamStatus::kUnknownParam);

  // The vehicle restarts: the radio write is still there (the seed's EEPROM).
  EXPECT_EQ(ParamStore(file_, 1).Get(ParamId::kHeadingKp), 2.25F);
}

}  // namespace
}  // namespace fireswarm::agents
