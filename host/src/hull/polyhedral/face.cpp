#include "hull/polyhedral/face.hpp"

#include <algorithm>

#include "util/printf_string.hpp"

namespace syncap::hull::polyhedral {

namespace {

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

}  // namespace

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
            "the working volume reaches behind camera %zu (the working volume is the ball around "
            "the silhouettes' rays, its radius times --hull-margin): give a smaller --hull-margin",
            j));
      }
    }
  }
  return f;
}

namespace {

[[noreturn]] void throw_cut_by_volume() {
  throw HullError(
      "the working volume cuts the hull (the hull reaches its near or far bound; the working "
      "volume is the ball around the silhouettes' rays, its radius times --hull-margin): give a "
      "larger --hull-margin");
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

}  // namespace

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

namespace {

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

}  // namespace

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

}  // namespace syncap::hull::polyhedral
