// libFuzzer target: the simulator's scenario reader (sim::parse_scenario, which load_scenario
// uses), on the input as a scenario file's YAML text.
//
// Contract: the reader returns a scenario or throws sim::ScenarioError naming file and line,
// nothing else (yaml-cpp's own exceptions included); an accepted scenario has phases and cameras.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_check.hpp"
#include "scenario.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  syncap::sim::Scenario scenario;
  const bool read = syncap::fuzz::decodes<syncap::sim::ScenarioError>("parse_scenario", [&] {
    scenario = syncap::sim::parse_scenario(text, "/nonexistent/fuzz.yaml");
  });
  if (!read) return 0;
  syncap::fuzz::check(!scenario.phases.empty(), "a scenario without phases was accepted");
  syncap::fuzz::check(scenario.cameras.count > 0, "a scenario without cameras was accepted");
  return 0;
}
