// The visual hull (docs/visual-hull.md): hull-8cam, the exact hull of 8 person silhouettes at
// 640x480 (issue 17's goal: <= 10 ms per frame on one core), and hull-exact-vs-voxel, the exact
// hull against the voxel baseline at 256 cells along the hull's longest side (R = voxel time /
// exact time), and hull-polyhedral-8cam, the polyhedral hull of the same views (R against the
// voxel baseline = the baseline's time / its time; its agreement with the voxel hull as the min
// over the views of the IoU of the two hulls' reprojections). The silhouettes are extracted once,
// outside the timing; the time is the hull's.
#include <benchmark/benchmark.h>

#include <algorithm>

#include "hull/polyhedral_hull.hpp"
#include "hull/voxel_hull.hpp"
#include "hull_scenes.hpp"

namespace {

using namespace syncap::hull;

const std::vector<HullView>& person_views() {
  static const std::vector<HullView> views =
      test::views_of(test::person_mesh(), test::person_cameras());
  return views;
}

void exact_hull(benchmark::State& state) {
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

void polyhedral_hull(benchmark::State& state) {
  const std::vector<HullView>& views = person_views();
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

BENCHMARK(polyhedral_hull)->Name("hull-polyhedral-8cam")->Unit(benchmark::kMillisecond);
BENCHMARK(exact_hull)->Name("hull-8cam/ours")->Unit(benchmark::kMillisecond);
BENCHMARK(exact_hull)->Name("hull-exact-vs-voxel/ours")->Unit(benchmark::kMillisecond);
BENCHMARK(voxel_hull_256)->Name("hull-exact-vs-voxel/baseline")->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
