// End-to-end tests of `fireswarm radio-decode`: a real capture file on disk, the
// real executable (env FIRESWARM_BIN, set by the test suite), its JSON lines.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/run_fireswarm.hpp"
#include "fireswarm/radio/messages.hpp"

namespace fireswarm::app {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<std::uint8_t>;
using Json = nlohmann::json;

class RadioDecodeCommand : public CommandTest {
 protected:
  std::string WriteCapture(const std::string& name, const Bytes& bytes) const {
    const fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()),
               static_cast<std::streamsize>(bytes.size()));
    return path.string();
  }
};

radio::Telemetry SampleTelemetry() {
  radio::Telemetry t;
  t.header = {.sender = 3, .sequence = 513};
  t.lat_deg = 47.3977419;
  t.lon_deg = 8.5455938;
  t.altitude_m = 52.37;
  t.heading_deg = 271.05;
  t.mode = radio::FlightMode::kSearch;
  t.flags = radio::telemetry_flags::kGpsFix;
  return t;
}

// garbage | telemetry | garbage | poll | unknown ID 0x99 | poll with a 2-byte payload |
// corrupted frame | the first 10 bytes of a frame.
Bytes MakeCapture(radio::ChecksumMode mode, std::vector<std::size_t>& offsets) {
  Bytes capture{0x00, 0x70, 0x96, 0x11, 0xFF};
  offsets.push_back(capture.size());
  radio::AppendMessageFrame(capture, radio::kServerId, SampleTelemetry(), mode);
  capture.insert(capture.end(), {0xAC, 0x96, 0x70});
  offsets.push_back(capture.size());
  radio::AppendMessageFrame(capture, 4, radio::Poll{{0, 7}, radio::ReplyKind::kAck}, mode);
  offsets.push_back(capture.size());
  radio::AppendFrame(capture, 5, 0x99, Bytes{0xDE, 0xAD}, mode);
  offsets.push_back(capture.size());
  radio::AppendFrame(capture, 5, 0x01, Bytes{0x01, 0x02}, mode);
  Bytes corrupted;
  radio::AppendMessageFrame(corrupted, 6, radio::Heartbeat{}, mode);
  corrupted[8] ^= 0x10;
  capture.insert(capture.end(), corrupted.begin(), corrupted.end());
  Bytes cut;
  radio::AppendMessageFrame(cut, 6, SampleTelemetry(), mode);
  capture.insert(capture.end(), cut.begin(), cut.begin() + 10);
  return capture;
}

TEST_F(RadioDecodeCommand, PrintsOneJsonLinePerFrameAndASummary) {
  std::vector<std::size_t> offsets;
  const Bytes capture = MakeCapture(radio::ChecksumMode::kCrc16, offsets);
  const RunResult run = RunFireswarm("radio-decode '" + WriteCapture("crc.bin", capture) + "'");
  ASSERT_EQ(run.exit_code, 0);
  ASSERT_EQ(run.lines.size(), 5U);
  std::vector<Json> lines;
  for (const std::string& line : run.lines) lines.push_back(Json::parse(line));

  EXPECT_EQ(lines[0]["offset"], offsets[0]);
  EXPECT_EQ(lines[0]["receiver"], 0);
  EXPECT_EQ(lines[0]["message_id"], 0x10);
  EXPECT_EQ(lines[0]["length"], 41);
  EXPECT_EQ(lines[0]["message"], "telemetry");
  EXPECT_EQ(lines[0]["fields"]["sender"], 3);
  EXPECT_EQ(lines[0]["fields"]["sequence"], 513);
  EXPECT_EQ(lines[0]["fields"]["lat_deg"], 47.3977419);
  EXPECT_EQ(lines[0]["fields"]["altitude_m"], 52.37);
  EXPECT_EQ(lines[0]["fields"]["heading_deg"], 271.05);
  EXPECT_EQ(lines[0]["fields"]["mode"], "search");
  EXPECT_EQ(lines[0]["fields"]["flag_names"], Json::array({"gps_fix"}));

  EXPECT_EQ(lines[1]["offset"], offsets[1]);
  EXPECT_EQ(lines[1]["message"], "poll");
  EXPECT_EQ(lines[1]["fields"]["reply"], "ack");

  EXPECT_EQ(lines[2]["offset"], offsets[2]);
  EXPECT_FALSE(lines[2].contains("message"));
  EXPECT_EQ(lines[2]["hex"], "dead");

  EXPECT_EQ(lines[3]["offset"], offsets[3]);
  EXPECT_EQ(lines[3]["message"], "poll");
  EXPECT_EQ(lines[3]["decode_error"], "too_short");
  EXPECT_FALSE(lines[3].contains("fields"));

  const Json& summary = lines[4]["summary"];
  EXPECT_EQ(summary["frames"], 4);
  EXPECT_EQ(summary["bytes"], capture.size());
  EXPECT_EQ(summary["checksum_errors"], 1);
  EXPECT_EQ(summary["truncated_frames"], 1);
  EXPECT_EQ(summary["decode_errors"], 1);
  EXPECT_GT(summary["skipped_bytes"].get<std::size_t>(), 0U);
}

TEST_F(RadioDecodeCommand, ReadsXorCapturesFromStandardInput) {
  std::vector<std::size_t> offsets;
  const Bytes capture = MakeCapture(radio::ChecksumMode::kXor, offsets);
  const std::string path = WriteCapture("xor.bin", capture);
  const RunResult run = RunFireswarm("radio-decode --checksum xor - < '" + path + "'");
  ASSERT_EQ(run.exit_code, 0);
  ASSERT_EQ(run.lines.size(), 5U);
  EXPECT_EQ(Json::parse(run.lines[0])["message"], "telemetry");
  EXPECT_EQ(Json::parse(run.lines[4])["summary"]["frames"], 4);
  // Read as CRC-16, the same capture holds no frame, and that is not an error.
  const RunResult as_crc = RunFireswarm("radio-decode --checksum crc16 '" + path + "'");
  ASSERT_EQ(as_crc.exit_code, 0);
  ASSERT_EQ(as_crc.lines.size(), 1U);
  EXPECT_EQ(Json::parse(as_crc.lines[0])["summary"]["frames"], 0);
}

TEST_F(RadioDecodeCommand, GarbageOnlyCaptureIsExitZero) {
  const RunResult run =
      RunFireswarm("radio-decode '" + WriteCapture("g.bin", Bytes(1000, 0x70)) + "'");
  EXPECT_EQ(run.exit_code, 0);
  ASSERT_EQ(run.lines.size(), 1U);
  EXPECT_EQ(Json::parse(run.lines[0])["summary"]["skipped_bytes"], 1000);
}

TEST_F(RadioDecodeCommand, BadChecksumFlagIsExitTwoNamingFlagAndValue) {
  const RunResult run =
      RunFireswarm("radio-decode --checksum md5 '" + WriteCapture("c.bin", Bytes{}) + "'");
  EXPECT_EQ(run.exit_code, 2);
  ASSERT_FALSE(run.lines.empty());
  EXPECT_NE(run.lines[0].find("--checksum"), std::string::npos) << run.lines[0];
  EXPECT_NE(run.lines[0].find("md5"), std::string::npos) << run.lines[0];
}

TEST_F(RadioDecodeCommand, MissingFileIsExitTwoNamingTheFile) {
  const std::string missing = (dir_ / "no_such_capture.bin").string();
  const RunResult run = RunFireswarm("radio-decode '" + missing + "'");
  EXPECT_EQ(run.exit_code, 2);
  ASSERT_FALSE(run.lines.empty());
  EXPECT_NE(run.lines[0].find(missing), std::string::npos) << run.lines[0];
}

TEST_F(RadioDecodeCommand, MissingFileArgumentIsExitTwo) {
  EXPECT_EQ(RunFireswarm("radio-decode").exit_code, 2);
}

}  // namespace
}  // namespace fireswarm::app
