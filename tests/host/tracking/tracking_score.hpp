// The tracker's ids scored against the truth of a test::Motion (synthetic_motion.hpp): per marker
// seen, whether its id changed since it was last seen, and whether it changed to an id that last
// meant another marker (an exchange) or not (a break: a new id, or one it had itself before), as
// syncap-hil-compare scores them (hil/compare/src/markers_check.hpp).
#pragma once

#include <array>
#include <cstdio>
#include <map>
#include <vector>

#include "synthetic_motion.hpp"
#include "tracking/marker_tracker.hpp"

namespace syncap::tracking {

struct Score {
  long marker_frames = 0;  // markers seen
  long unlabelled = 0;     // of them given no id
  long switches = 0;       // a marker's id differs from its previous one
  long breaks = 0;         // of the switches, to an id that last meant no other marker
  long occlusions = 0;     // gaps of <= max_missed_frames between two seen frames
  long bridged = 0;        // of them, the same id on both sides
  // Switches by the frames since the marker was last seen (1: seen in the frame before; the
  // last counts all of 7 and more): a switch after an occlusion or on a marker in full view.
  std::array<long, 8> switches_after_gap{};
  double switches_per_1000() const { return 1000.0 * switches / marker_frames; }
  double breaks_per_1000() const { return 1000.0 * breaks / marker_frames; }
  // Switches to an id that meant another marker.
  double exchanges_per_1000() const { return 1000.0 * (switches - breaks) / marker_frames; }
};

// Runs the tracker over the motion and scores its ids against the truth.
inline Score track_and_score(const test::Motion& motion, const TrackerOptions& options,
                             TrackerCounters* counters = nullptr) {
  MarkerTracker tracker(options);
  Score score;
  std::vector<std::vector<TrackId>> id_of(motion.frames.size());  // [frame][marker]
  std::map<int, TrackId> last_id;
  std::map<int, int64_t> last_seen;
  std::map<TrackId, int> meant;  // the marker an id last meant
  for (const test::MotionFrame& f : motion.frames) {
    const TrackedFrame& out = tracker.update(f.frame, f.time_s, f.points);
    id_of[f.frame].assign(motion.truth[f.frame].size(), kNoTrack);
    for (std::size_t p = 0; p < f.points.size(); ++p) {
      const int m = f.marker_of_point[p];
      if (m < 0) continue;
      ++score.marker_frames;
      id_of[f.frame][m] = out.ids[p];
      if (out.ids[p] == kNoTrack) {
        ++score.unlabelled;
        continue;
      }
      if (last_id.contains(m) && last_id[m] != out.ids[p]) {
        ++score.switches;
        ++score.switches_after_gap[std::min<int64_t>(7, f.frame - last_seen[m])];
        const auto owner = meant.find(out.ids[p]);
        score.breaks += owner == meant.end() || owner->second == m;
      }
      last_id[m] = out.ids[p];
      last_seen[m] = f.frame;
      meant[out.ids[p]] = m;
    }
  }
  for (const test::Occlusion& o : motion.occlusions) {
    if (o.length > options.max_missed_frames) continue;
    ++score.occlusions;
    const TrackId before = id_of[o.first_hidden - 1][o.marker];
    score.bridged += before != kNoTrack && before == id_of[o.first_hidden + o.length][o.marker];
  }
  if (counters) *counters = tracker.counters();
  return score;
}

}  // namespace syncap::tracking
