// Speed of the self-calibrating bundle adjustment (host/src/estimators): six cameras on a ring,
// 1000 wand frames with three targets each (18000 image measurements, 9000 object points), all
// ten interior and six exterior parameters per camera estimated from perturbed start values with
// triangulated points, then the covariance (S-transformed to the inner-constraint datum), the
// standardised residuals and the tests. Goal: <= 2 s on one core. Data snooping's re-adjustments
// are left out: without blunders they would only repeat the same work for the ~1/1000 good
// measurements beyond the critical value.
#include <benchmark/benchmark.h>

#include "estimators/bundle_adjustment.hpp"
#include "six_camera_wand_network.hpp"

namespace {

using syncap::estimators::adjust;
using syncap::estimators::BundleAdjustmentResult;

const syncap::scene::Network& six_camera_network() {
  static const syncap::scene::Network network = [] {
    syncap::scene::Network n = syncap::bench::six_camera_wand_network();
    n.residual_test.iterative_rejection = false;
    return n;
  }();
  return network;
}

void calibrate(benchmark::State& state) {
  const syncap::scene::Network& network = six_camera_network();
  for (auto _ : state) {
    const BundleAdjustmentResult r = adjust(network, {});
    if (!r.converged || !r.covariance_computed) state.SkipWithError(r.termination.c_str());
    benchmark::DoNotOptimize(r.sigma0);
    state.counters["iterations"] = r.iterations;
    state.counters["sigma0"] = r.sigma0;
  }
  state.counters["measurements"] = static_cast<double>(network.measurements.size());
}

BENCHMARK(calibrate)->Name("calib-6cam-1000/ours")->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
