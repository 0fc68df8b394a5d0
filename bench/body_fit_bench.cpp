// The body fit of one frame (docs/design/body-fit.md; issue 18's body-fit-frame: >= 30 frames/s on
// one core). ours: a tracked frame, fitted from the prediction of the two before (as BodyTracker
// does) on points of a random pose moving smoothly; baseline: the same frame fitted from the rest
// pose at the body's place (no warm start). Both fit the same ~700 points of the body's surface (2
// mm noise). The counter joint_rms_mm says how near the truth each one lands.
#include <benchmark/benchmark.h>

#include <random>

#include "body/hanim_model.hpp"
#include "body_scenes.hpp"
#include "fitting/surface_fit.hpp"

namespace {

using namespace syncap::fitting;

struct Scene {
  PoseParameters parameters{syncap::body::hanim_skeleton()};
  PoseVector before_last{}, last{}, truth{};
  std::vector<SurfacePoint> points;
  Scene() {
    std::mt19937 rng(17);
    before_last = test::random_pose(rng, 0.3);
    PoseVector step{};
    step[0] = 40.0;  // 1.2 m/s at 30 Hz
    for (std::size_t i = 6; i < step.size(); ++i) step[i] = 0.03;
    for (std::size_t i = 0; i < step.size(); ++i) {
      last[i] = before_last[i] + step[i];
      truth[i] = last[i] + step[i];
    }
    points = test::surface_points(
        syncap::body::body_frame(parameters.skeleton(), parameters.pose(truth.data())), 40, rng,
        2.0);
  }
};

const Scene& scene() {
  static const Scene s;
  return s;
}

// What BodyTracker::track does on the third frame: the fit from the constant-velocity
// prediction of the two before.
void tracked_frame(benchmark::State& state) {
  const Scene& s = scene();
  PoseVector predicted{};
  for (std::size_t i = 0; i < predicted.size(); ++i)
    predicted[i] = 2.0 * s.last[i] - s.before_last[i];
  PoseVector fitted{};
  for (auto _ : state) {
    fitted = fit_surface(s.parameters, s.points, predicted).x;
    benchmark::DoNotOptimize(fitted);
  }
  state.counters["points"] = static_cast<double>(s.points.size());
  state.counters["joint_rms_mm"] = test::joint_rms_mm(s.parameters, fitted, s.truth);
}

void from_rest(benchmark::State& state) {
  const Scene& s = scene();
  PoseVector start = s.parameters.rest();
  start[0] = s.truth[0], start[1] = s.truth[1];
  PoseVector fitted{};
  for (auto _ : state) {
    fitted = fit_surface(s.parameters, s.points, start).x;
    benchmark::DoNotOptimize(fitted);
  }
  state.counters["joint_rms_mm"] = test::joint_rms_mm(s.parameters, fitted, s.truth);
}

}  // namespace

BENCHMARK(tracked_frame)->Name("body-fit-frame/ours")->Unit(benchmark::kMillisecond);
BENCHMARK(from_rest)->Name("body-fit-frame/baseline")->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
