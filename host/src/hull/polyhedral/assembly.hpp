// The polyhedral hull's assembly: the planes of every cone face and cap, the vertices named by the
// three planes that meet there (so that neighbouring faces agree on them), the triangles of every
// face, and the candidates and pieces of the face being built.
#pragma once

#include <boost/container/small_vector.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "hull/mesh.hpp"
#include "hull/polyhedral/view_data.hpp"

namespace syncap::hull::polyhedral {

using Key = std::uint64_t;  // a vertex: the sorted triple of the plane ids that meet there

constexpr int kPlaneBits = 21;

// A configuration the combinatorial assembly cannot name consistently (four planes through one
// point, a crossing missed by rounding): retried with another perturbation.
struct Degenerate {
  const char* what;  // which step found it, for the final error
};

inline Key key_of(int a, int b, int c) {
  if (a > b) std::swap(a, b);
  if (b > c) std::swap(b, c);
  if (a > b) std::swap(a, b);
  return (static_cast<Key>(a) << (2 * kPlaneBits)) | (static_cast<Key>(b) << kPlaneBits) |
         static_cast<Key>(c);
}

// Planes n . X = d, n unit: cone faces (by view, edge), then each view's near and far cap.
struct Plane {
  Vec3 n;
  double d = 0.0;
};

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

// The vertex of `key`, added (the three planes' intersection) when new. Throws Degenerate for
// nearly parallel planes.
int vertex_index(Assembly& as, Key key);
// The planes of every view's cone faces, then each view's near and far cap.
void add_planes(Assembly& as);
// The triangles as a closed mesh; throws Degenerate where they are not one.
Mesh to_mesh(const Assembly& as);
[[noreturn]] void throw_empty(const std::vector<HullView>& views, const Assembly& as);

}  // namespace syncap::hull::polyhedral
