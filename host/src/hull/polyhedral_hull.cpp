// The polyhedral visual hull, cone face by cone face (docs/design/visual-hull.md, "The polyhedral
// method"). Notation: view i's contour edge k spans the cone face f = (i, k) between the rays D_k
// and D_{k+1} from the projection centre C_i, the rays scaled to depth 1 along the viewing axis.
// The face's domain is (s, v) in [0, 1]^2: X = C_i + Dir(s) / u, Dir(s) = D_k + s (D_{k+1} - D_k),
// u = u0 + v du the inverse depth between the working volume's far and near side. Lines in 3D on
// the face are lines in (s, v), and view j sees the domain through a 3x3 map G_j (its ideal image
// coordinates, homogeneous, the third row positive in front of it).
#include "hull/polyhedral_hull.hpp"

#include <chrono>

#include "hull/capture_volume.hpp"
#include "hull/polyhedral/assembly.hpp"
#include "hull/polyhedral/face.hpp"
#include "hull/polyhedral/face_triangulation.hpp"
#include "hull/polyhedral/view_data.hpp"
#include "util/printf_string.hpp"

// The steps, one file each in hull/polyhedral/: a view's contour edges and their bins
// (view_data), the planes, vertex names and mesh (assembly), a cone face's boundary in its
// domain (face), its triangles (face_triangulation). This file builds every face and retries a
// degenerate assembly with the next perturbation.
namespace syncap::hull {

namespace {

using namespace polyhedral;

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
  const std::vector<polyhedral::Triangle> triangles = triangulate(loops, pts, keys);
  const bool flip = flips_orientation(as, f);
  for (const polyhedral::Triangle& t : triangles) {
    const int a = vertex_index(as, keys[t[0]]), b = vertex_index(as, keys[t[1]]),
              c = vertex_index(as, keys[t[2]]);
    as.triangles.push_back(flip ? std::array<int, 3>{a, c, b} : std::array<int, 3>{a, b, c});
  }
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
      Mesh mesh = finished(assemble(views, s.volume, attempt, s), options);
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
