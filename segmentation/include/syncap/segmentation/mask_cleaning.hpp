// Cleaning a foreground mask: the closing and the removal of small components, and the filling
// of small holes inside the foreground's box. Internal to the masking (MediPicture); clean_mask,
// fill_holes and clip_to_polygon (medi_picture.hpp) are the public forms.
#pragma once

#include <opencv2/core.hpp>

#include "syncap/segmentation/packed_mask.hpp"

namespace syncap::segmentation::detail {

void clean_mask_with(cv::Mat& mask, int closing_diameter, int min_component_area, cv::Mat& labels,
                     cv::Mat& stats, cv::Mat& centroids);

// Fills the holes of `mask` up to `max_area` pixels; `box` holds every foreground pixel. A hole
// lies inside the foreground's bounding box, and a background component of the box that reaches the
// box's edge reaches the outside (or the image border): the box alone decides.
void fill_holes_in(cv::Mat& mask, cv::Rect box, int max_area, detail::PackedMask& packed);

}  // namespace syncap::segmentation::detail
