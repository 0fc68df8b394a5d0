// One cone face of the polyhedral hull in its own domain (s, v) in [0, 1]^2: how the other views
// see it, the boundary candidates (its sides and the other views' contour edges crossing it),
// and the pieces of them inside every other cone, which bound the hull's part of the face.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "hull/polyhedral/assembly.hpp"

namespace syncap::hull::polyhedral {

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

// The face (view i, edge k) with its domain's depth range narrowed to the other silhouettes'
// boxes; nullopt when the face has no part of the hull. Throws HullError when the working
// volume reaches behind a camera.
std::optional<Face> make_face(const Assembly& as, int i, int k);
// The domain's four sides as boundary candidates.
std::array<Segment, 4> domain_sides(const Face& f);
// The other views' contour edges whose cone faces cross this face inside the working volume;
// endpoints on a side split that side.
void find_candidates(Assembly& as, const Face& f, std::array<Segment, 4>& sides,
                     std::vector<Segment>& candidates);
// Splits every two candidates of different views where they cross.
void split_at_crossings(const Face& f, std::vector<Segment>& candidates);
// The pieces of a segment inside every other cone, directed with the face's region on the
// left. Throws HullError where the working volume cuts the hull, Degenerate for crossings named
// alike.
void keep_pieces(const Assembly& as, const Face& f, Segment& s, std::vector<Piece>& pieces);
// Whether counter-clockwise loops in the domain give inward-facing triangles.
bool flips_orientation(const Assembly& as, const Face& f);

}  // namespace syncap::hull::polyhedral
