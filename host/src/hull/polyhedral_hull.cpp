// The polyhedral visual hull, cone face by cone face (docs/design/visual-hull.md, "The polyhedral
// method"). Notation: view i's contour edge k spans the cone face f = (i, k) between the rays D_k
// and D_{k+1} from the projection centre C_i, the rays scaled to depth 1 along the viewing axis.
// The face's domain is (s, v) in [0, 1]^2: X = C_i + Dir(s) / u, Dir(s) = D_k + s (D_{k+1} - D_k),
// u = u0 + v du the inverse depth between the working volume's far and near side. Lines in 3D on
// the face are lines in (s, v), and view j sees the domain through a 3x3 map G_j (its ideal image
// coordinates, homogeneous, the third row positive in front of it).
#include "hull/polyhedral_hull.hpp"

#include <boost/container/small_vector.hpp>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <list>
#include <optional>
#include <unordered_map>

#include "hull/nesting_triangulation.hpp"
#include "util/printf_string.hpp"

namespace syncap::hull {

namespace {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Key = std::uint64_t;  // a vertex: the sorted triple of the plane ids that meet there

constexpr int kPlaneBits = 21;

// A configuration the combinatorial assembly cannot name consistently (four planes through one
// point, a crossing missed by rounding): retried with another perturbation.
struct Degenerate {
  const char* what;  // which step found it, for the final error
};

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
Vec3 homogeneous(const Vec2& p) { return {p.x(), p.y(), 1.0}; }

Key key_of(int a, int b, int c) {
  if (a > b) std::swap(a, b);
  if (b > c) std::swap(b, c);
  if (a > b) std::swap(a, b);
  return (static_cast<Key>(a) << (2 * kPlaneBits)) | (static_cast<Key>(b) << kPlaneBits) |
         static_cast<Key>(c);
}

struct Edge {
  int a = 0, b = 0;          // contour points, the silhouette's interior on the left of a -> b
  int prev = 0, next = 0;    // the edges ending at a and starting at b
  Vec3 line = Vec3::Zero();  // homogeneous, positive on the interior side
};

// Even-odd point-in-polygon in O(edges per band): the edges binned by the rows they span.
struct Bands {
  double y0 = 0.0, y1 = 0.0, scale = 0.0;
  std::vector<std::vector<int>> edges;
};

// The edges by the cells of a uniform grid over the silhouette's box that they pass through
// (their bounding boxes' cells): the candidates for a face are looked up by the cells under the
// face's image instead of testing every edge.
struct EdgeGrid {
  Vec2 origin = Vec2::Zero();
  Vec2 scale = Vec2::Zero();  // cells per unit
  int n = 1;
  std::vector<std::vector<int>> cells;  // row-major, n x n
};

struct ViewData {
  Vec3 centre;
  Mat3 to_camera;  // object -> (x', y', depth): ideal image coordinates times depth
  double near = 0.0, far = 0.0;
  std::vector<Vec2> points;  // ideal image coordinates (x', y' at depth 1)
  std::vector<Vec3> rays;    // object space, depth 1 along the viewing axis
  std::vector<Edge> edges;
  Bands bands;
  EdgeGrid grid;
  mutable std::vector<unsigned> seen;  // per edge: the lookup that last returned it
  mutable unsigned lookup = 0;
  Eigen::AlignedBox2d box;  // of the points
  int first_plane = 0;      // the plane id of edges[0]
};

int band_of(const Bands& b, double y) {
  return std::clamp(static_cast<int>((y - b.y0) * b.scale), 0,
                    static_cast<int>(b.edges.size()) - 1);
}

void build_bands(ViewData& v) {
  Bands& b = v.bands;
  b.y0 = b.y1 = v.points.front().y();
  for (const Vec2& p : v.points) {
    b.y0 = std::min(b.y0, p.y());
    b.y1 = std::max(b.y1, p.y());
  }
  const int n = std::clamp(static_cast<int>(v.edges.size() / 2), 1, 256);
  b.scale = n / std::max(b.y1 - b.y0, 1e-12);
  b.edges.assign(n, {});
  for (std::size_t e = 0; e < v.edges.size(); ++e) {
    const double ya = v.points[v.edges[e].a].y(), yb = v.points[v.edges[e].b].y();
    const int lo = band_of(b, std::min(ya, yb)), hi = band_of(b, std::max(ya, yb));
    for (int k = lo; k <= hi; ++k) b.edges[k].push_back(static_cast<int>(e));
  }
}

bool inside_silhouette(const ViewData& v, const Vec2& p) {
  const Bands& b = v.bands;
  if (!v.box.contains(p)) return false;
  bool in = false;
  for (int e : b.edges[band_of(b, p.y())]) {
    const Vec2& a = v.points[v.edges[e].a];
    const Vec2& c = v.points[v.edges[e].b];
    if ((a.y() > p.y()) == (c.y() > p.y())) continue;
    const double x = a.x() + (p.y() - a.y()) / (c.y() - a.y()) * (c.x() - a.x());
    if (x > p.x()) in = !in;
  }
  return in;
}

int cell_of(const EdgeGrid& g, double x, int axis) {
  return std::clamp(static_cast<int>((x - g.origin[axis]) * g.scale[axis]), 0, g.n - 1);
}

void build_grid(ViewData& v) {
  EdgeGrid& g = v.grid;
  g.n = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(v.edges.size()))), 1, 64);
  g.origin = v.box.min();
  g.scale =
      Vec2(g.n / std::max(v.box.sizes().x(), 1e-12), g.n / std::max(v.box.sizes().y(), 1e-12));
  g.cells.assign(static_cast<std::size_t>(g.n * g.n), {});
  for (std::size_t e = 0; e < v.edges.size(); ++e) {
    const Vec2 &a = v.points[v.edges[e].a], &b = v.points[v.edges[e].b];
    for (int y = cell_of(g, std::min(a.y(), b.y()), 1); y <= cell_of(g, std::max(a.y(), b.y()), 1);
         ++y) {
      for (int x = cell_of(g, std::min(a.x(), b.x()), 0);
           x <= cell_of(g, std::max(a.x(), b.x()), 0); ++x)
        g.cells[static_cast<std::size_t>(y * g.n + x)].push_back(static_cast<int>(e));
    }
  }
  v.seen.assign(v.edges.size(), 0);
}

// The edges in the grid cells under `box` (each once).
template <typename Visit>
void edges_near(const ViewData& v, const Eigen::AlignedBox2d& box, Visit visit) {
  if (!box.intersects(v.box)) return;
  const EdgeGrid& g = v.grid;
  ++v.lookup;
  for (int y = cell_of(g, box.min().y(), 1); y <= cell_of(g, box.max().y(), 1); ++y) {
    for (int x = cell_of(g, box.min().x(), 0); x <= cell_of(g, box.max().x(), 0); ++x) {
      for (int e : g.cells[static_cast<std::size_t>(y * g.n + x)]) {
        if (v.seen[e] == v.lookup) continue;
        v.seen[e] = v.lookup;
        visit(e);
      }
    }
  }
}

// Whether the silhouette's interior lies left of the edge (just beside its middle).
bool interior_on_left(const ViewData& v, const Edge& e) {
  const Vec2 d = v.points[e.b] - v.points[e.a];
  const Vec2 left(-d.y(), d.x());
  return inside_silhouette(v, 0.5 * (v.points[e.a] + v.points[e.b]) + 1e-3 * left);
}

void orient_contour(ViewData& v, std::size_t first, std::size_t end) {
  if (interior_on_left(v, v.edges[first])) return;
  for (std::size_t e = first; e < end; ++e) {
    std::swap(v.edges[e].a, v.edges[e].b);
    std::swap(v.edges[e].prev, v.edges[e].next);
  }
}

// Ideal image coordinates of a pixel: its ray in the camera frame at depth 1.
Vec2 ideal_point(const HullView& view, const Mat3& r_t, const Vec2& pixel) {
  const Vec3 local = r_t * view.camera.back_project(pixel).direction;
  if (local.z() >= 0.0) throw HullError(view.name + ": a contour pixel's ray points backwards");
  return {local.x() / -local.z(), local.y() / -local.z()};
}

// View `index` with attempt `attempt`'s perturbation (hull_view.hpp: the exact method's too).
ViewData prepare_view(const HullView& view, std::size_t index, const WorkingVolume& volume,
                      unsigned attempt, int first_plane) {
  ViewData v;
  const Mat3 r = view.camera.rotation();
  v.centre = view.camera.projection_centre();
  v.to_camera = Vec3(1.0, 1.0, -1.0).asDiagonal() * r.transpose();
  const ConeDepths depths = cone_depths(view.camera, volume);
  v.near = depths.near;
  v.far = depths.far;
  v.first_plane = first_plane;
  std::vector<std::pair<std::size_t, std::size_t>> contours;
  for (const Contour& c : perturbed(view.silhouette, attempt, index).contours) {
    std::vector<Vec2> pts;
    for (const Vec2& p : c.points) pts.push_back(ideal_point(view, r.transpose(), p));
    if (pts.size() < 3) continue;
    const int base = static_cast<int>(v.points.size()), n = static_cast<int>(pts.size());
    const int e0 = static_cast<int>(v.edges.size());
    for (int t = 0; t < n; ++t) {
      v.points.push_back(pts[t]);
      v.edges.push_back(
          {base + t, base + (t + 1) % n, e0 + (t + n - 1) % n, e0 + (t + 1) % n, Vec3::Zero()});
    }
    contours.emplace_back(e0, v.edges.size());
  }
  if (v.edges.empty()) throw HullError(view.name + ": the silhouette has no area");
  for (const Vec2& p : v.points) v.box.extend(p);
  build_bands(v);
  for (const auto& [first, end] : contours) orient_contour(v, first, end);
  for (Edge& e : v.edges) e.line = homogeneous(v.points[e.a]).cross(homogeneous(v.points[e.b]));
  for (const Vec2& p : v.points) v.rays.push_back(r * Vec3(p.x(), p.y(), -1.0));
  build_grid(v);
  return v;
}

// Planes n . X = d, n unit: cone faces (by view, edge), then each view's near and far cap.
struct Plane {
  Vec3 n;
  double d = 0.0;
};

struct Segment;
struct Piece;

struct Assembly {
  std::vector<ViewData> views;
  std::vector<Plane> planes;
  int first_cap = 0;
  std::unordered_map<Key, int> vertex_of;
  std::vector<Vec3> points;
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::vector<char>> meets;  // meets[i][j]: a face of cone i meets cone j
  std::size_t candidates = 0;
  mutable std::size_t last_rejecting = 0;  // inside_other_cones' first guess
  // One face's candidates and pieces, reused from face to face (perf: malloc and free took
  // about a tenth of the time before).
  std::vector<Segment> candidate_buffer;
  std::vector<Piece> piece_buffer;
  int near_cap(std::size_t view) const { return first_cap + 2 * static_cast<int>(view); }
  int far_cap(std::size_t view) const { return near_cap(view) + 1; }
};

Vec3 meet(const Plane& a, const Plane& b, const Plane& c) {
  const Vec3 bc = b.n.cross(c.n), ca = c.n.cross(a.n), ab = a.n.cross(b.n);
  const double det = a.n.dot(bc);
  if (std::abs(det) < 1e-12) throw Degenerate{"three planes of a vertex nearly parallel"};
  return (a.d * bc + b.d * ca + c.d * ab) / det;
}

int vertex_index(Assembly& as, Key key) {
  const auto [it, added] = as.vertex_of.try_emplace(key, static_cast<int>(as.points.size()));
  if (added) {
    const Key mask = (Key{1} << kPlaneBits) - 1;
    as.points.push_back(meet(as.planes[key >> (2 * kPlaneBits)],
                             as.planes[(key >> kPlaneBits) & mask], as.planes[key & mask]));
  }
  return it->second;
}

void add_planes(Assembly& as) {
  for (const ViewData& v : as.views) {
    for (const Edge& e : v.edges) {
      const Vec3 n = v.rays[e.a].cross(v.rays[e.b]).normalized();
      as.planes.push_back({n, n.dot(v.centre)});
    }
  }
  as.first_cap = static_cast<int>(as.planes.size());
  for (const ViewData& v : as.views) {
    const Vec3 axis = v.to_camera.row(2).transpose();
    as.planes.push_back({axis, axis.dot(v.centre) + v.near});
    as.planes.push_back({axis, axis.dot(v.centre) + v.far});
  }
  if (as.planes.size() >= (std::size_t{1} << kPlaneBits))
    throw HullError("too many silhouette vertices for the polyhedral hull's vertex keys");
}

// A boundary candidate in a face's domain: a side of the domain or the preimage of another
// view's contour edge, with the crossings that split it.
struct Segment {
  Vec2 p0, p1;
  Key k0 = 0, k1 = 0;
  int plane = 0;
  int view = 0;  // the view whose cone it bounds
  Vec3 line;     // in (s, v, 1), positive on that cone's interior side
  bool cap = false;
  // Most segments cross a few others: inline storage saves an allocation per segment.
  boost::container::small_vector<std::pair<double, Key>, 8> splits;
};

struct Piece {
  Key from = 0, to = 0;
  Vec2 at;  // the `from` point in the domain
};

// One cone face and how the other views see its domain.
struct Face {
  int view = 0, edge = 0, plane = 0;
  Vec3 dk, dk1;
  double u0 = 0.0, du = 0.0;
  std::array<int, 4> side_plane{};  // v = 0 (far), s = 1, v = 1 (near), s = 0
  std::vector<Mat3> g;              // per view: (s, v, 1) -> homogeneous ideal image
  // Where the hull can be: in front of the other views and inside their silhouettes' boxes
  // (convex, counter-clockwise). A candidate that misses it bounds nothing.
  std::vector<Vec2> region;
};

// Whether the segment a-b meets the convex counter-clockwise polygon (Cyrus-Beck).
bool meets_convex(const std::vector<Vec2>& poly, const Vec2& a, const Vec2& b) {
  double t0 = 0.0, t1 = 1.0;
  for (std::size_t n = 0; n < poly.size(); ++n) {
    const Vec2 side = poly[(n + 1) % poly.size()] - poly[n];
    const double ha = cross2(side, a - poly[n]), hb = cross2(side, b - poly[n]);
    if (ha < 0.0 && hb < 0.0) return false;
    if (ha >= 0.0 && hb >= 0.0) continue;
    const double t = ha / (ha - hb);
    if (ha < 0.0)
      t0 = std::max(t0, t);
    else
      t1 = std::min(t1, t);
  }
  return t0 <= t1;
}

const std::array<Vec2, 4> kCorners = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};

// How view j sees the domain with the face's current depth range.
Mat3 domain_map(const ViewData& vi, const ViewData& vj, const Face& f) {
  const Vec3 base = vi.centre - vj.centre;
  Mat3 g;
  g.col(0) = vj.to_camera * (f.dk1 - f.dk);
  g.col(1) = vj.to_camera * (f.du * base);
  g.col(2) = vj.to_camera * (f.dk + f.u0 * base);
  return g;
}

// Replaces a convex polygon by its part where h . (s, v, 1) >= 0 (Sutherland-Hodgman, one
// plane); `scratch` is reused between calls (the clipping runs 5 times per view and face).
void clip_polygon(std::vector<Vec2>& poly, std::vector<Vec2>& scratch, const Vec3& h) {
  scratch.clear();
  for (std::size_t n = 0; n < poly.size(); ++n) {
    const Vec2& a = poly[n];
    const Vec2& b = poly[(n + 1) % poly.size()];
    const double ha = h.dot(homogeneous(a)), hb = h.dot(homogeneous(b));
    if (ha >= 0.0) scratch.push_back(a);
    if ((ha >= 0.0) != (hb >= 0.0)) scratch.push_back(a + ha / (ha - hb) * (b - a));
  }
  poly.swap(scratch);
}

// The part of the domain whose image lies in front of every other view and inside its
// silhouette's bounding box (convex): the hull's part of the face lies there. Empty when none.
std::vector<Vec2> region_in_boxes(const Assembly& as, const Face& f) {
  std::vector<Vec2> poly(kCorners.begin(), kCorners.end()), scratch;
  poly.reserve(4 + 5 * as.views.size());
  scratch.reserve(poly.capacity());
  for (std::size_t j = 0; j < as.views.size() && !poly.empty(); ++j) {
    if (static_cast<int>(j) == f.view) continue;
    const Eigen::AlignedBox2d& box = as.views[j].box;
    const Mat3 g = domain_map(as.views[f.view], as.views[j], f);
    const Vec3 x = g.row(0).transpose(), y = g.row(1).transpose(), w = g.row(2).transpose();
    for (const Vec3& h : {w, Vec3(x - box.min().x() * w), Vec3(box.max().x() * w - x),
                          Vec3(y - box.min().y() * w), Vec3(box.max().y() * w - y)}) {
      clip_polygon(poly, scratch, h);
      if (poly.empty()) break;
    }
  }
  return poly;
}

// The face with its domain's depth range narrowed to the other silhouettes' boxes (a margin of
// 1e-3 of the range keeps the narrowed sides strictly outside some cone, so they never bound
// the hull); nullopt when the face has no part of the hull.
std::optional<Face> make_face(const Assembly& as, int i, int k) {
  const ViewData& vi = as.views[i];
  const Edge& e = vi.edges[k];
  Face f;
  f.view = i;
  f.edge = k;
  f.plane = vi.first_plane + k;
  f.dk = vi.rays[e.a];
  f.dk1 = vi.rays[e.b];
  f.u0 = 1.0 / vi.far;
  f.du = 1.0 / vi.near - f.u0;
  f.side_plane = {as.far_cap(i), vi.first_plane + e.next, as.near_cap(i), vi.first_plane + e.prev};
  f.region = region_in_boxes(as, f);
  if (f.region.size() < 3) return std::nullopt;
  double lo = 1.0, hi = 0.0;
  for (const Vec2& p : f.region) {
    lo = std::min(lo, p.y());
    hi = std::max(hi, p.y());
  }
  lo = std::max(0.0, lo - 1e-3);
  hi = std::min(1.0, hi + 1e-3);
  f.u0 += lo * f.du;
  f.du *= hi - lo;
  for (Vec2& p : f.region) p.y() = (p.y() - lo) / (hi - lo);  // in the narrowed domain
  f.g.resize(as.views.size());
  for (std::size_t j = 0; j < as.views.size(); ++j) {
    if (static_cast<int>(j) == i) continue;
    f.g[j] = domain_map(vi, as.views[j], f);
    for (const Vec2& c : kCorners) {
      if ((f.g[j] * homogeneous(c)).z() <= 0.0) {
        throw HullError(util::printf_string(
            "the working volume reaches behind camera %zu: give a smaller HullOptions::volume", j));
      }
    }
  }
  return f;
}

[[noreturn]] void throw_cut_by_volume() {
  throw HullError(
      "the working volume cuts the hull (the hull reaches its near or far bound): give a larger "
      "HullOptions::volume or volume_margin");
}

// Whether a domain point projects inside every other view's silhouette. A point inside them all
// but beyond a cone's truncation means the working volume cuts the hull: an error, since the
// caps of one view are no boundary candidates in the other views' faces. The view that rejected
// the last point is tried first (neighbouring pieces tend to leave by the same cone).
bool inside_other_cones(const Assembly& as, const Face& f, const Vec2& p, int except) {
  const double u = f.u0 + p.y() * f.du;
  bool beyond_volume = false;
  const auto inside = [&](std::size_t j) {
    const ViewData& vj = as.views[j];
    const Vec3 x = f.g[j] * homogeneous(p);
    const double depth = x.z() / u;
    beyond_volume = beyond_volume || depth < vj.near || depth > vj.far;
    return inside_silhouette(vj, x.head<2>() / x.z());
  };
  const std::size_t first = as.last_rejecting;
  const auto tested = [&](std::size_t j) {
    return static_cast<int>(j) == f.view || static_cast<int>(j) == except;
  };
  if (!tested(first) && !inside(first)) return false;
  for (std::size_t j = 0; j < as.views.size(); ++j) {
    if (j == first || tested(j)) continue;
    if (!inside(j)) {
      as.last_rejecting = j;
      return false;
    }
  }
  if (beyond_volume) throw_cut_by_volume();
  return true;
}

std::array<Segment, 4> domain_sides(const Face& f) {
  static const std::array<Vec3, 4> kLines = {Vec3(0, 1, 0), Vec3(-1, 0, 1), Vec3(0, -1, 1),
                                             Vec3(1, 0, 0)};
  std::array<Segment, 4> sides;
  for (int m = 0; m < 4; ++m) {
    Segment& s = sides[m];
    s.p0 = kCorners[m];
    s.p1 = kCorners[(m + 1) % 4];
    s.k0 = key_of(f.plane, f.side_plane[(m + 3) % 4], f.side_plane[m]);
    s.k1 = key_of(f.plane, f.side_plane[m], f.side_plane[(m + 1) % 4]);
    s.plane = f.side_plane[m];
    s.view = f.view;
    s.line = kLines[m];
    s.cap = m % 2 == 0;
  }
  return sides;
}

// The position along domain side m of a point on it.
double side_parameter(int m, const Vec2& p) {
  switch (m) {
    case 0:
      return p.x();
    case 1:
      return p.y();
    case 2:
      return 1.0 - p.x();
    default:
      return 1.0 - p.y();
  }
}

Vec2 snapped_to_side(int m, Vec2 p) {
  if (m % 2 == 0)
    p.y() = m == 0 ? 0.0 : 1.0;
  else
    p.x() = m == 1 ? 1.0 : 0.0;
  return p;
}

// Clips edge e of view j to the domain's image in view j (a convex quad, Cyrus-Beck) and maps
// the rest back into the domain. Endpoints clipped by a side split that side.
void add_candidate(const Assembly& as, const Face& f, int j, int e, const std::array<Vec2, 4>& q,
                   double orientation, const Mat3& g_inverse, std::vector<Segment>& candidates,
                   std::array<Segment, 4>& sides) {
  const ViewData& vj = as.views[j];
  const Edge& edge = vj.edges[e];
  const Vec2 a = vj.points[edge.a], b = vj.points[edge.b];
  double t0 = 0.0, t1 = 1.0;
  int m0 = -1, m1 = -1;
  for (int m = 0; m < 4; ++m) {
    const Vec2 side = q[(m + 1) % 4] - q[m];
    const double ha = orientation * cross2(side, a - q[m]);
    const double hb = orientation * cross2(side, b - q[m]);
    if (ha < 0.0 && hb < 0.0) return;
    if (ha >= 0.0 && hb >= 0.0) continue;
    const double t = ha / (ha - hb);
    if (ha < 0.0 && t > t0) {
      t0 = t;
      m0 = m;
    } else if (ha >= 0.0 && t < t1) {
      t1 = t;
      m1 = m;
    }
  }
  if (t0 >= t1) return;
  const int plane = vj.first_plane + e;
  const auto to_domain = [&](double t, int m) {
    const Vec3 p = g_inverse * homogeneous(a + t * (b - a));
    const Vec2 d = p.head<2>() / p.z();
    return m < 0 ? d : snapped_to_side(m, d);
  };
  Segment s;
  s.p0 = to_domain(t0, m0);
  s.p1 = to_domain(t1, m1);
  s.k0 = key_of(f.plane, plane, m0 < 0 ? vj.first_plane + edge.prev : f.side_plane[m0]);
  s.k1 = key_of(f.plane, plane, m1 < 0 ? vj.first_plane + edge.next : f.side_plane[m1]);
  s.plane = plane;
  s.view = j;
  s.line = f.g[j].transpose() * edge.line;
  if (!meets_convex(f.region, s.p0, s.p1)) return;  // outside some cone all along
  if (m0 >= 0) sides[m0].splits.emplace_back(side_parameter(m0, s.p0), s.k0);
  if (m1 >= 0) sides[m1].splits.emplace_back(side_parameter(m1, s.p1), s.k1);
  candidates.push_back(std::move(s));
}

// The other views' contour edges whose cone faces cross this face inside the working volume: the
// edges that meet the domain's image in view j, a thin convex quad (add_candidate rejects an edge
// with both ends outside one of its sides).
void find_candidates(Assembly& as, const Face& f, std::array<Segment, 4>& sides,
                     std::vector<Segment>& candidates) {
  candidates.clear();
  for (std::size_t j = 0; j < as.views.size(); ++j) {
    if (static_cast<int>(j) == f.view) continue;
    const ViewData& vj = as.views[j];
    const Mat3& g = f.g[j];
    std::array<Vec2, 4> q;
    for (int m = 0; m < 4; ++m) {
      const Vec3 x = g * homogeneous(kCorners[m]);
      q[m] = x.head<2>() / x.z();
    }
    const double orientation =
        cross2(q[1] - q[0], q[2] - q[0]) + cross2(q[2] - q[0], q[3] - q[0]) > 0.0 ? 1.0 : -1.0;
    const Mat3 g_inverse = g.inverse();
    const std::size_t before = candidates.size();
    Eigen::AlignedBox2d image_box;
    for (const Vec2& c : q) image_box.extend(c);
    edges_near(vj, image_box, [&](int e) {
      add_candidate(as, f, static_cast<int>(j), e, q, orientation, g_inverse, candidates, sides);
    });
    if (candidates.size() > before) as.meets[f.view][j] = 1;
  }
  as.candidates += candidates.size();
}

void split_at_crossings(const Face& f, std::vector<Segment>& candidates) {
  for (std::size_t x = 0; x < candidates.size(); ++x) {
    for (std::size_t y = x + 1; y < candidates.size(); ++y) {
      Segment& a = candidates[x];
      Segment& b = candidates[y];
      if (a.view == b.view) continue;  // one silhouette's edges meet only at their ends
      const Vec2 da = a.p1 - a.p0, db = b.p1 - b.p0, w = b.p0 - a.p0;
      const double den = cross2(da, db);
      if (den == 0.0) continue;
      const double ta = cross2(w, db) / den, tb = cross2(w, da) / den;
      if (ta <= 0.0 || ta >= 1.0 || tb <= 0.0 || tb >= 1.0) continue;
      const Key key = key_of(f.plane, a.plane, b.plane);
      a.splits.emplace_back(ta, key);
      b.splits.emplace_back(tb, key);
    }
  }
}

// The pieces of a segment inside every other cone, directed with the face's region on the left.
void keep_pieces(const Assembly& as, const Face& f, Segment& s, std::vector<Piece>& pieces) {
  std::ranges::sort(s.splits);
  s.splits.insert(s.splits.begin(), {0.0, s.k0});
  s.splits.emplace_back(1.0, s.k1);
  const Vec2 d = s.p1 - s.p0;
  const bool forward = Vec2(-d.y(), d.x()).dot(s.line.head<2>()) > 0.0;
  for (std::size_t n = 0; n + 1 < s.splits.size(); ++n) {
    const auto& [ta, ka] = s.splits[n];
    const auto& [tb, kb] = s.splits[n + 1];
    if (ka == kb) throw Degenerate{"two crossings of a segment named alike"};
    const Vec2 mid = s.p0 + 0.5 * (ta + tb) * d;
    if (!inside_other_cones(as, f, mid, s.view)) continue;
    if (s.cap) throw_cut_by_volume();
    if (forward) {
      pieces.push_back({ka, kb, s.p0 + ta * d});
    } else {
      pieces.push_back({kb, ka, s.p0 + tb * d});
    }
  }
}

struct Loop {
  std::vector<Vec2> points;
  std::vector<Key> keys;
  double area() const {
    double a = 0.0;
    for (std::size_t n = 0; n < points.size(); ++n)
      a += cross2(points[n], points[(n + 1) % points.size()]);
    return 0.5 * a;
  }
};

std::vector<Loop> chain_loops(std::vector<Piece>& pieces) {
  std::ranges::sort(pieces, [](const Piece& a, const Piece& b) { return a.from < b.from; });
  for (std::size_t n = 0; n + 1 < pieces.size(); ++n) {
    if (pieces[n].from == pieces[n + 1].from)
      throw Degenerate{"two boundary pieces leave one vertex"};
  }
  std::vector<char> used(pieces.size(), 0);
  std::vector<Loop> loops;
  for (std::size_t start = 0; start < pieces.size(); ++start) {
    if (used[start]) continue;
    Loop loop;
    std::size_t n = start;
    while (!used[n]) {
      used[n] = 1;
      loop.points.push_back(pieces[n].at);
      loop.keys.push_back(pieces[n].from);
      const auto next = std::ranges::lower_bound(pieces, pieces[n].to, {}, &Piece::from);
      if (next == pieces.end() || next->from != pieces[n].to)
        throw Degenerate{"a face's boundary does not close"};
      n = static_cast<std::size_t>(next - pieces.begin());
    }
    if (n != start || loop.points.size() < 3) throw Degenerate{"a face's boundary loop is broken"};
    loops.push_back(std::move(loop));
  }
  return loops;
}

using Triangle = std::array<std::size_t, 3>;  // indices into the face's loop points

bool in_triangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  return cross2(b - a, p - a) >= 0.0 && cross2(c - b, p - b) >= 0.0 && cross2(a - c, p - c) >= 0.0;
}

// Ear clipping of one counter-clockwise loop (vertices `first` ..). False when no strictly
// convex empty ear is left (the caller falls back to the constrained Delaunay triangulation).
bool clip_ears(const std::vector<Vec2>& pts, std::size_t first, std::size_t count,
               std::vector<Triangle>& out) {
  std::vector<std::size_t> ring(count);
  for (std::size_t n = 0; n < count; ++n) ring[n] = first + n;
  while (ring.size() > 3) {
    bool clipped = false;
    for (std::size_t n = 0; n < ring.size() && !clipped; ++n) {
      const std::size_t a = ring[(n + ring.size() - 1) % ring.size()], b = ring[n],
                        c = ring[(n + 1) % ring.size()];
      if (cross2(pts[b] - pts[a], pts[c] - pts[b]) <= 0.0) continue;
      bool empty = true;
      for (std::size_t m : ring) {
        if (m != a && m != b && m != c && in_triangle(pts[m], pts[a], pts[b], pts[c])) {
          empty = false;
          break;
        }
      }
      if (!empty) continue;
      out.push_back({a, b, c});
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(n));
      clipped = true;
    }
    if (!clipped) return false;
  }
  out.push_back({ring[0], ring[1], ring[2]});
  return true;
}

using nesting::Cdt;

// Loops with holes: CGAL's constrained Delaunay triangulation and nesting levels.
std::vector<Triangle> triangulate_with_holes(const std::vector<Vec2>& pts,
                                             const std::vector<std::size_t>& loop_starts) {
  Cdt cdt;
  std::vector<Cdt::Vertex_handle> handles;
  for (std::size_t n = 0; n < pts.size(); ++n) {
    handles.push_back(cdt.insert(Kernel::Point_2(pts[n].x(), pts[n].y())));
    handles.back()->info() = n;
  }
  if (cdt.number_of_vertices() != pts.size()) throw Degenerate{"a face's loops cross"};
  for (std::size_t l = 0; l + 1 < loop_starts.size(); ++l) {
    const std::size_t first = loop_starts[l], end = loop_starts[l + 1];
    for (std::size_t n = first; n < end; ++n)
      cdt.insert_constraint(handles[n], handles[n + 1 == end ? first : n + 1]);
  }
  if (cdt.number_of_vertices() != pts.size()) throw Degenerate{"a face's loops cross"};
  nesting::mark_nesting(cdt);
  std::vector<Triangle> out;
  for (Cdt::Face_handle f : cdt.finite_face_handles()) {
    if (f->info().inside())
      out.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  }
  return out;
}

std::vector<Triangle> triangulate(const std::vector<Loop>& loops, std::vector<Vec2>& pts,
                                  std::vector<Key>& keys) {
  std::vector<std::size_t> starts{0};
  bool holes = false;
  for (const Loop& loop : loops) {
    pts.insert(pts.end(), loop.points.begin(), loop.points.end());
    keys.insert(keys.end(), loop.keys.begin(), loop.keys.end());
    starts.push_back(pts.size());
    holes = holes || loop.area() <= 0.0;
  }
  std::vector<Triangle> out;
  if (!holes) {
    bool ok = true;
    for (std::size_t l = 0; l + 1 < starts.size() && ok; ++l)
      ok = clip_ears(pts, starts[l], starts[l + 1] - starts[l], out);
    if (ok) return out;
  }
  return triangulate_with_holes(pts, starts);
}

// Whether counter-clockwise loops in the domain give inward-facing triangles: the domain's
// orientation against the cone's outward normal (away from the silhouette's interior).
bool flips_orientation(const Assembly& as, const Face& f) {
  const ViewData& vi = as.views[f.view];
  const Vec3 n = f.dk.cross(f.dk1);
  const bool n_inward = vi.edges[f.edge].line.dot(vi.to_camera * n) > 0.0;
  const double u = f.u0 + 0.5 * f.du;
  const Vec3 d_s = (f.dk1 - f.dk) / u;
  const Vec3 d_v = -f.du * (0.5 * (f.dk + f.dk1)) / (u * u);
  const double along_n = d_s.cross(d_v).dot(n);
  return (along_n > 0.0) == n_inward;
}

void build_face(Assembly& as, int i, int k) {
  const std::optional<Face> narrowed = make_face(as, i, k);
  if (!narrowed) return;
  const Face& f = *narrowed;
  std::array<Segment, 4> sides = domain_sides(f);
  std::vector<Segment>& candidates = as.candidate_buffer;
  find_candidates(as, f, sides, candidates);
  split_at_crossings(f, candidates);
  std::vector<Piece>& pieces = as.piece_buffer;
  pieces.clear();
  for (Segment& s : sides) keep_pieces(as, f, s, pieces);
  for (Segment& s : candidates) keep_pieces(as, f, s, pieces);
  if (pieces.empty()) return;
  for (std::size_t j = 0; j < as.views.size(); ++j) {
    if (static_cast<int>(j) != i) as.meets[i][j] = 1;
  }
  const std::vector<Loop> loops = chain_loops(pieces);
  std::vector<Vec2> pts;
  std::vector<Key> keys;
  const std::vector<Triangle> triangles = triangulate(loops, pts, keys);
  const bool flip = flips_orientation(as, f);
  for (const Triangle& t : triangles) {
    const int a = vertex_index(as, keys[t[0]]), b = vertex_index(as, keys[t[1]]),
              c = vertex_index(as, keys[t[2]]);
    as.triangles.push_back(flip ? std::array<int, 3>{a, c, b} : std::array<int, 3>{a, b, c});
  }
}

// The view whose cone meets the fewest other cones: the one to blame for an empty hull.
[[noreturn]] void throw_empty(const std::vector<HullView>& views, const Assembly& as) {
  std::size_t worst = 0;
  long fewest = static_cast<long>(views.size());
  for (std::size_t i = 0; i < views.size(); ++i) {
    const long met = std::ranges::count(as.meets[i], 1);
    if (met < fewest) {
      fewest = met;
      worst = i;
    }
  }
  throw EmptyHullError(views[worst].name +
                       ": its cone misses the others' intersection (empty hull; do the cameras "
                       "and masks agree?)");
}

Mesh to_mesh(const Assembly& as) {
  Mesh mesh;
  mesh.reserve(as.points.size(), 3 * as.triangles.size() / 2, as.triangles.size());
  for (const Vec3& p : as.points) mesh.add_vertex(Point3(p.x(), p.y(), p.z()));
  for (const auto& t : as.triangles) {
    const Mesh::Face_index face =
        mesh.add_face(Mesh::Vertex_index(t[0]), Mesh::Vertex_index(t[1]), Mesh::Vertex_index(t[2]));
    if (face == Mesh::null_face()) throw Degenerate{"a triangle would make the mesh non-manifold"};
  }
  for (Mesh::Halfedge_index h : mesh.halfedges()) {
    if (mesh.is_border(h)) throw Degenerate{"an edge of one face has no neighbour (open mesh)"};
  }
  return mesh;
}

Mesh assemble(const std::vector<HullView>& views, const WorkingVolume& volume, unsigned attempt,
              PolyhedralStats& stats) {
  Assembly as;
  int first_plane = 0;
  for (std::size_t i = 0; i < views.size(); ++i) {
    as.views.push_back(prepare_view(views[i], i, volume, attempt, first_plane));
    first_plane += static_cast<int>(as.views.back().edges.size());
  }
  add_planes(as);
  as.meets.assign(views.size(), std::vector<char>(views.size(), 0));
  for (std::size_t i = 0; i < as.views.size(); ++i) {
    for (std::size_t k = 0; k < as.views[i].edges.size(); ++k)
      build_face(as, static_cast<int>(i), static_cast<int>(k));
  }
  stats.cone_faces = static_cast<std::size_t>(first_plane);
  stats.candidates = as.candidates;
  if (as.triangles.empty()) throw_empty(views, as);
  Mesh mesh = to_mesh(as);
  stats.vertices = mesh.number_of_vertices();
  stats.triangles = mesh.number_of_faces();
  return mesh;
}

}  // namespace

Mesh polyhedral_visual_hull(const std::vector<HullView>& views, const HullOptions& options,
                            PolyhedralStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  PolyhedralStats local;
  PolyhedralStats& s = stats != nullptr ? *stats : local;
  s.volume = checked_working_volume(views, options);
  if (views.size() < 2) throw HullError("the polyhedral hull needs at least two views");
  for (unsigned attempt = 0;; ++attempt) {
    try {
      Mesh mesh = assemble(views, s.volume, attempt, s);
      s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return mesh;
    } catch (const Degenerate& d) {
      s.failed_attempts = attempt + 1;
      s.last_failure = d.what;
      if (attempt + 1 == kPerturbationAttempts) {
        throw HullError(util::printf_string(
            "the polyhedral hull's faces did not assemble into a closed mesh on %u "
            "perturbations of the input (degenerate configuration: %s)",
            kPerturbationAttempts, d.what));
      }
    }
  }
}

}  // namespace syncap::hull
