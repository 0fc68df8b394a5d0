// The host's JSON line of one frame group as the 8-camera mocap log gives them (8 cameras x 40
// blobs, 33 tracked markers with their sigmas, a rigid set; "-silhouettes": a person's outline of
// ~340 points in every camera as well): io::append_frame_line into a reused string against
// nlohmann::json's document and dump(), the writer before it (tests/host/io/
// frame_json_reference.hpp). scripts/bench.sh prints "frame-json: R x" and
// "frame-json-silhouettes: R x".
#include <benchmark/benchmark.h>

#include <random>
#include <string>
#include <vector>

#include "frame_json_reference.hpp"
#include "io/frame_json.hpp"
#include "sample_groups.hpp"

namespace {

// 16 different groups, cycled: one group's cost, not one lucky group's.
std::vector<syncap::pipeline::FrameWork> groups(bool silhouettes) {
  std::mt19937 rng(5);
  syncap::test::SampleGroupOptions o;
  o.silhouettes = silhouettes;
  std::vector<syncap::pipeline::FrameWork> out;
  for (int i = 0; i < 16; ++i) out.push_back(syncap::test::sample_group(rng, o));
  return out;
}

void BM_Ours(benchmark::State& state, bool silhouettes) {
  const auto works = groups(silhouettes);
  std::string line;
  std::size_t i = 0, bytes = 0;
  for (auto _ : state) {
    line.clear();  // as outputs::JsonLinesStage does
    syncap::io::append_frame_line(line, works[i++ % works.size()], true);
    bytes += line.size();
    benchmark::DoNotOptimize(line.data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(bytes));
}

void BM_Nlohmann(benchmark::State& state, bool silhouettes) {
  const auto works = groups(silhouettes);
  std::size_t i = 0, bytes = 0;
  for (auto _ : state) {
    const std::string line =
        syncap::test::reference_frame_json(works[i++ % works.size()], true).dump();
    bytes += line.size();
    benchmark::DoNotOptimize(line.data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(bytes));
}

BENCHMARK_CAPTURE(BM_Ours, blobs, false)->Name("frame-json/ours")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Nlohmann, blobs, false)
    ->Name("frame-json/baseline")
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Ours, silhouettes, true)
    ->Name("frame-json-silhouettes/ours")
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_Nlohmann, silhouettes, true)
    ->Name("frame-json-silhouettes/baseline")
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
