// `fireswarm radio-decode [--checksum xor|crc16] FILE|-`: decodes a raw APOne byte
// capture (a serial or radio dump) into one compact JSON line per valid frame, then
// one summary line. Garbage in the capture is normal input (exit 0); a file that
// cannot be read or a bad option is exit 2.

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli.hpp"
#include "commands.hpp"
#include "fireswarm/radio/messages.hpp"
#include "fireswarm/radio/parser.hpp"
#include "message_json.hpp"

namespace fireswarm::app {
namespace {

namespace po = boost::program_options;
using Json = nlohmann::ordered_json;

constexpr std::size_t kReadChunkBytes = 64 * 1024;

// One JSON line for a frame: where it was, its header, and its message decoded
// (known ID), the decode error and raw data (known ID, bad payload), or the raw
// data (unknown ID). Returns whether the payload failed to decode.
bool PrintFrame(const radio::FrameView& frame, std::ostream& out) {
  Json line;
  line["offset"] = frame.offset;
  line["receiver"] = frame.receiver;
  line["message_id"] = frame.message_id;
  line["length"] = frame.data.size();
  const std::optional<std::string_view> name = radio::MessageName(frame.message_id);
  bool decode_error = false;
  if (name) {
    line["message"] = *name;
    const radio::DecodeResult result = radio::DecodePayload(frame.message_id, frame.data);
    if (result.message) {
      line["fields"] = MessageToJson(*result.message);
    } else {
      line["decode_error"] = radio::ToString(result.error);
      line["hex"] = HexString(frame.data);
      decode_error = true;
    }
  } else {
    line["hex"] = HexString(frame.data);
  }
  out << line.dump() << '\n';
  return decode_error;
}

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};

}  // namespace

int RunRadioDecode(const std::vector<std::string>& args) {
  std::string checksum = "crc16";
  std::string path;
  po::options_description options("options");
  options.add_options()(
      "checksum", po::value(&checksum)->default_value(checksum),
      "checksum of the capture's frames: crc16 (fleet link) or xor (seed-compatible)")(
      "input", po::value(&path)->required(), "capture file, or - for standard input");
  po::positional_options_description positional;
  positional.add("input", 1);
  po::variables_map values;
  if (!ParseCommandLine("radio-decode", "[--checksum xor|crc16] FILE|-", options, positional, args,
                        values)) {
    return kExitOk;
  }

  const std::optional<radio::ChecksumMode> mode = radio::ParseChecksumMode(checksum);
  if (mode == radio::ChecksumMode::kSecure) {
    throw UsageError(
        "fireswarm radio-decode: --checksum secure captures are encrypted; radio-decode reads "
        "xor and crc16 captures only");
  }
  if (!mode) {
    throw UsageError("fireswarm radio-decode: --checksum must be 'xor' or 'crc16', not '" +
                     checksum + "'");
  }

  std::unique_ptr<std::FILE, FileCloser> opened;
  std::FILE* input = stdin;
  if (path != "-") {
    opened.reset(std::fopen(path.c_str(), "rb"));
    if (!opened) {
      throw UsageError("fireswarm radio-decode: cannot open '" + path +
                       "': " + std::strerror(errno));
    }
    input = opened.get();
  }

  radio::FrameParser parser(*mode);
  std::uint64_t decode_errors = 0;
  const auto on_frame = [&decode_errors](const radio::FrameView& frame) {
    if (PrintFrame(frame, std::cout)) ++decode_errors;
  };
  std::vector<std::uint8_t> chunk(kReadChunkBytes);
  while (const std::size_t read = std::fread(chunk.data(), 1, chunk.size(), input)) {
    parser.Feed(std::span(chunk.data(), read), on_frame);
  }
  if (std::ferror(input) != 0) {
    throw UsageError("fireswarm radio-decode: cannot read '" + path + "': " + std::strerror(errno));
  }
  parser.Finish(on_frame);

  const radio::ParserStats& stats = parser.stats();
  const Json summary{{"summary",
                      {{"frames", stats.frames},
                       {"bytes", stats.bytes},
                       {"skipped_bytes", stats.skipped_bytes},
                       {"checksum_errors", stats.checksum_errors},
                       {"truncated_frames", stats.truncated_frames},
                       {"decode_errors", decode_errors}}}};
  std::cout << summary.dump() << '\n' << std::flush;
  return kExitOk;
}

}  // namespace fireswarm::app
