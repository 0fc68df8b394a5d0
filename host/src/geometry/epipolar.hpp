// Epipolar geometry between two cameras' rays, for matching: two pixels can see the same point
// only when their rays meet, i.e. when ray b lies in the plane through ray a and b's centre.
#pragma once

#include "sensor/camera_model.hpp"

namespace syncap::geometry {

// The angle between ray b and the epipolar plane of ray a (the plane that holds ray a and b's
// origin) [rad]: 0 for rays that meet. Times b's pixels per radian it is, to first order, the
// distance of b's pixel from the epipolar line of a's in b's image. NaN when ray a points along
// the baseline (every plane through it holds b's origin).
double epipolar_angle(const sensor::Ray& a, const sensor::Ray& b);

// The epipolar plane's unit normal of ray a towards the camera centre `other_origin`; zero when
// undefined. Precomputed once per ray and camera pair, the test of every ray b of that camera
// is then one dot product: asin(|n . d_b|).
Eigen::Vector3d epipolar_normal(const sensor::Ray& a, const Eigen::Vector3d& other_origin);

}  // namespace syncap::geometry
