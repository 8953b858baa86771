#include "stop_signals.hpp"

namespace fireswarm::app {
namespace {

volatile std::sig_atomic_t stop_requested = 0;

void RequestStop(int /*signal*/) {
  stop_requested = 1;
}

}  // namespace

bool StopRequested() {
  return stop_requested != 0;
}

StopOnSignals::StopOnSignals() {
  stop_requested = 0;
  interrupt_ = std::signal(SIGINT, RequestStop);
  terminate_ = std::signal(SIGTERM, RequestStop);
}

StopOnSignals::~StopOnSignals() {
  std::signal(SIGINT, interrupt_);
  std::signal(SIGTERM, terminate_);
}

}  // namespace fireswarm::app
