// The live marker reconstruction's per-group work (docs/design/reconstruction.md, "Speed"):
// matching and triangulation of one group of 8 cameras x 32 markers with 3 reflections per camera
// and 15 % of the views hidden, against the brute force (every blob pair of every camera pair
// triangulated and checked in all other cameras) on the same groups. scripts/bench.sh prints
// "markers-8cam-vs-bruteforce: R x".
#include <benchmark/benchmark.h>

#include "matching/brute_force_matcher.hpp"
#include "matching/marker_matcher.hpp"
#include "synthetic_markers.hpp"

namespace {

using syncap::matching::MarkerMatcher;

// 20 different groups, cycled: one group's cost, not one lucky group's.
const std::vector<syncap::test::MarkerFrame>& groups() {
  static const std::vector<syncap::test::MarkerFrame> frames = [] {
    std::mt19937 rng(4);
    const auto cameras = syncap::test::marker_ring(8);
    std::vector<syncap::test::MarkerFrame> out;
    for (int i = 0; i < 20; ++i) {
      out.push_back(syncap::test::observe(cameras, syncap::test::random_markers(rng, 32),
                                          syncap::test::MarkerFrameOptions{}, rng));
    }
    return out;
  }();
  return frames;
}

syncap::matching::MatchOptions volume_options() {
  syncap::matching::MatchOptions o;
  o.volume =
      Eigen::AlignedBox3d(Eigen::Vector3d(-1000, -1000, 0), Eigen::Vector3d(1000, 1000, 2000));
  return o;
}

void BM_Ours(benchmark::State& state) {
  const MarkerMatcher matcher(syncap::test::marker_ring(8), volume_options());
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(matcher.match(groups()[i++ % groups().size()].blobs));
  }
}
BENCHMARK(BM_Ours)->Name("markers-8cam-vs-bruteforce/ours")->Unit(benchmark::kMicrosecond);

void BM_BruteForce(benchmark::State& state) {
  const auto cameras = syncap::test::marker_ring(8);
  const auto options = volume_options();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(syncap::matching::match_by_brute_force(
        cameras, groups()[i++ % groups().size()].blobs, options));
  }
}
BENCHMARK(BM_BruteForce)
    ->Name("markers-8cam-vs-bruteforce/baseline")
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
