// Ctrl-C and SIGTERM as a request to end a subcommand's listening loop (syncap calibrate's live
// collection, syncap record): while a StopRequest lives, both signals set its flag instead of
// ending the program; the previous handlers come back when it ends. One at a time: the flag is
// the process's.
#pragma once

#include <csignal>

namespace syncap::tools {

class StopRequest {
 public:
  StopRequest() {
    requested_ = 0;
    previous_int_ = std::signal(SIGINT, on_signal);
    previous_term_ = std::signal(SIGTERM, on_signal);
  }
  ~StopRequest() {
    std::signal(SIGINT, previous_int_);
    std::signal(SIGTERM, previous_term_);
  }
  StopRequest(const StopRequest&) = delete;
  StopRequest& operator=(const StopRequest&) = delete;

  bool requested() const { return requested_ != 0; }

 private:
  static void on_signal(int) { requested_ = 1; }

  static inline volatile std::sig_atomic_t requested_ = 0;
  void (*previous_int_)(int) = nullptr;
  void (*previous_term_)(int) = nullptr;
};

}  // namespace syncap::tools
