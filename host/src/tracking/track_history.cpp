#include "tracking/track_history.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace syncap::tracking {
namespace {

MarkerSample sample_of(const PointObservation& p) {
  MarkerSample s;
  s.position_mm = p.position_mm;
  // a measured point's residual must be > 0 (0 marks an interpolated one in C3D)
  s.residual_mm = std::max(1e-3, std::sqrt(std::max(0.0, p.covariance_mm2.trace()) / 3));
  s.cameras = static_cast<uint32_t>(p.cameras);
  return s;
}

std::string track_label(TrackId id) {
  char label[24];
  std::snprintf(label, sizeof label, "M%03d", static_cast<int>(id));
  return label;
}

}  // namespace

void TrackHistory::add(const TrackedFrame& frame, std::span<const PointObservation> points,
                       std::span<const RigidSetPose> poses) {
  Frame f;
  f.frame = frame.frame;
  for (std::size_t p = 0; p < points.size() && p < frame.ids.size(); ++p) {
    if (frame.ids[p] == kNoTrack) continue;
    f.samples.push_back({frame.ids[p], sample_of(points[p])});
    ++lengths_[frame.ids[p]];
  }
  for (std::size_t s = 0; s < poses.size(); ++s) {
    if (!poses[s].found) continue;
    for (std::size_t m = 0; m < poses[s].ids.size(); ++m) {
      set_markers_.try_emplace(poses[s].ids[m],
                               SetMarker{static_cast<int>(s), static_cast<int>(m)});
    }
  }
  frames_.push_back(std::move(f));
}

MarkerTrajectories to_trajectories(const TrackHistory& history, const std::vector<RigidSet>& sets,
                                   const TrajectoryOptions& options) {
  MarkerTrajectories out;
  out.rate_hz = options.rate_hz;
  if (history.frames().empty()) return out;
  out.first_frame = history.frames().front().frame;
  // column of each set marker, then of each long enough track
  std::map<std::pair<int, int>, int> set_column;
  for (const auto& entry : history.set_markers()) {
    set_column.try_emplace({entry.second.set, entry.second.marker}, 0);
  }
  for (auto& [key, column] : set_column) {
    column = static_cast<int>(out.labels.size());
    out.labels.push_back(sets.at(key.first).markers.at(key.second).name);
  }
  std::map<TrackId, int> column_of;
  for (const auto& [id, sm] : history.set_markers())
    column_of[id] = set_column[{sm.set, sm.marker}];
  for (const auto& [id, length] : history.lengths()) {
    if (column_of.contains(id) || length < options.min_points) continue;
    column_of[id] = static_cast<int>(out.labels.size());
    out.labels.push_back(track_label(id));
  }
  const int64_t rows = history.frames().back().frame - out.first_frame + 1;
  out.samples.assign(rows, std::vector<std::optional<MarkerSample>>(out.labels.size()));
  for (const TrackHistory::Frame& f : history.frames()) {
    auto& row = out.samples[f.frame - out.first_frame];
    for (const TrackHistory::Sample& s : f.samples) {
      const auto column = column_of.find(s.id);
      if (column != column_of.end() && !row[column->second]) row[column->second] = s.sample;
    }
  }
  return out;
}

}  // namespace syncap::tracking
