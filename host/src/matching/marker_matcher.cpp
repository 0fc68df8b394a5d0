#include "matching/marker_matcher.hpp"

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <queue>

#include "matching/blob_graph.hpp"

namespace syncap::matching {
namespace {

struct Candidate {
  std::vector<int> nodes;  // graph nodes, one per camera
  geometry::RayPoint point;
  double rms_px = 0;  // point.rms_px(), kept for the queue's comparisons
};

// More cameras first, then the smaller RMS: the order of the evidence.
bool better(const Candidate& a, const Candidate& b) {
  if (a.nodes.size() != b.nodes.size()) return a.nodes.size() > b.nodes.size();
  return a.rms_px < b.rms_px;
}

struct Worse {
  bool operator()(const Candidate& a, const Candidate& b) const { return better(b, a); }
};

class Growth {
 public:
  Growth(const BlobGraph& graph, const MatchOptions& options,
         const std::vector<double>& critical_chi_square, MatchStats& stats)
      : g_(graph), options_(options), critical_(critical_chi_square), stats_(stats) {}

  // Triangulates the candidate's rays; while one is off by more than the tolerance or together
  // they fail the chi-square test, the worst is left out. False when fewer than two remain, the
  // rays fix no point, or it lies outside the volume.
  bool settle(Candidate& c) const {
    while (c.nodes.size() >= 2) {
      std::vector<geometry::ViewRay> rays;
      for (const int n : c.nodes) rays.push_back(g_.rays[static_cast<std::size_t>(n)]);
      c.point = geometry::triangulate(rays, options_.sigma_px);
      if (!c.point.ok) return false;
      if (options_.volume && !options_.volume->contains(c.point.position)) return false;
      const auto worst = std::max_element(c.point.errors_px.begin(), c.point.errors_px.end());
      if (*worst <= options_.tolerance_px && c.point.chi_square <= critical_[rays.size()]) {
        c.rms_px = c.point.rms_px();
        return true;
      }
      c.nodes.erase(c.nodes.begin() + (worst - c.point.errors_px.begin()));
      ++stats_.rays_dropped;
    }
    return false;
  }

  // The point of edge (a, b), with one blob of each other camera that is joined to every member
  // and passes closest to it.
  Candidate grow(int a, int b, const Eigen::Vector3d& start) const {
    Candidate c{{a, b}, {}, 0};
    NodeSet joined = g_.neighbours[static_cast<std::size_t>(a)];
    joined &= g_.neighbours[static_cast<std::size_t>(b)];
    std::vector<std::pair<double, int>> near;
    joined.for_each([&](int n) {
      const geometry::ViewRay& r = g_.rays[static_cast<std::size_t>(n)];
      // Twice the tolerance: the start is only the middle of two rays' closest points.
      const double error_px = geometry::angle_to(r.ray, start) * r.pixels_per_rad;
      if (error_px <= 2 * options_.tolerance_px) near.emplace_back(error_px, n);
    });
    std::sort(near.begin(), near.end());
    std::vector<int> cameras{camera(a), camera(b)};
    for (const auto& [error_px, n] : near) {
      if (!joined.contains(n) ||
          std::find(cameras.begin(), cameras.end(), camera(n)) != cameras.end())
        continue;
      c.nodes.push_back(n);
      cameras.push_back(camera(n));
      joined &= g_.neighbours[static_cast<std::size_t>(n)];
    }
    return c;
  }

  int camera(int node) const { return g_.blobs[static_cast<std::size_t>(node)].camera; }

 private:
  const BlobGraph& g_;
  const MatchOptions& options_;
  const std::vector<double>& critical_;
  MatchStats& stats_;
};

// Grows a candidate from every edge no earlier candidate explains.
std::vector<Candidate> candidates_of(const BlobGraph& g, const Growth& growth, MatchStats& stats,
                                     const MatchOptions& options) {
  std::vector<NodeSet> explained(static_cast<std::size_t>(g.size()), NodeSet(g.size()));
  std::vector<Candidate> out;
  for (const auto& [a, b] : g.edges) {
    if (explained[static_cast<std::size_t>(a)].contains(b)) continue;
    Eigen::Vector3d start;
    rays_meet(g.rays[static_cast<std::size_t>(a)], g.rays[static_cast<std::size_t>(b)],
              options.tolerance_px, options.min_depth_mm, &start);
    Candidate c = growth.grow(a, b, start);
    ++stats.candidates;
    if (!growth.settle(c)) continue;
    for (const int m : c.nodes) {
      for (const int n : c.nodes) explained[static_cast<std::size_t>(m)].insert(n);
    }
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace

uint64_t MatchedPoint::camera_mask() const {
  uint64_t mask = 0;
  for (const BlobRef& b : blobs) {
    if (b.camera < 64) mask |= uint64_t{1} << b.camera;
  }
  return mask;
}

MarkerMatcher::MarkerMatcher(std::vector<sensor::CameraModel> cameras, MatchOptions options)
    : cameras_(std::move(cameras)), options_(options) {
  // n rays: 2 n - 3 degrees of freedom (2 per ray, 3 for the point); from boost, once.
  critical_chi_square_.assign(cameras_.size() + 1, 0.0);
  for (std::size_t n = 2; n <= cameras_.size(); ++n) {
    const boost::math::chi_squared_distribution<double> chi_square(static_cast<double>(2 * n - 3));
    critical_chi_square_[n] = boost::math::quantile(chi_square, 1.0 - options_.alpha);
  }
}

MatchResult MarkerMatcher::match(const std::vector<std::vector<Eigen::Vector2d>>& blobs) const {
  MatchResult result;
  const BlobGraph g = BlobGraph::build(cameras_, blobs, options_);
  result.stats.edges = static_cast<long>(g.edges.size());
  const Growth growth(g, options_, critical_chi_square_, result.stats);
  std::priority_queue<Candidate, std::vector<Candidate>, Worse> queue;
  for (Candidate& c : candidates_of(g, growth, result.stats, options_)) queue.push(std::move(c));

  // Best first; a candidate that lost blobs to a better one competes again with what is left.
  NodeSet used(g.size());
  while (!queue.empty()) {
    Candidate c = queue.top();
    queue.pop();
    const auto taken =
        std::remove_if(c.nodes.begin(), c.nodes.end(), [&](int n) { return used.contains(n); });
    if (taken != c.nodes.end()) {
      ++result.stats.conflicts;
      c.nodes.erase(taken, c.nodes.end());
      if (c.nodes.size() >= 2 && growth.settle(c)) queue.push(std::move(c));
      continue;
    }
    MatchedPoint p;
    for (const int n : c.nodes) {
      used.insert(n);
      p.blobs.push_back(g.blobs[static_cast<std::size_t>(n)]);
    }
    std::vector<std::size_t> order(p.blobs.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](std::size_t x, std::size_t y) { return p.blobs[x].camera < p.blobs[y].camera; });
    MatchedPoint sorted;
    sorted.point = c.point;
    sorted.point.errors_px.clear();
    for (const std::size_t i : order) {
      sorted.blobs.push_back(p.blobs[i]);
      sorted.point.errors_px.push_back(c.point.errors_px[i]);
    }
    result.points.push_back(std::move(sorted));
  }
  return result;
}

}  // namespace syncap::matching
