// A cone face's hull part as triangles: its boundary pieces chained into loops, each loop
// ear-clipped (or, with holes, a constrained Delaunay triangulation and nesting levels).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "hull/polyhedral/assembly.hpp"

namespace syncap::hull::polyhedral {

// One closed boundary loop of a face's hull part, in the domain, with its vertices' keys.
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

// The pieces chained into closed loops; throws Degenerate where they do not close.
std::vector<Loop> chain_loops(std::vector<Piece>& pieces);

using Triangle = std::array<std::size_t, 3>;  // indices into the face's loop points

// The loops' triangles; `pts` and `keys` receive the loops' points and keys in order.
std::vector<Triangle> triangulate(const std::vector<Loop>& loops, std::vector<Vec2>& pts,
                                  std::vector<Key>& keys);

}  // namespace syncap::hull::polyhedral
