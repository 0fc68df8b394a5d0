// What a flood of forged commands costs an edge (docs/design/security.md): one MAC check each, no
// state. scripts/bench.sh prints "command-check-forged: S s on one core" per check; S x the flood's
// rate is the share of a core it takes.
#include <benchmark/benchmark.h>

#include "syncap/edge_command_t.hpp"
#include "syncap/proto/command_auth.hpp"

namespace {

using syncap::edge_command_t;
using syncap::proto::CommandGuard;
using syncap::proto::CommandKey;
using syncap::proto::CommandSigner;

void BM_ForgedCommandCheck(benchmark::State& state) {
  CommandGuard guard(CommandKey::generate(), 5'000'000'000, 0);
  CommandSigner attacker(CommandKey::generate());
  edge_command_t forged{};
  forged.command = edge_command_t::STOP;
  attacker.sign(forged);
  const int64_t now = forged.sent_realtime_ns;
  for (auto _ : state) benchmark::DoNotOptimize(guard.check(forged, now));
}
BENCHMARK(BM_ForgedCommandCheck)->Name("command-check-forged/ours");

}  // namespace

BENCHMARK_MAIN();
