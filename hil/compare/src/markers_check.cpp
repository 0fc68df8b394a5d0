#include "markers_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>

#include "csv_reader.hpp"

namespace syncap::compare {
namespace {

// Targets of `frame` that two or more cameras see.
std::vector<int> visible_targets(const Truth& truth, long frame) {
  std::map<int, int> views;
  for (const auto& [id, size] : truth.images) {
    const auto it = truth.projections.find({frame, id});
    if (it == truth.projections.end()) continue;
    for (const Projection& p : it->second) views[p.target] += p.visible;
  }
  std::vector<int> out;
  for (const auto& [target, n] : views)
    if (n >= 2) out.push_back(target);
  return out;
}

double distance(const Marker& m, const std::array<double, 3>& t) {
  return std::hypot(m.x - t[0], m.y - t[1], m.z - t[2]);
}

// Which trajectory id each target was last found with, and which target each id last meant.
struct IdHistory {
  std::map<int, long> id_of_target;
  std::map<long, int> target_of_id;
  void clear() { id_of_target.clear(), target_of_id.clear(); }
  // A target found under another id than before: a switch when that id meant another target
  // (two trajectories exchanged their markers), else a break (a new trajectory for it).
  void see(int target, long id, MarkersCheck& c) {
    const auto [last, first_time] = id_of_target.try_emplace(target, id);
    if (!first_time && last->second != id) {
      const auto owner = target_of_id.find(id);
      if (owner != target_of_id.end() && owner->second != target) {
        ++c.id_switches;
      } else {
        ++c.track_breaks;
      }
    }
    last->second = id;
    target_of_id[id] = target;
  }
};

// One frame: pairs within the radius, nearest first, each marker and target used once.
void check_frame(const std::vector<Marker>& markers, const std::vector<int>& targets,
                 const std::map<int, std::array<double, 3>>& positions, double radius,
                 IdHistory& ids, MarkersCheck& c) {
  std::vector<std::tuple<double, std::size_t, int>> pairs;
  for (std::size_t m = 0; m < markers.size(); ++m) {
    for (const auto& [target, position] : positions) {
      const double d = distance(markers[m], position);
      if (d <= radius) pairs.emplace_back(d, m, target);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<bool> marker_used(markers.size(), false);
  std::map<int, bool> target_used;
  for (const auto& [d, m, target] : pairs) {
    if (marker_used[m] || target_used[target]) continue;
    marker_used[m] = target_used[target] = true;
    if (std::find(targets.begin(), targets.end(), target) != targets.end()) {
      ++c.found;
      c.squared_error_sum += d * d;
    }
    if (markers[m].id >= 0) ids.see(target, markers[m].id, c);
  }
  c.visible_targets += static_cast<long>(targets.size());
  c.markers += static_cast<long>(markers.size());
  c.ghosts += static_cast<long>(std::count(marker_used.begin(), marker_used.end(), false));
  for (const Marker& m : markers) c.two_camera_markers += m.cameras == 2;
}

}  // namespace

double MarkersCheck::found_share() const {
  return visible_targets > 0 ? static_cast<double>(found) / static_cast<double>(visible_targets)
                             : 1.0;
}

double MarkersCheck::ghost_share() const {
  return markers > 0 ? static_cast<double>(ghosts) / static_cast<double>(markers) : 0.0;
}

double MarkersCheck::per_1000_found(long count) const {
  return found > 0 ? 1000.0 * static_cast<double>(count) / static_cast<double>(found) : 0.0;
}

double MarkersCheck::id_switches_per_1000() const { return per_1000_found(id_switches); }

double MarkersCheck::track_breaks_per_1000() const { return per_1000_found(track_breaks); }

double MarkersCheck::rms_mm() const {
  return found > 0 ? std::sqrt(squared_error_sum / static_cast<double>(found)) : 0.0;
}

void move_markers(std::vector<Group>& groups, const Similarity& motion) {
  for (Group& g : groups) {
    if (!g.markers) continue;
    for (Marker& m : *g.markers) {
      const Eigen::Vector3d moved = motion.apply({m.x, m.y, m.z});
      m.x = moved.x(), m.y = moved.y(), m.z = moved.z();
    }
  }
}

TruePositions read_true_positions(const std::filesystem::path& targets_csv) {
  TruePositions positions;
  read_csv(targets_csv, {"frame", "target", "X_mm", "Y_mm", "Z_mm", "radius_mm"},
           [&](const CsvRow& row) {
             positions[static_cast<long>(row.number(0))][static_cast<int>(row.number(1))] = {
                 row.number(2), row.number(3), row.number(4)};
           });
  return positions;
}

MarkersCheck check_markers(const Truth& truth, const TruePositions& positions,
                           const std::vector<Group>& groups, double match_radius_mm) {
  MarkersCheck c;
  static const std::map<int, std::array<double, 3>> kNone;
  IdHistory ids;  // within a phase (each phase numbers its own targets)
  int phase = -1;
  for (const Group& g : groups) {
    if (!g.markers) continue;
    ++c.frames;
    const auto frame = truth.frames.find(g.frame);
    const int frame_phase = frame == truth.frames.end() ? -1 : frame->second.phase;
    if (frame_phase != phase) ids.clear(), phase = frame_phase;
    const auto it = positions.find(g.frame);
    check_frame(*g.markers, visible_targets(truth, g.frame),
                it == positions.end() ? kNone : it->second, match_radius_mm, ids, c);
  }
  return c;
}

std::string format_markers_check(const MarkersCheck& c) {
  char line[480];
  std::snprintf(line, sizeof line,
                "markers: %ld frames, %ld of %ld visible targets found (%.2f %%), %ld ghosts of "
                "%ld markers (%.2f %%), 3D RMS %.3f mm, %ld seen by two cameras only, %ld id "
                "switches (%.2f per 1000 found), %ld track breaks (%.2f per 1000 found)\n",
                c.frames, c.found, c.visible_targets, 100 * c.found_share(), c.ghosts, c.markers,
                100 * c.ghost_share(), c.rms_mm(), c.two_camera_markers, c.id_switches,
                c.id_switches_per_1000(), c.track_breaks, c.track_breaks_per_1000());
  return line;
}

}  // namespace syncap::compare
