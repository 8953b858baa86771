// SIGINT and SIGTERM as a clean stop for the long-running subcommands (vehicle,
// sim, serve): the handler only sets a flag the run loop polls between waits.
#pragma once

#include <csignal>

namespace fireswarm::app {

/// True once SIGINT or SIGTERM arrived while a StopOnSignals was alive.
bool StopRequested();

/// Handles SIGINT and SIGTERM for its lifetime; the previous handlers come back after it.
class StopOnSignals {
 public:
  StopOnSignals();
  ~StopOnSignals();
  StopOnSignals(const StopOnSignals&) = delete;
  StopOnSignals& operator=(const StopOnSignals&) = delete;

 private:
  void (*interrupt_)(int) = SIG_DFL;
  void (*terminate_)(int) = SIG_DFL;
};

}  // namespace fireswarm::app
