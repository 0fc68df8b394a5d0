#include "aggregator/arrival_tally.hpp"

#include <sstream>

namespace syncap::host {
namespace {

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

}  // namespace

void ArrivalTally::add_record(const blob_frame_t& part) {
  if (part.part_index == 0) ++records_[part.camera_id];
}

void ArrivalTally::add_status(const camera_status_t& status) { status_[status.camera_id] = status; }

long ArrivalTally::records_here(int camera_id) const {
  const auto it = records_.find(camera_id);
  return it == records_.end() ? 0 : it->second;
}

std::optional<long> ArrivalTally::lost_in_transit(int camera_id) const {
  const auto it = status_.find(camera_id);
  if (it == status_.end() || it->second.state != camera_status_t::STATE_STOPPED) return {};
  return std::max(0L, static_cast<long>(it->second.frames_received) - records_here(camera_id));
}

std::string ArrivalTally::summary() const {
  std::ostringstream out;
  for (const auto& [id, s] : status_) {
    out << "  camera " << id << " status: " << state_name(s.state) << ", " << s.frames_received
        << " frames received, " << s.frames_lost << " lost, " << records_here(id) << " here";
    const auto lost = lost_in_transit(id);
    if (lost && *lost > 0) out << " (" << *lost << " lost between edge and host)";
    out << (s.message.empty() ? "" : ", note: " + s.message) << "\n";
  }
  return out.str();
}

}  // namespace syncap::host
