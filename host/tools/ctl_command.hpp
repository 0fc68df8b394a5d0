// syncap ctl: sends the edges a signed command (start, stop, train the background, thresholds,
// ROI, exposure, gain, shutdown) and shows each camera's acknowledgement from its heartbeats.
// syncap keygen: creates the installation's command key. docs/design/security.md.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <ostream>
#include <span>
#include <string>

#include "syncap/camera_status_t.hpp"
#include "syncap/edge_command_t.hpp"

namespace syncap::tools {

int ctl_command(std::span<const std::string> args, std::ostream& out, std::ostream& err);
int keygen_command(std::span<const std::string> args, std::ostream& out, std::ostream& err);

// The command a `syncap ctl` action names ("threshold", {"40"}); std::invalid_argument with the
// reason for an unknown action or a bad value. camera_id, sender, sequence and MAC are left.
edge_command_t command_of_action(const std::string& action, std::span<const std::string> values);

// What the heartbeats said about one sent command, camera by camera.
class Acknowledgements {
 public:
  Acknowledgements(int64_t sender, int64_t sequence) : sender_(sender), sequence_(sequence) {}
  // Takes one heartbeat; true when it answered the command (accepted or refused).
  bool take(const camera_status_t& status);
  // A camera's answer: camera_status_t::COMMAND_*, or nothing while it has not answered.
  std::optional<int8_t> answer(int camera_id) const;
  // Every camera heard from, with its last heartbeat.
  const std::map<int, camera_status_t>& heard() const { return heard_; }

 private:
  int64_t sender_;
  int64_t sequence_;
  std::map<int, camera_status_t> heard_;
  std::map<int, int8_t> answers_;
};

}  // namespace syncap::tools
