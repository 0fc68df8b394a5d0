#include "surface/surface_matcher.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>

namespace syncap::surface {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// A seed: a hull point seen best by its reference view, with the views that also see it.
struct Seed {
  int reference = 0;
  Eigen::Vector3d point;
  Eigen::Vector3d normal;
  std::vector<int> search;
};

double facing(const sensor::CameraModel& camera, const Eigen::Vector3d& point,
              const Eigen::Vector3d& normal) {
  return normal.dot((camera.projection_centre() - point).normalized());
}

// The seeds of reference view r: its facet-ID image's grid pixels whose hull point r faces
// better than any other view that sees it.
std::vector<Seed> seeds_of_view(int r, const std::vector<MatchingView>& views,
                                const std::vector<FacetIdImage>& ids,
                                const std::vector<Eigen::Vector3d>& normals,
                                const SurfaceMatchingOptions& options) {
  std::vector<Seed> seeds;
  const double min_facing = std::cos(options.max_view_angle_deg * std::numbers::pi / 180.0);
  const FacetIdImage& image = ids[r];
  const Eigen::Vector3d centre = image.ideal().projection_centre();
  const double spacing = std::max(1.0, options.seed_spacing_px);
  for (double v = spacing / 2; v < image.height(); v += spacing) {
    for (double u = spacing / 2; u < image.width(); u += spacing) {
      const int x = static_cast<int>(u), y = static_cast<int>(v);
      const int f = image.facet_at(x, y);
      if (f == FacetIdImage::kNoFacet) continue;
      Seed seed{r, centre + image.depth_at(x, y) * image.ray(x, y), normals[f], {}};
      const double own = facing(views[r].camera, seed.point, seed.normal);
      if (own < min_facing) continue;
      bool best = true;
      for (int j = 0; j < static_cast<int>(views.size()) && best; ++j) {
        if (j == r || !ids[j].sees(seed.point, f, options.visibility_tolerance)) continue;
        const double other = facing(views[j].camera, seed.point, seed.normal);
        if (other < min_facing) continue;
        if (other > own) best = false;
        seed.search.push_back(j);
      }
      if (best) seeds.push_back(std::move(seed));
    }
  }
  return seeds;
}

std::vector<const MatchingView*> pointers(const std::vector<MatchingView>& views,
                                          const std::vector<int>& indices) {
  std::vector<const MatchingView*> out;
  for (const int i : indices) out.push_back(&views[i]);
  return out;
}

// The search view whose window correlates best at depth t.
int best_search_view(const ScanWindow& window, const std::vector<MatchingView>& views,
                     const std::vector<int>& search, double t) {
  int best = -1;
  double best_ncc = -2.0;
  for (const int j : search) {
    const auto warp = warp_window(window, views[j], t);
    const auto ncc = warp ? window_ncc(window, views[j], *warp) : std::nullopt;
    if (ncc && *ncc > best_ncc) best_ncc = *ncc, best = j;
  }
  return best;
}

Eigen::Vector2i rounded(const Eigen::Vector2d& p) {
  return {static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y()))};
}

// Thesis rule 2: matched back from the best search image, with the others and the reference as
// search images and the same stretch of scan line around the candidate, the point lands within
// back_matching_px of the reference pixel.
bool matches_back(const ScanWindow& window, const Seed& seed, double t, double t_from, double t_to,
                  const std::vector<MatchingView>& views, const SurfaceMatchingOptions& options) {
  const Eigen::Vector3d candidate = window.point(t);
  const int b = best_search_view(window, views, seed.search, t);
  if (b < 0) return false;
  const auto at_b = views[b].camera.project(candidate);
  if (!at_b.ok()) return false;
  const auto back = make_scan_window(views[b], rounded(at_b.pixel), window.half, seed.normal);
  if (!back) return false;
  std::vector<int> others{seed.reference};
  for (const int j : seed.search)
    if (j != b) others.push_back(j);
  const double t_b = (candidate - back->centre).dot(back->direction);
  const ScanProfile profile = scan_sncc(*back, pointers(views, others), t_b - (t - t_from),
                                        t_b + (t_to - t), options.step_px, options.min_sncc);
  if (profile.peaks.empty()) return false;
  const auto at_reference = views[seed.reference].camera.project(back->point(profile.peaks[0].t));
  return at_reference.ok() &&
         (at_reference.pixel - window.pixel.cast<double>()).norm() <= options.back_matching_px;
}

struct SeedOutcome {
  std::optional<MatchedPoint> point;
  Rejection rejection = Rejection::kOccluded;
};

SeedOutcome match_seed(const Seed& seed, const std::vector<MatchingView>& views,
                       const SurfaceMatchingOptions& options, SurfaceMatchingResult& timing) {
  SeedOutcome out;
  if (static_cast<int>(seed.search.size()) < options.min_search_views) return out;
  const auto sweep_start = Clock::now();
  const MatchingView& reference = views[seed.reference];
  const auto pixel = reference.camera.project(seed.point);
  if (!pixel.ok()) return out;
  const auto window =
      make_scan_window(reference, rounded(pixel.pixel), options.half_window, seed.normal);
  if (!window) return out;
  if (window->grey_sd < options.min_template_sd ||
      window->object_share < options.min_object_share) {
    out.rejection = Rejection::kNoTexture;
    return out;
  }
  // The hull's surface on this pixel's ray, and the stretch of the ray searched around it.
  const double t_hull =
      seed.normal.dot(seed.point - window->centre) / seed.normal.dot(window->direction);
  const double t_from = t_hull - options.search_front, t_to = t_hull + options.search_depth;
  const auto search = pointers(views, seed.search);
  const ScanProfile profile =
      scan_sncc(*window, search, t_from, t_to, options.step_px, options.min_sncc);
  if (profile.peaks.empty()) {
    out.rejection = Rejection::kLowNcc;
    timing.sweep_seconds += seconds_since(sweep_start);
    return out;
  }
  const SnccPeak& peak = profile.peaks[0];
  if (profile.peaks.size() > 1 && profile.peaks[1].sncc > options.max_second_peak * peak.sncc) {
    out.rejection = Rejection::kAmbiguous;
    timing.sweep_seconds += seconds_since(sweep_start);
    return out;
  }
  const bool back = matches_back(*window, seed, peak.t, t_from, t_to, views, options);
  timing.sweep_seconds += seconds_since(sweep_start);
  if (!back) {
    out.rejection = Rejection::kBackMatching;
    return out;
  }
  MatchedPoint m;
  m.ray_origin = window->centre;
  m.ray_direction = window->direction;
  m.normal = seed.normal;
  m.sncc = peak.sncc;
  m.sweep_t = peak.t;
  m.reference = seed.reference;
  m.pixel = window->pixel;
  m.search = seed.search;
  double t = peak.t;
  if (options.least_squares) {
    const auto lsm_start = Clock::now();
    const LsmSolution lsm = solve_multi_image_lsm(*window, search, peak.t, options.lsm);
    timing.lsm_seconds += seconds_since(lsm_start);
    if (!lsm.converged) {
      out.rejection = Rejection::kNotConverged;
      return out;
    }
    t = lsm.t;
    m.sigma_ray_mm = lsm.sigma_t;
    m.sigma_normal_mm = lsm.sigma_t * std::abs(window->direction.dot(seed.normal));
    m.sigma0 = lsm.sigma0;
    m.iterations = lsm.iterations;
  }
  m.point = window->point(t);
  out.point = std::move(m);
  return out;
}

// The statistical test: a point's residuals much larger than the run's typical ones.
void reject_blunders(const SurfaceMatchingOptions& options, SurfaceMatchingResult& result) {
  if (!options.least_squares || result.points.size() < 10) return;
  std::vector<double> sigma0;
  for (const auto& p : result.points) sigma0.push_back(p.sigma0);
  std::nth_element(sigma0.begin(), sigma0.begin() + sigma0.size() / 2, sigma0.end());
  const double limit = options.blunder_sigma0_ratio * sigma0[sigma0.size() / 2];
  const auto kept = std::remove_if(result.points.begin(), result.points.end(),
                                   [&](const MatchedPoint& p) { return p.sigma0 > limit; });
  result.rejected[static_cast<std::size_t>(Rejection::kBlunder)] +=
      static_cast<std::size_t>(result.points.end() - kept);
  result.points.erase(kept, result.points.end());
}

// The options with their lengths taken from the hull's size where they are 0.
SurfaceMatchingOptions sized_to(const std::vector<Facet>& hull, SurfaceMatchingOptions options) {
  Eigen::AlignedBox3d box;
  for (const Facet& f : hull) box.extend(f.a), box.extend(f.b), box.extend(f.c);
  const double diagonal = box.isEmpty() ? 0.0 : box.diagonal().norm();
  if (options.visibility_tolerance <= 0) options.visibility_tolerance = 0.0025 * diagonal;
  if (options.search_front <= 0) options.search_front = 0.0075 * diagonal;
  if (options.search_depth <= 0) options.search_depth = 0.06 * diagonal;
  return options;
}

}  // namespace

const char* rejection_name(Rejection r) {
  switch (r) {
    case Rejection::kOccluded:
      return "occluded (facet-ID)";
    case Rejection::kNoTexture:
      return "no texture";
    case Rejection::kLowNcc:
      return "low NCC";
    case Rejection::kAmbiguous:
      return "ambiguous";
    case Rejection::kBackMatching:
      return "back-matching";
    case Rejection::kNotConverged:
      return "not converged";
    case Rejection::kBlunder:
      return "blunder (sigma0 test)";
    case Rejection::kCount:
      break;
  }
  return "?";
}

SurfaceMatchingResult match_surface(const std::vector<MatchingView>& views,
                                    const std::vector<Facet>& hull,
                                    const SurfaceMatchingOptions& given) {
  const SurfaceMatchingOptions options = sized_to(hull, given);
  SurfaceMatchingResult result;
  result.visibility_tolerance = options.visibility_tolerance;
  result.search_front = options.search_front;
  result.search_depth = options.search_depth;
  const auto visibility_start = Clock::now();
  std::vector<FacetIdImage> ids;
  for (const auto& view : views) ids.emplace_back(view.camera, hull);
  std::vector<Eigen::Vector3d> normals;
  for (const auto& f : hull) normals.push_back(f.normal());
  std::vector<Seed> seeds;
  for (int r = 0; r < static_cast<int>(views.size()); ++r) {
    auto own = seeds_of_view(r, views, ids, normals, options);
    seeds.insert(seeds.end(), own.begin(), own.end());
  }
  result.visibility_seconds = seconds_since(visibility_start);
  result.seeds = seeds.size();
  for (const Seed& seed : seeds) {
    SeedOutcome outcome = match_seed(seed, views, options, result);
    if (outcome.point)
      result.points.push_back(std::move(*outcome.point));
    else
      ++result.rejected[static_cast<std::size_t>(outcome.rejection)];
  }
  reject_blunders(options, result);
  return result;
}

}  // namespace syncap::surface
