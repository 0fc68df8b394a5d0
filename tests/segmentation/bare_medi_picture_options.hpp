// Medi-picture options with every step after classification off (no shadow test, no closing, no
// component filter, no illumination correction), so that a test sees the classification itself
// (k 3, the thesis' interval).
#pragma once

#include "syncap/segmentation/medi_picture.hpp"

namespace syncap::segmentation::testing {

inline MediPictureOptions bare_options() {
  MediPictureOptions options = thesis_masking_options();
  options.remove_shadows = false;
  options.closing_diameter = 0;
  options.min_component_area = 0;
  return options;
}

}  // namespace syncap::segmentation::testing
