#include "air_capture.hpp"

#include <chrono>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <stdexcept>
#include <vector>

#include "fireswarm/common/output_files.hpp"
#include "fireswarm/common/time.hpp"
#include "fireswarm/radio_frame_t.hpp"

namespace fireswarm::app {
namespace {

std::int64_t Micros(common::Nanos t) {
  return std::chrono::duration_cast<std::chrono::microseconds>(t).count();
}

}  // namespace

struct AirCapture::Files {
  std::optional<std::string> raw_path;
  std::optional<std::string> lcm_log_path;
  std::ofstream raw;
  std::unique_ptr<lcm::LogFile> log;
  std::vector<std::uint8_t> encoded;  // reused for every event
  common::OutputFiles output;         // the temporaries, renamed into place by Commit()
};

AirCapture::AirCapture(std::optional<std::string> raw_path, std::optional<std::string> lcm_log_path)
    : files_(std::make_unique<Files>()) {
  files_->raw_path = std::move(raw_path);
  files_->lcm_log_path = std::move(lcm_log_path);
  if (files_->raw_path) {
    files_->raw.open(files_->output.Reserve(*files_->raw_path), std::ios::binary | std::ios::trunc);
    if (!files_->raw) throw std::runtime_error("cannot write capture " + *files_->raw_path);
  }
  if (files_->lcm_log_path) {
    files_->log = std::make_unique<lcm::LogFile>(files_->output.Reserve(*files_->lcm_log_path), "w");
    if (!files_->log->good())
      throw std::runtime_error("cannot write LCM log " + *files_->lcm_log_path);
  }
}

// A run that did not finish leaves no partial files behind: OutputFiles removes them.
AirCapture::~AirCapture() = default;

void AirCapture::Record(const radio::AirRecord& record) {
  if (files_->raw_path && !record.collided) {
    files_->raw.write(reinterpret_cast<const char*>(record.bytes.data()),
                      static_cast<std::streamsize>(record.bytes.size()));
  }
  if (!files_->log) return;
  radio_frame_t frame{};
  // Stamped with the end of the transmission, when receivers have it: records arrive
  // in order of end, so the log's timestamps never go backwards (lcm-logplayer needs that).
  frame.utime = Micros(record.end);
  frame.transmitter_radio = static_cast<std::int32_t>(record.transmitter);
  // In a bench or scenario run, radio 0 is the server and radio i the vehicle with ID i.
  frame.transmitter_receiver_id = static_cast<std::int16_t>(record.transmitter);
  frame.start_us = Micros(record.start);
  frame.end_us = Micros(record.end);
  frame.collided = record.collided;
  frame.byte_count = static_cast<std::int32_t>(record.bytes.size());
  frame.bytes.assign(record.bytes.begin(), record.bytes.end());
  files_->encoded.resize(static_cast<std::size_t>(frame.getEncodedSize()));
  frame.encode(files_->encoded.data(), 0, static_cast<int>(files_->encoded.size()));

  lcm::LogEvent event{};
  event.eventnum = 0;  // assigned by the log writer
  event.timestamp = frame.utime;
  event.channel = kAirLcmChannel;
  event.datalen = static_cast<std::int32_t>(files_->encoded.size());
  event.data = files_->encoded.data();
  if (files_->log->writeEvent(&event) != 0) {
    throw std::runtime_error("cannot write LCM log " + *files_->lcm_log_path);
  }
}

void AirCapture::Commit() {
  if (files_->raw_path) {
    files_->raw.close();
    if (!files_->raw) throw std::runtime_error("cannot finish capture " + *files_->raw_path);
  }
  files_->log.reset();  // closes the file
  files_->output.Commit();
}

}  // namespace fireswarm::app
