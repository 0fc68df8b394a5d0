// libFuzzer target: the calibration's CSV input (`syncap calibrate --input csv:FILE`;
// calibration::parse_csv_observations, which read_csv_observations uses), on the input as the
// file's text.
//
// Contract: the reader returns observations or throws calibration::ObservationError, nothing
// else; what it accepts has at least one spot, every spot finite, every identified target 0..9.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "calibration/observations.hpp"
#include "fuzz_check.hpp"

namespace {

void check_spots(const syncap::calibration::Observations& obs) {
  syncap::fuzz::check(obs.spot_count() > 0, "observations without a spot were accepted");
  for (const auto& [frame, cameras] : obs.frames) {
    for (const auto& [camera, spots] : cameras) {
      for (const auto& spot : spots) {
        syncap::fuzz::check(std::isfinite(spot.x) && std::isfinite(spot.y),
                            "a spot with a coordinate that is not finite was accepted");
        syncap::fuzz::check(spot.target >= -1 && spot.target <= 9,
                            "a spot's target is outside -1..9");
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  syncap::calibration::Observations obs;
  if (syncap::fuzz::decodes<syncap::calibration::ObservationError>("parse_csv_observations", [&] {
        obs = syncap::calibration::parse_csv_observations(text, "spots.csv");
      })) {
    check_spots(obs);
  }
  return 0;
}
