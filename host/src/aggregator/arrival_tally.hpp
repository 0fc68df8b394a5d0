// What reached the host from each camera, beside what its edge says it sent.
//
// An edge's camera_status_t counts the frames it processed, and it publishes one frame record
// (blob_frame_t part 0) for each. Its final status (STATE_STOPPED) therefore says how many
// records left the board: fewer here were lost between edge and host (the edge's publishing
// queue, the network, or a receiver that could not keep up). Earlier statuses are heartbeats,
// older than the records that follow them, and prove nothing.
#pragma once

#include <map>
#include <optional>
#include <string>

#include "syncap/blob_frame_t.hpp"
#include "syncap/camera_status_t.hpp"

namespace syncap::host {

class ArrivalTally {
 public:
  void add_record(const blob_frame_t& part);  // counts part 0s only
  void add_status(const camera_status_t& status);

  long records_here(int camera_id) const;
  // Records the camera's final status counts and this host never saw; nothing before that status.
  std::optional<long> lost_in_transit(int camera_id) const;
  // One line per camera that sent a status, by id: "camera 5 status: stopped, 90 frames
  // received, 0 lost, 89 here (1 lost between edge and host), note: ...".
  std::string summary() const;

 private:
  std::map<int, long> records_;
  std::map<int, camera_status_t> status_;
};

}  // namespace syncap::host
