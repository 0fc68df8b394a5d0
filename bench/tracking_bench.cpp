// The live reconstruction's tracking step (docs/design/reconstruction.md, "Tracking"): one frame of
// 32 markers (10 % hidden in runs of 1..5 frames, ~1 spurious point, 100 Hz) through the
// MarkerTracker. Goal: matching + triangulation + tracking of a group of 8 cameras x 32 markers
// <= 0.5 ms on one core, of which matching and triangulation take ~0.39 ms; tracking must stay
// well under 0.1 ms. scripts/bench.sh prints "tracking-32-markers: S s on one core".
#include <benchmark/benchmark.h>

#include "synthetic_motion.hpp"
#include "tracking/marker_tracker.hpp"

namespace {

void BM_Tracking(benchmark::State& state) {
  syncap::test::MotionOptions o;
  o.frames = 2000;
  const syncap::test::Motion motion = syncap::test::simulate_motion(o);
  syncap::tracking::MarkerTracker tracker;
  std::size_t i = 0;
  int64_t loop_start = 0;  // replayed in a loop, 100 frames apart: the old tracks end
  for (auto _ : state) {
    const auto& f = motion.frames[i];
    const int64_t frame = loop_start + f.frame;
    benchmark::DoNotOptimize(tracker.update(frame, frame / o.rate_hz, f.points).ids.data());
    if (++i == motion.frames.size()) {
      i = 0;
      loop_start = frame + 100;
    }
  }
}
BENCHMARK(BM_Tracking)->Name("tracking-32-markers/ours")->Unit(benchmark::kMicrosecond);

}  // namespace
BENCHMARK_MAIN();
