// Speed of reading a scene file (host/src/sdl): the six-camera ring of 1000 wand frames that
// bench_calib adjusts (18000 image measurements, 9000 points, 2000 distances, ~1.3 MB of SDL).
// Baseline: nlohmann::json parsing the same content as JSON (the same names and numbers, arrays
// instead of statements), a widely used parser for a simpler grammar. R > 1: SDL reads faster.
#include <benchmark/benchmark.h>

#include <nlohmann/json.hpp>
#include <string>

#include "sdl/sdl.hpp"
#include "six_camera_wand_network.hpp"

namespace {

const syncap::scene::Network& six_camera_network() {
  static const syncap::scene::Network network = [] {
    syncap::scene::Network n = syncap::bench::six_camera_wand_network();
    for (auto& point : n.points) point.has_approximation = true;  // as after the adjustment
    return n;
  }();
  return network;
}

std::string as_json(const syncap::scene::Network& n) {
  nlohmann::json json;
  for (const auto& s : n.stations) {
    const auto& e = s.exterior;
    json["stations"].push_back({s.name, s.model, e.X0, e.Y0, e.Z0, e.omega, e.phi, e.kappa});
  }
  for (const auto& p : n.points) json["points"].push_back({p.name, p.xyz[0], p.xyz[1], p.xyz[2]});
  for (const auto& m : n.measurements) {
    json["measurements"].push_back({m.station, m.point, m.u, m.v, m.sigma_px, m.frame_number});
  }
  for (const auto& d : n.distances) {
    json["distances"].push_back({d.point_a, d.point_b, d.distance, d.sigma});
  }
  return json.dump();
}

void parse_sdl(benchmark::State& state) {
  const std::string text = syncap::sdl::write(six_camera_network());
  for (auto _ : state) {
    const syncap::scene::Network n = syncap::sdl::parse_string(text, "bench.sdl");
    benchmark::DoNotOptimize(n.measurements.data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * text.size()));
}

void parse_json(benchmark::State& state) {
  const std::string text = as_json(six_camera_network());
  for (auto _ : state) {
    const nlohmann::json json = nlohmann::json::parse(text);
    benchmark::DoNotOptimize(json.size());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * text.size()));
}

void write_sdl(benchmark::State& state) {
  for (auto _ : state) {
    const std::string text = syncap::sdl::write(six_camera_network());
    benchmark::DoNotOptimize(text.data());
  }
}

void write_json(benchmark::State& state) {
  for (auto _ : state) {
    const std::string text = as_json(six_camera_network());
    benchmark::DoNotOptimize(text.data());
  }
}

BENCHMARK(parse_sdl)
    ->Name("sdl-parse-6cam-1000/ours")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(parse_json)
    ->Name("sdl-parse-6cam-1000/baseline")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(write_sdl)
    ->Name("sdl-write-6cam-1000/ours")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(write_json)
    ->Name("sdl-write-6cam-1000/baseline")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
