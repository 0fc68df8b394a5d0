// What reached the host from each camera, beside what its edge says it sent.
//
// An edge counts the frames it processed (camera_status_t.frames_received) and publishes one
// frame record (blob_frame_t part 0) for each, before any status that counts it. Between the
// first status this host saw from a camera and its final one (STATE_STOPPED) the edge therefore
// sent (final - first) records: fewer arriving after that first status were lost between edge
// and host (the edge's publishing queue, the network, or a receiver that could not keep up). The
// first status is the baseline because edges run before the host starts, often for hours; an
// edge that restarted (its count went down) starts a new baseline.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "syncap/blob_frame_t.hpp"
#include "syncap/camera_status_t.hpp"

namespace syncap::grouping {

// camera_status_t's state as a word: "idle", "acquiring", "error", "stopped" ("unknown").
const char* state_name(int8_t state);

class ArrivalTally {
 public:
  void add_record(const blob_frame_t& part);  // counts part 0s only
  void add_status(const camera_status_t& status);

  long records_here(int camera_id) const;  // all of the camera's records that arrived
  // Records the edge sent after the baseline status and before its final one that never arrived;
  // nothing before the final status.
  std::optional<long> lost_in_transit(int camera_id) const;
  // One line per camera that sent a status, by id: "camera 5 status: stopped, 90 frames
  // received, 0 lost, 89 here (1 lost between edge and host), note: ...".
  std::string summary() const;

 private:
  struct Camera {
    long records = 0;                  // all that arrived
    long records_at_baseline = 0;      // of them, those that arrived before the baseline status
    int64_t received_at_baseline = 0;  // the edge's count in the baseline status
    std::optional<camera_status_t> last_status;
  };
  std::map<int, Camera> cameras_;
};

}  // namespace syncap::grouping
