// Speed of `syncap calibrate --led` on a big rig (issue 37): the simulated 20-camera arena of
// tests/host/calibration/big_led_rig.hpp (1920x1200, c ~ 2600 px, barrel lenses, one LED over
// 5000 frames seen in stretches, noise, a systematic centroid bias, blunders), calibrated with
// every default, as the command does: start search, network start, model selection, data
// snooping, check points, halves. Goal: <= 2 min on one core. Each step's start is printed on
// stderr with the seconds since the calibration began (the share of the time in each), and the
// counters say whether the minimum is the truth's: the worst focal length's error, the cameras'
// centres after a similarity against their sigmas.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>

#include "big_led_rig.hpp"
#include "calibration/calibrate.hpp"

namespace {

using namespace syncap;

void calibrate_big_rig(benchmark::State& state) {
  const calibration::test::BigLedRig rig =
      calibration::test::big_led_rig(static_cast<int>(state.range(0)), 5000);
  calibration::CalibrationOptions options;
  options.wand.led = true;
  options.pixel_size_mm = calibration::test::kBigRigPixelMm;
  for (auto _ : state) {
    const auto begin = std::chrono::steady_clock::now();
    options.progress = [begin](const std::string& line) {
      const double s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
      std::cerr << "  " << std::fixed << std::setprecision(1) << s << " s: " << line << '\n';
    };
    const calibration::CalibrationResult r = calibration::calibrate(rig.observations, options);
    if (!r.adjustment.converged) state.SkipWithError("the adjustment did not converge");
    const calibration::test::RigErrors e = calibration::test::rig_errors(rig, r);
    state.counters["worst_focal_error"] = e.worst_focal;
    state.counters["centres_rms"] = e.centres;
    state.counters["centre_sigma_rms"] = e.centre_sigma;
    state.counters["focal_z_rms"] = e.focal_z_rms;
    state.counters["measurements"] = static_cast<double>(r.network.measurements.size());
  }
  state.counters["frames"] = static_cast<double>(rig.observations.frames.size());
}

BENCHMARK(calibrate_big_rig)
    ->Name("calibrate-20cam/ours")
    ->Arg(20)
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
