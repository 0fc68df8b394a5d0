#include "hull/polyhedral/face_triangulation.hpp"

#include <algorithm>

#include "hull/nesting_triangulation.hpp"

namespace syncap::hull::polyhedral {

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

namespace {

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

}  // namespace

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

}  // namespace syncap::hull::polyhedral
