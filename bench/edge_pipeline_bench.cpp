// CPU time of syncap-edge's per-frame work at 1280x1024, as EdgeNode::on_trigger does it on a
// board: copy the camera buffer, detect the blobs, (with --mode both) the medi-picture mask and
// its contours, encode the messages. Publishing is a no-op here (on a board it is the publishing
// queue's thread). Prints per mode the mean CPU ms per frame of the calling thread and the share
// of one core that costs at 30 Hz:
//
//   ninja -C build bench_edge_pipeline && build/bin/bench_edge_pipeline
//
// Frames (edge_bench_frames.hpp): a lit room, a moving person-sized ellipse and 16 markers, 8
// different frames in turn: what the replay bench renders, at the thesis' camera size.
#include <benchmark/benchmark.h>

#include <ctime>
#include <vector>

#include "app/edge_node.hpp"
#include "edge_bench_frames.hpp"

namespace {

using namespace syncap::edge;
using namespace syncap::edge::bench;

double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

void BM_EdgePipeline(benchmark::State& state, bool mask) {
  EdgeOptions options;
  options.quiet = true;
  options.detector.threshold = 200;  // the replay bench's: targets above the lit room
  options.mask = mask;
  options.train_frames = mask ? kTrainingFrames : 0;
  BenchSource source;
  int64_t blobs = 0, silhouette_parts = 0;
  EdgeNode node(options, source,
                {[&](const syncap::blob_frame_t& f) { blobs += f.num_blobs; },
                 [](const syncap::camera_status_t&) {},
                 [&](const syncap::silhouette_part_t&) { ++silhouette_parts; },
                 {}});
  syncap::trigger_t trigger{};
  for (; trigger.frame_number < kTrainingFrames; ++trigger.frame_number) node.on_trigger(trigger);
  blobs = silhouette_parts = 0;
  const double cpu_start = thread_cpu_s();
  int64_t frames = 0;
  for (auto _ : state) {
    node.on_trigger(trigger);
    ++trigger.frame_number;
    ++frames;
  }
  const double cpu_ms = (thread_cpu_s() - cpu_start) * 1e3 / static_cast<double>(frames);
  state.counters["cpu_ms_per_frame"] = cpu_ms;
  state.counters["core_pct_at_30Hz"] = cpu_ms * 30.0 / 10.0;  // ms per 1000 ms, in %
  state.counters["blobs_per_frame"] = static_cast<double>(blobs) / static_cast<double>(frames);
  state.counters["silhouette_parts_per_frame"] =
      static_cast<double>(silhouette_parts) / static_cast<double>(frames);
}
BENCHMARK_CAPTURE(BM_EdgePipeline, blobs, false)
    ->Name("edge-pipeline/blobs")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_EdgePipeline, both, true)
    ->Name("edge-pipeline/both")
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
