// Surface matching (docs/design/matching.md) on a textured sphere rendered exactly, seen by five
// 640x480 cameras 30 degrees apart (tests/host/surface/textured_scene.hpp), its hull an
// icosphere 20 mm larger; one thread:
// - lsm-vs-ncc-sweep/ours: GC3 along every seed's scan line, the candidate rules, then
//   multi-image least squares (the method);
// - lsm-vs-ncc-sweep/baseline: the same seeds, scan lines and rules, the SNCC peak (refined by a
//   parabola) as the point: the plain NCC sweep.
// R = baseline time / our time (below 1: least squares costs more); the counters give each
// side's points, their radial RMS against the true sphere [mm] and points per second, and
// scripts/bench.sh prints the precision ratio (the baseline's RMS over ours).
#include <benchmark/benchmark.h>

#include <cmath>

#include "surface/surface_matcher.hpp"
#include "surface/textured_scene.hpp"

namespace {

using namespace syncap::surface;

const std::vector<MatchingView>& views() {
  static const std::vector<MatchingView> v =
      test::render_views(test::arc_cameras(5, 30.0, test::Sphere{}), test::Sphere{}, 2.0);
  return v;
}

void match(benchmark::State& state, bool least_squares) {
  const test::Sphere sphere;
  const auto hull = test::icosphere(sphere.centre, sphere.radius + 20, 3);
  SurfaceMatchingOptions options;
  options.least_squares = least_squares;
  SurfaceMatchingResult r;
  for (auto _ : state) {
    r = match_surface(views(), hull, options);
    benchmark::DoNotOptimize(r.points.data());
  }
  double sum2 = 0;
  for (const auto& p : r.points) {
    const double e = (p.point - sphere.centre).norm() - sphere.radius;
    sum2 += e * e;
  }
  state.counters["points"] = static_cast<double>(r.points.size());
  state.counters["error_rms"] = std::sqrt(sum2 / static_cast<double>(r.points.size()));
  state.counters["points_per_s"] = benchmark::Counter(
      static_cast<double>(r.points.size()), benchmark::Counter::kIsIterationInvariantRate);
}

void lsm(benchmark::State& state) { match(state, true); }
void sweep(benchmark::State& state) { match(state, false); }

BENCHMARK(lsm)->Name("lsm-vs-ncc-sweep/ours")->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(sweep)->Name("lsm-vs-ncc-sweep/baseline")->Unit(benchmark::kMillisecond)->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
