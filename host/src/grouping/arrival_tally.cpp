#include "grouping/arrival_tally.hpp"

#include <algorithm>
#include <sstream>

namespace syncap::grouping {

const char* state_name(int8_t state) {
  switch (state) {
    case camera_status_t::STATE_IDLE:
      return "idle";
    case camera_status_t::STATE_ACQUIRING:
      return "acquiring";
    case camera_status_t::STATE_ERROR:
      return "error";
    case camera_status_t::STATE_STOPPED:
      return "stopped";
    default:
      return "unknown";
  }
}

void ArrivalTally::add_record(const blob_frame_t& part) {
  if (part.part_index == 0) ++cameras_[part.camera_id].records;
}

void ArrivalTally::add_status(const camera_status_t& status) {
  Camera& camera = cameras_[status.camera_id];
  const bool restarted =
      camera.last_status && status.frames_received < camera.last_status->frames_received;
  if (!camera.last_status || restarted) {
    camera.records_at_baseline = camera.records;
    camera.received_at_baseline = status.frames_received;
  }
  camera.last_status = status;
}

long ArrivalTally::records_here(int camera_id) const {
  const auto it = cameras_.find(camera_id);
  return it == cameras_.end() ? 0 : it->second.records;
}

std::optional<long> ArrivalTally::lost_in_transit(int camera_id) const {
  const auto it = cameras_.find(camera_id);
  if (it == cameras_.end() || !it->second.last_status ||
      it->second.last_status->state != camera_status_t::STATE_STOPPED) {
    return std::nullopt;
  }
  const Camera& c = it->second;
  const long sent = static_cast<long>(c.last_status->frames_received - c.received_at_baseline);
  return std::max(0L, sent - (c.records - c.records_at_baseline));
}

std::string ArrivalTally::summary() const {
  std::ostringstream out;
  for (const auto& [id, camera] : cameras_) {
    if (!camera.last_status) continue;
    const camera_status_t& s = *camera.last_status;
    out << "  camera " << id << " status: " << state_name(s.state) << ", " << s.frames_received
        << " frames received, " << s.frames_lost << " lost, " << camera.records << " here";
    const auto lost = lost_in_transit(id);
    if (lost && *lost > 0) out << " (" << *lost << " lost between edge and host)";
    out << (s.message.empty() ? "" : ", note: " + s.message) << "\n";
  }
  return out.str();
}

}  // namespace syncap::grouping
