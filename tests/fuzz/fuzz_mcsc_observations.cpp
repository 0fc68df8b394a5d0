// libFuzzer target: the calibration's MultiCamSelfCal input (`syncap calibrate --input
// mcsc:DIR`; calibration::parse_mcsc_observations, which read_mcsc_observations uses). The input
// holds the folder's three files, camera_order.txt, Res.dat and points.dat, separated by "%%\n".
//
// Contract: the reader returns observations or throws calibration::ObservationError, nothing
// else; what it accepts has a positive image size for every camera it has spots of.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "calibration/observations.hpp"
#include "fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<std::string> files = syncap::fuzz::split_input(data, size, "%%\n", 3);
  files.resize(3);
  syncap::calibration::Observations obs;
  const bool read =
      syncap::fuzz::decodes<syncap::calibration::ObservationError>("parse_mcsc_observations", [&] {
        obs = syncap::calibration::parse_mcsc_observations({files[0], files[1], files[2]},
                                                           "/nonexistent/mcsc");
      });
  if (!read) return 0;
  syncap::fuzz::check(!obs.frames.empty(), "observations without a frame were accepted");
  for (const auto& [frame, cameras] : obs.frames) {
    for (const auto& [camera, spots] : cameras) {
      const auto size_of = obs.image_sizes.find(camera);
      syncap::fuzz::check(size_of != obs.image_sizes.end() && size_of->second.width > 0 &&
                              size_of->second.height > 0,
                          "a camera with spots has no positive image size");
    }
  }
  return 0;
}
