#include "markers_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>

#include "csv_reader.hpp"
#include "geometry/triangulation.hpp"
#include "matcher.hpp"
#include "util/printf_string.hpp"

namespace syncap::compare {
namespace {

// The image noise the reference's rays are weighed with: every ray gets the same one, so the point
// does not depend on it (the weights differ by the distances only, as the host's).
constexpr double kSigmaPx = 0.2;

// A whole view of a target: the blob the image comparison paired with it, and its true pixel.
struct WholeView {
  int camera = 0;
  Eigen::Vector2d blob, truth;
};

// Every target's whole views in the group's frame: the cameras whose message arrived, that the
// truth has a camera model for, where the target's spot is whole and a blob was paired with it.
std::map<int, std::vector<WholeView>> whole_views(const Truth& truth, const Group& g,
                                                  double blob_radius_px) {
  std::map<int, std::vector<WholeView>> views;
  for (const auto& [id, camera] : g.cameras) {
    const auto targets = truth.projections.find({g.frame, id});
    const auto image = truth.images.find(id);
    if (targets == truth.projections.end() || image == truth.images.end() ||
        !truth.cameras.contains(id))
      continue;
    const std::vector<Projection>& list = targets->second;
    std::vector<Eigen::Vector2d> blobs;
    for (const Blob& b : camera.blobs) blobs.emplace_back(b.x, b.y);
    std::vector<std::size_t> visible;
    const Matching m = match_visible(list, blobs, blob_radius_px, visible);
    for (const Match& match : m.matches) {
      const std::size_t t = visible[match.target];
      if (!whole_view(list, t, image->second)) continue;
      const Projection& p = list[t];
      views[p.target].push_back({id, blobs[match.blob], {p.x_px, p.y_px}});
    }
  }
  return views;
}

// The found target's reference: its whole views triangulated through the true cameras, the error
// against its true position, beside the host's `host_error_mm`.
void add_reference(const Truth& truth, const std::vector<WholeView>* views,
                   const std::array<double, 3>& position, double host_error_mm,
                   WholeViewReference& r) {
  if (views == nullptr || views->size() < 2) {
    ++r.without;
    return;
  }
  std::vector<geometry::ViewRay> rays;
  for (const WholeView& v : *views) {
    rays.push_back(geometry::view_ray(truth.cameras.at(v.camera), v.blob));
  }
  const geometry::RayPoint point = geometry::triangulate(rays, kSigmaPx);
  if (!point.ok) {
    ++r.without;
    return;
  }
  ++r.targets;
  r.squared_error_sum +=
      (point.position - Eigen::Vector3d(position[0], position[1], position[2])).squaredNorm();
  r.host_squared_error_sum += host_error_mm * host_error_mm;
  for (const WholeView& v : *views) {
    ++r.views;
    r.view_squared_error_sum += (v.blob - v.truth).squaredNorm();
  }
}

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
// A found target gets its reference from `views` (whole_views of the frame).
void check_frame(const Truth& truth, const std::vector<Marker>& markers,
                 const std::vector<int>& targets,
                 const std::map<int, std::array<double, 3>>& positions,
                 const std::map<int, std::vector<WholeView>>& views, double radius, IdHistory& ids,
                 MarkersCheck& c) {
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
      const auto v = views.find(target);
      add_reference(truth, v == views.end() ? nullptr : &v->second, positions.at(target), d,
                    c.reference);
    }
    if (markers[m].id >= 0) ids.see(target, markers[m].id, c);
  }
  c.visible_targets += static_cast<long>(targets.size());
  c.markers += static_cast<long>(markers.size());
  c.ghosts += static_cast<long>(std::count(marker_used.begin(), marker_used.end(), false));
  for (const Marker& m : markers) c.two_camera_markers += m.cameras == 2;
}

}  // namespace

bool whole_view(const std::vector<Projection>& targets, std::size_t target,
                const ImageSize& image) {
  const Projection& p = targets[target];
  if (classify(p, image) != TargetClass::counted) return false;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const Projection& q = targets[i];
    if (i == target || q.radius_px <= 0) continue;  // radius 0: behind the camera, no disc
    if (std::hypot(q.x_px - p.x_px, q.y_px - p.y_px) <= p.radius_px + q.radius_px + 1) return false;
  }
  return true;
}

namespace {
std::optional<double> rms(double squared_sum, long count) {
  if (count <= 0) return std::nullopt;
  return std::sqrt(squared_sum / static_cast<double>(count));
}
}  // namespace

std::optional<double> WholeViewReference::rms_mm() const { return rms(squared_error_sum, targets); }

std::optional<double> WholeViewReference::host_rms_mm() const {
  return rms(host_squared_error_sum, targets);
}

std::optional<double> WholeViewReference::ratio() const {
  const auto reference = rms_mm(), host = host_rms_mm();
  if (!reference || !host || *reference <= 0) return std::nullopt;
  return *host / *reference;
}

std::optional<double> WholeViewReference::view_rms_px() const {
  return rms(view_squared_error_sum, views);
}

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
                           const std::vector<Group>& groups, double match_radius_mm,
                           double blob_radius_px) {
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
    check_frame(truth, *g.markers, visible_targets(truth, g.frame),
                it == positions.end() ? kNone : it->second, whole_views(truth, g, blob_radius_px),
                match_radius_mm, ids, c);
  }
  return c;
}

namespace {

// "best estimator on the same whole views 0.19 mm (the host 0.20 mm on those 2960 targets, ratio
// 1.05; 10 with fewer than 2 whole views; their 9120 blobs' 2D RMS 0.070 px)".
std::string format_reference(const WholeViewReference& r) {
  const auto rms = r.rms_mm(), host = r.host_rms_mm(), ratio = r.ratio(), view = r.view_rms_px();
  if (!rms || !host || !view) {
    return util::printf_string(
        "best estimator on the same whole views - (0 targets; %ld with fewer than 2 whole views)",
        r.without);
  }
  const std::string ratio_text = ratio ? util::printf_string("%.2f", *ratio) : "-";
  return util::printf_string(
      "best estimator on the same whole views %.3f mm (the host %.3f mm on those %ld targets, "
      "ratio %s; %ld with fewer than 2 whole views; their %ld blobs' 2D RMS %.3f px)",
      *rms, *host, r.targets, ratio_text.c_str(), r.without, r.views, *view);
}

nlohmann::ordered_json optional_number(std::optional<double> value) {
  return value ? nlohmann::ordered_json(*value) : nlohmann::ordered_json(nullptr);
}

}  // namespace

std::string format_markers_check(const MarkersCheck& c) {
  return util::printf_string(
      "markers: %ld frames, %ld of %ld visible targets found (%.2f %%), %ld ghosts of %ld markers "
      "(%.2f %%), 3D RMS %.3f mm, %s, %ld seen by two cameras only, %ld id switches (%.2f per "
      "1000 found), %ld track breaks (%.2f per 1000 found)\n",
      c.frames, c.found, c.visible_targets, 100 * c.found_share(), c.ghosts, c.markers,
      100 * c.ghost_share(), c.rms_mm(), format_reference(c.reference).c_str(),
      c.two_camera_markers, c.id_switches, c.id_switches_per_1000(), c.track_breaks,
      c.track_breaks_per_1000());
}

nlohmann::ordered_json markers_json(const MarkersCheck& c) {
  const WholeViewReference& r = c.reference;
  return {{"frames", c.frames},
          {"visible_targets", c.visible_targets},
          {"found", c.found},
          {"found_share", c.found_share()},
          {"markers", c.markers},
          {"ghosts", c.ghosts},
          {"ghost_share", c.ghost_share()},
          {"rms_mm",
           c.found > 0 ? nlohmann::ordered_json(c.rms_mm()) : nlohmann::ordered_json(nullptr)},
          {"two_camera_markers", c.two_camera_markers},
          {"id_switches", c.id_switches},
          {"track_breaks", c.track_breaks},
          {"reference_rms_mm", optional_number(r.rms_mm())},
          {"host_rms_on_reference_mm", optional_number(r.host_rms_mm())},
          {"rms_over_reference", optional_number(r.ratio())},
          {"reference_targets", r.targets},
          {"targets_without_reference", r.without},
          {"reference_views", r.views},
          {"reference_view_rms_px", optional_number(r.view_rms_px())}};
}

}  // namespace syncap::compare
