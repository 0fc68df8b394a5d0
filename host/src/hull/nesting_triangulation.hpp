// The constrained Delaunay triangulation that triangulates nested polygons (outlines, holes,
// islands in holes) for the viewing cones' caps and the polyhedral hull's faces, and its nesting
// levels (CGAL's polygon-with-holes example): a face's level counts the constraints crossed on
// the way from the outside, odd levels are inside. Internal to host/src/hull's .cpp files: it
// includes CGAL's triangulation headers, which hull/mesh.hpp's users need not compile.
#pragma once

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cstddef>
#include <list>

#include "hull/mesh.hpp"

namespace syncap::hull::nesting {

struct FaceInfo {
  int nesting = -1;  // constraints crossed from the outside; -1 before mark_nesting
  bool inside() const { return nesting % 2 == 1; }
};

using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::size_t, Kernel>;
using Fbi = CGAL::Triangulation_face_base_with_info_2<FaceInfo, Kernel>;
using Fb = CGAL::Constrained_triangulation_face_base_2<Kernel, Fbi>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// Exact_predicates_tag: constraints that cross become a vertex at the crossing instead of an
// exception; a caller that must not have crossings compares the vertex count.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_predicates_tag>;

// Flood fill from `start` up to the constrained edges: the faces of one level; the constrained
// edges met are queued in `border`.
inline void mark_level(Cdt& cdt, Cdt::Face_handle start, int level, std::list<Cdt::Edge>& border) {
  std::list<Cdt::Face_handle> queue{start};
  while (!queue.empty()) {
    Cdt::Face_handle f = queue.front();
    queue.pop_front();
    if (f->info().nesting != -1) continue;
    f->info().nesting = level;
    for (int i = 0; i < 3; ++i) {
      if (f->neighbor(i)->info().nesting != -1) continue;
      if (cdt.is_constrained(Cdt::Edge(f, i))) {
        border.emplace_back(f, i);
      } else {
        queue.push_back(f->neighbor(i));
      }
    }
  }
}

// Every face's nesting level, from the infinite face (level 0) inwards.
inline void mark_nesting(Cdt& cdt) {
  std::list<Cdt::Edge> border;
  mark_level(cdt, cdt.infinite_face(), 0, border);
  while (!border.empty()) {
    const Cdt::Edge e = border.front();
    border.pop_front();
    Cdt::Face_handle n = e.first->neighbor(e.second);
    if (n->info().nesting == -1) mark_level(cdt, n, e.first->info().nesting + 1, border);
  }
}

}  // namespace syncap::hull::nesting
