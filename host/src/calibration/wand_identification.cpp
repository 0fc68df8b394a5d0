#include "calibration/wand_identification.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "syncap/blob_t.hpp"

namespace syncap::calibration {
namespace {

enum class Outcome { kIdentified, kMissing, kAmbiguous };

// The spots of one image assigned to targets (indices into the image's spots, in target order).
struct Assignment {
  Outcome outcome = Outcome::kMissing;
  std::vector<int> spots;
};

Eigen::Vector2d at(const Spot& s) { return {s.x, s.y}; }

Assignment identified(std::vector<int> spots) { return {Outcome::kIdentified, std::move(spots)}; }
Assignment missing() { return {Outcome::kMissing, {}}; }
Assignment ambiguous() { return {Outcome::kAmbiguous, {}}; }

// Spots already labelled by the source: one per target index.
Assignment labelled(const std::vector<Spot>& spots, int targets) {
  std::vector<int> index(static_cast<size_t>(targets), -1);
  for (int i = 0; i < static_cast<int>(spots.size()); ++i) {
    const int t = spots[static_cast<size_t>(i)].target;
    if (t >= targets) return ambiguous();
    if (index[static_cast<size_t>(t)] >= 0) return ambiguous();
    index[static_cast<size_t>(t)] = i;
  }
  // Targets not seen stay -1 and are left out later.
  return identified(index);
}

// Tells the two ends of a wand apart; `a`, `b` are spot indices, `previous` the camera's
// identified ends in the frame before (when it has them).
class EndResolver {
 public:
  EndResolver(const WandSpec& wand, const IdentificationOptions& options)
      : wand_(wand), options_(options) {}

  // {A, B}, or nothing when the ends cannot be told apart.
  std::optional<std::pair<int, int>> resolve(
      const std::vector<Spot>& spots, int a, int b,
      const std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& previous) const {
    const Spot& sa = spots[static_cast<size_t>(a)];
    const Spot& sb = spots[static_cast<size_t>(b)];
    if (wand_.ends == EndIdentity::kSize) {
      const double larger = std::max(sa.area, sb.area);
      if (!(larger > 0) || std::abs(sa.area - sb.area) < options_.size_margin * larger) {
        return std::nullopt;
      }
      return sa.area > sb.area ? std::make_pair(a, b) : std::make_pair(b, a);
    }
    if (!previous) return sa.y <= sb.y ? std::make_pair(a, b) : std::make_pair(b, a);
    const auto [pa, pb] = *previous;
    const double keep = (at(sa) - pa).norm() + (at(sb) - pb).norm();
    const double swap = (at(sa) - pb).norm() + (at(sb) - pa).norm();
    const double gate = options_.continuity_gate * (pa - pb).norm();
    if (std::min(keep, swap) > 2.0 * gate) return std::nullopt;  // the wand jumped: lost track
    if (std::abs(keep - swap) < 0.5 * gate) return std::nullopt;
    return keep < swap ? std::make_pair(a, b) : std::make_pair(b, a);
  }

 private:
  const WandSpec& wand_;
  const IdentificationOptions& options_;
};

class ImageIdentifier {
 public:
  ImageIdentifier(const WandSpec& wand, const IdentificationOptions& options)
      : wand_(wand), options_(options), ends_(wand, options) {}

  Assignment identify(
      const std::vector<Spot>& spots,
      const std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& previous) const {
    const int n = static_cast<int>(spots.size());
    const bool labelled_input =
        !spots.empty() &&
        std::all_of(spots.begin(), spots.end(), [](const Spot& s) { return s.target >= 0; });
    if (labelled_input) return labelled(spots, wand_.point_count());
    if (wand_.led) {
      if (n == 0) return missing();
      return n == 1 ? identified({0}) : ambiguous();
    }
    if (n < wand_.targets) return missing();
    if (n > options_.max_spots) return ambiguous();
    if (wand_.targets == 2) return two_targets(spots, previous);
    return three_targets(spots, previous);
  }

 private:
  bool symmetric() const { return std::abs(wand_.middle_ratio - 0.5) < options_.ratio_tolerance; }

  Assignment two_targets(
      const std::vector<Spot>& spots,
      const std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& previous) const {
    const int n = static_cast<int>(spots.size());
    if (n == 2) {
      if (!long_enough(spots, 0, 1)) return missing();
      const auto ends = ends_.resolve(spots, 0, 1, previous);
      if (!ends) return ambiguous();
      return identified({ends->first, ends->second});
    }
    // More spots than targets: only continuity can choose.
    if (wand_.ends != EndIdentity::kContinuity || !previous) return ambiguous();
    const auto nearest = [&](const Eigen::Vector2d& p) {
      int best = -1;
      double best_d = 0;
      for (int i = 0; i < n; ++i) {
        const double d = (at(spots[static_cast<size_t>(i)]) - p).norm();
        if (best < 0 || d < best_d) best = i, best_d = d;
      }
      return std::make_pair(best, best_d);
    };
    const auto [a, da] = nearest(previous->first);
    const auto [b, db] = nearest(previous->second);
    const double gate = options_.continuity_gate * (previous->first - previous->second).norm();
    if (a == b || da > gate || db > gate) return ambiguous();
    return identified({a, b});
  }

  Assignment three_targets(
      const std::vector<Spot>& spots,
      const std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& previous) const {
    const int n = static_cast<int>(spots.size());
    std::vector<std::vector<int>> candidates;  // {A, middle, B}
    for (int i = 0; i < n; ++i) {
      for (int j = i + 1; j < n; ++j) {
        for (int k = j + 1; k < n; ++k) {
          if (auto wand = as_wand(spots, i, j, k, previous)) candidates.push_back(*wand);
          if (candidates.size() > 1) return ambiguous();
        }
      }
    }
    if (candidates.empty()) return missing();
    return identified(candidates[0]);
  }

  bool long_enough(const std::vector<Spot>& spots, int a, int b) const {
    return (at(spots[static_cast<size_t>(a)]) - at(spots[static_cast<size_t>(b)])).norm() >=
           options_.min_length_px;
  }

  // The triple as {A, middle, B} when it looks like the wand.
  std::optional<std::vector<int>> as_wand(
      const std::vector<Spot>& spots, int i, int j, int k,
      const std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& previous) const {
    // The ends are the two spots farthest apart.
    const auto dist = [&](int a, int b) {
      return (at(spots[static_cast<size_t>(a)]) - at(spots[static_cast<size_t>(b)])).norm();
    };
    int e1 = i, e2 = j, m = k;
    double longest = dist(i, j);
    for (const auto& [a, b, c] : {std::array<int, 3>{i, k, j}, std::array<int, 3>{j, k, i}}) {
      if (dist(a, b) > longest) longest = dist(a, b), e1 = a, e2 = b, m = c;
    }
    if (longest < options_.min_length_px) return std::nullopt;
    const Eigen::Vector2d p1 = at(spots[static_cast<size_t>(e1)]);
    const Eigen::Vector2d p2 = at(spots[static_cast<size_t>(e2)]);
    const Eigen::Vector2d pm = at(spots[static_cast<size_t>(m)]);
    const Eigen::Vector2d axis = (p2 - p1) / longest;
    const double off_line = std::abs(axis.x() * (pm - p1).y() - axis.y() * (pm - p1).x());
    if (off_line > options_.collinearity_px + options_.collinearity_fraction * longest) {
      return std::nullopt;
    }
    const double t = axis.dot(pm - p1) / longest;  // 0 at e1, 1 at e2
    if (symmetric()) {
      if (std::abs(t - 0.5) > options_.ratio_tolerance) return std::nullopt;
      const auto ends = ends_.resolve(spots, e1, e2, previous);
      if (!ends) return std::nullopt;
      return std::vector<int>{ends->first, m, ends->second};
    }
    const double r = wand_.middle_ratio;
    if (std::abs(t - r) <= options_.ratio_tolerance) return std::vector<int>{e1, m, e2};
    if (std::abs(t - (1.0 - r)) <= options_.ratio_tolerance) return std::vector<int>{e2, m, e1};
    return std::nullopt;
  }

  const WandSpec& wand_;
  const IdentificationOptions& options_;
  EndResolver ends_;
};

}  // namespace

std::vector<double> WandSpec::offsets_mm() const {
  if (led) return {0.0};
  if (targets == 2) return {0.0, length_mm};
  return {0.0, middle_ratio * length_mm, length_mm};
}

long Identification::rejected_frames() const {
  long n = 0;
  for (const auto& [id, stats] : cameras) n += stats.ambiguous;
  return n;
}

namespace {

// A spot that touches the image's border is not measured whole (the edge flags it); one whose
// centre lies outside the image (pixel centres at 0 .. size - 1) is no detection at all: a
// corrupt record. Neither is used.
bool measurable(const Spot& spot, const Observations& observations, int camera) {
  if (spot.flags & blob_t::FLAG_AT_BORDER) return false;
  const auto size = observations.image_sizes.find(camera);
  if (size == observations.image_sizes.end() || size->second.width <= 0) return true;
  return spot.x >= -0.5 && spot.y >= -0.5 && spot.x <= size->second.width - 0.5 &&
         spot.y <= size->second.height - 0.5;
}

}  // namespace

Identification identify_targets(const Observations& observations, const WandSpec& wand,
                                const IdentificationOptions& options) {
  const ImageIdentifier identifier(wand, options);
  Identification result;
  // The ends of each camera's last identified frame, for continuity.
  std::map<int, std::pair<int64_t, std::pair<Eigen::Vector2d, Eigen::Vector2d>>> last_ends;
  for (const auto& [frame, cameras] : observations.frames) {
    for (const auto& [camera, spots] : cameras) {
      CameraIdentificationStats& stats = result.cameras[camera];
      ++stats.frames;
      std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>> previous;
      const auto last = last_ends.find(camera);
      if (last != last_ends.end() && last->second.first == frame - 1)
        previous = last->second.second;
      const Assignment assignment = identifier.identify(spots, previous);
      if (assignment.outcome == Outcome::kMissing) ++stats.missing;
      if (assignment.outcome == Outcome::kAmbiguous) ++stats.ambiguous;
      if (assignment.outcome != Outcome::kIdentified) continue;
      ++stats.identified;
      TargetPositions positions(assignment.spots.size());
      for (size_t t = 0; t < assignment.spots.size(); ++t) {
        const int s = assignment.spots[t];
        if (s < 0) continue;
        const Spot& spot = spots[static_cast<size_t>(s)];
        if (!measurable(spot, observations, camera)) {
          ++stats.at_border;
          continue;
        }
        positions[t] = at(spot);
      }
      if (!wand.led && assignment.spots.size() >= 2 && assignment.spots.front() >= 0 &&
          assignment.spots.back() >= 0) {
        last_ends[camera] = {frame,
                             {at(spots[static_cast<size_t>(assignment.spots.front())]),
                              at(spots[static_cast<size_t>(assignment.spots.back())])}};
      }
      result.frames[frame][camera] = std::move(positions);
    }
  }
  return result;
}

std::string format_identification(const Identification& identification) {
  std::ostringstream out;
  for (const auto& [camera, s] : identification.cameras) {
    out << "camera " << camera << ": " << s.frames << " frames, " << s.identified << " identified, "
        << s.missing << " missing, " << s.ambiguous << " ambiguous, " << s.at_border
        << " targets at the border\n";
  }
  return out.str();
}

}  // namespace syncap::calibration
