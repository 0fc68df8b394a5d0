// Reflections: static bright discs in a camera's image (light off shiny things in the room), drawn
// over the rendered scene in every frame of a mocap phase. They are not targets: the host sees them
// as blobs, and they make ghost points when matched across cameras.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "scenario.hpp"

namespace syncap::sim {

struct ImageDisc {
  Eigen::Vector2d centre_px = Eigen::Vector2d::Zero();
  double radius_px = 1;
  double brightness_dn = 250;
};

// spec.count discs at random positions, wholly inside the width x height image; the same for the
// same seed and camera (and different for another camera).
std::vector<ImageDisc> reflection_discs(const ReflectionSpec& spec, unsigned seed, int camera,
                                        int width, int height);

// Blends each disc into `radiance` (CV_32F) towards its brightness by its exact pixel coverage.
void paint_discs(const std::vector<ImageDisc>& discs, cv::Mat& radiance);

}  // namespace syncap::sim
