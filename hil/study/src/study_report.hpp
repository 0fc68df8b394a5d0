// The calibration accuracy study as the Markdown page docs/design/calibration-accuracy.md: the
// setup, the tables beside the thesis' values, each claim with its figure and PASS / FAIL, and the
// place of the real-data section.
#pragma once

#include <string>
#include <vector>

#include "calibration_study.hpp"

namespace syncap::study {

struct StudyReport {
  std::string command;  // how the page was made, printed at its top
  bool short_mode = false;
  Table43Options table_options;
  std::vector<Table43Row> table_4_3;
  // The weak rows again with the noise much smaller (diagnostic, no claim): whether their
  // sigmas fall short because of the noise (the model's curvature) or always.
  std::vector<Table43Row> table_4_3_small_noise;
  RingOptions ring_options;
  RingStudy ring;
  ClaimLimits limits;
  // Section 3, real data (real_data.hpp's format_real_data); empty: not computed.
  std::string real_data_markdown;
};

std::string format_markdown(const StudyReport& report);

// Every claim of the page (Table 4.3 then the ring).
std::vector<Claim> all_claims(const StudyReport& report);

}  // namespace syncap::study
