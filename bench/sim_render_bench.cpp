// Rendering speed of the scene generator: one frame of six 640x480 cameras with the room, a
// person-sized set of ellipsoids, their shadow and sensor noise (the ring-6cam-person setup).
// Goal (replay-bench issue): 50 frames per second or more on one core. Baseline in the same
// process: the same frame with every pixel tested against every ellipsoid (no culling).
#include <benchmark/benchmark.h>

#include "camera_rig.hpp"
#include "render.hpp"
#include "scenario.hpp"

namespace {

using syncap::sim::Ellipsoid;

// Fifteen limb-sized ellipsoids standing at the origin: the load of one person.
std::vector<Ellipsoid> person_load() {
  struct Limb {
    double x, y, z, rx, ry, rz;
  };
  const Limb limbs[] = {
      {0, 0, 1100, 170, 110, 280}, {0, 0, 1600, 100, 100, 120}, {-90, 0, 700, 70, 70, 230},
      {90, 0, 700, 70, 70, 230},   {-90, 0, 250, 55, 55, 220},  {90, 0, 250, 55, 55, 220},
      {-90, 60, 30, 50, 110, 35},  {90, 60, 30, 50, 110, 35},   {-250, 0, 1250, 45, 45, 150},
      {250, 0, 1250, 45, 45, 150}, {-260, 0, 950, 40, 40, 130}, {260, 0, 950, 40, 40, 130},
      {-265, 0, 780, 35, 25, 60},  {265, 0, 780, 35, 25, 60},   {0, 0, 1430, 50, 50, 60}};
  std::vector<Ellipsoid> body;
  for (const Limb& l : limbs) {
    Ellipsoid e;
    e.centre_mm = {l.x, l.y, l.z};
    e.radii_mm = {l.rx, l.ry, l.rz};
    body.push_back(e);
  }
  return body;
}

struct Setup {
  syncap::sim::Scenario scenario;
  std::vector<syncap::sim::View> views;
  syncap::sim::FrameContent content;
};

const Setup& setup() {
  static const Setup s = [] {
    Setup out;
    out.scenario = syncap::sim::load_scenario(std::string(SYNCAP_SOURCE_DIR) +
                                              "/hil/scenarios/ring-6cam-person.yaml");
    for (const auto& camera : syncap::sim::build_rig(out.scenario)) {
      out.views.push_back(syncap::sim::make_view(camera, out.scenario));
    }
    out.content.room_background = true;
    out.content.body = person_load();
    return out;
  }();
  return s;
}

void BM_RenderSixCameras(benchmark::State& state) {
  const Setup& s = setup();
  uint64_t seed = 1;
  for (auto _ : state) {
    for (const auto& view : s.views) {
      benchmark::DoNotOptimize(syncap::sim::render_view(view, s.content, s.scenario.image, ++seed));
    }
  }
  state.SetItemsProcessed(state.iterations());  // frames (of six cameras) per second
}
// scripts/bench.sh pairs "<name>/ours" with "<name>/baseline".
BENCHMARK(BM_RenderSixCameras)
    ->Name("sim-render-vs-no-culling/ours")
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);

void BM_BaselineSilhouetteWithoutCulling(benchmark::State& state) {
  const Setup& s = setup();
  for (auto _ : state) {
    for (const auto& view : s.views) {
      benchmark::DoNotOptimize(syncap::sim::silhouette_brute_force(view, s.content.body));
    }
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_BaselineSilhouetteWithoutCulling)
    ->Name("sim-render-vs-no-culling/baseline")
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
