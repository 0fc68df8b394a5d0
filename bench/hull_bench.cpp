// The visual hull (docs/design/visual-hull.md), on 8 person silhouettes at 640x480 (contours
// simplified by 1 px, the library's default; hull-8cam-0.5px: by 0.5 px, as the edges send them: 3x
// the candidates, 2.6x the time):
// - hull-8cam/ours: the exact hull by the polyhedral method, the live stage's (issue 17's goal:
//   <= 10 ms per frame on one core); its counters: the candidates it tested, its agreement with
//   the masks and with the voxel hull at 256 (the worst view's reprojection IoU);
// - hull-exact-vs-voxel: the same hull against the voxel baseline at 256 cells along the hull's
//   longest side (R = voxel time / polyhedral time, at no worse IoU: the counters above);
// - hull-corefinement-8cam: the same solid by CGAL's corefinement (the reference; seconds).
// The silhouettes are extracted once, outside the timing; the time is the hull's.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>

#include "hull/polyhedral_hull.hpp"
#include "hull/visual_hull.hpp"
#include "hull/voxel_hull.hpp"
#include "hull_scenes.hpp"

namespace {

using namespace syncap::hull;

const std::vector<HullView>& person_views(double simplify_px = kDefaultSimplifyPx) {
  static std::map<double, std::vector<HullView>> views;
  auto [at, added] = views.try_emplace(simplify_px);
  if (added) at->second = test::views_of(test::person_mesh(), test::person_cameras(), simplify_px);
  return at->second;
}

void exact_hull(benchmark::State& state) {  // corefinement
  const std::vector<HullView>& views = person_views();
  std::size_t faces = 0;
  for (auto _ : state) {
    const Mesh hull = exact_visual_hull(views);
    faces = hull.number_of_faces();
    benchmark::DoNotOptimize(faces);
  }
  state.counters["faces"] = static_cast<double>(faces);
  state.counters["silhouette_vertices"] = [&] {
    std::size_t n = 0;
    for (const HullView& v : views) n += v.silhouette.vertex_count();
    return static_cast<double>(n);
  }();
}

void voxel_hull_256(benchmark::State& state) {
  const std::vector<HullView>& views = person_views();
  for (auto _ : state) {
    const Mesh hull = voxel_visual_hull(views, {256});
    benchmark::DoNotOptimize(hull.number_of_faces());
  }
}

// The worst view's IoU of the two meshes' reprojections.
double min_iou_between(const Mesh& a, const Mesh& b, const std::vector<HullView>& views) {
  double worst = 1.0;
  for (const HullView& v : views) {
    worst = std::min(worst, mask_iou(render_mask(a, v.camera), render_mask(b, v.camera)));
  }
  return worst;
}

void polyhedral_hull(benchmark::State& state, double simplify_px) {
  const std::vector<HullView>& views = person_views(simplify_px);
  PolyhedralStats stats;
  for (auto _ : state) {
    const Mesh hull = polyhedral_visual_hull(views, {}, &stats);
    benchmark::DoNotOptimize(hull.number_of_faces());
  }
  const Mesh hull = polyhedral_visual_hull(views);
  state.counters["faces"] = static_cast<double>(stats.triangles);
  state.counters["candidates"] = static_cast<double>(stats.candidates);
  state.counters["failed_attempts"] = stats.failed_attempts;
  state.counters["min_iou_vs_voxel256"] =
      min_iou_between(hull, voxel_visual_hull(views, {256}), views);
  state.counters["min_iou_vs_masks"] = test::min_reprojection_iou(hull, views);
}

}  // namespace

BENCHMARK_CAPTURE(polyhedral_hull, 1px, kDefaultSimplifyPx)
    ->Name("hull-8cam/ours")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(polyhedral_hull, 0.5px, 0.5)
    ->Name("hull-8cam-0.5px")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(polyhedral_hull, 1px, kDefaultSimplifyPx)
    ->Name("hull-exact-vs-voxel/ours")
    ->Unit(benchmark::kMillisecond);
BENCHMARK(exact_hull)->Name("hull-corefinement-8cam")->Unit(benchmark::kMillisecond);
BENCHMARK(voxel_hull_256)->Name("hull-exact-vs-voxel/baseline")->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
