// The thesis' camera model and OpenCV's (K, distortion k1 k2 p1 p2 k3, rvec, tvec), converted
// both ways, and a CameraModel from a 3x4 projection matrix.
//
// Where the models agree the conversion is exact: the collinearity with any c, xp, yp, pixel
// size and sc, sh maps onto K (with skew) and a rotation, to rounding. Where they do not, the
// lens distortion is fitted by linear least squares over a grid of pixels covering the image and
// the remaining disagreement is reported in pixels: the thesis corrects the measured (distorted)
// coordinates with a polynomial in mm, OpenCV distorts the ideal normalised coordinates, so one
// polynomial is the other's inverse series, which no finite set of coefficients matches exactly.
// docs/reference/camera-model.md, "OpenCV", lists every difference.
#pragma once

#include <opencv2/core.hpp>

#include "sensor/camera_model.hpp"

namespace syncap::sensor {

// OpenCV's pinhole camera. Camera frame x right, y down, z forward (the viewing direction);
// pixel (0, 0) at the centre of the top-left pixel, as in the project.
struct OpenCvCamera {
  cv::Size image_size;
  // K: fx, skew, cx; 0, fy, cy; 0, 0, 1 [px]. cv::projectPoints ignores the skew K(0, 1);
  // project_opencv() does not.
  cv::Matx33d camera_matrix = cv::Matx33d::eye();
  cv::Vec<double, 5> distortion = cv::Vec<double, 5>::all(0.0);  // k1, k2, p1, p2, k3
  cv::Vec3d rvec = cv::Vec3d::all(0.0);                          // object -> camera, Rodrigues
  cv::Vec3d tvec = cv::Vec3d::all(0.0);                          // [mm]
};

// How closely a converted camera reproduces the original: over a grid of pixels covering the
// image, the distance between the pixel the original gives a ray and the pixel the converted
// camera gives the same ray.
struct ConversionResidual {
  double rms_px = 0.0;
  double max_px = 0.0;
  int samples = 0;
};

// The OpenCV camera closest to `camera`. Exact when k1 = k2 = k3 = p1 = p2 = 0 (with the skew of
// K when sh != 0), with or without an OpenCV lens kept on the camera; otherwise the OpenCV
// distortion is fitted, and `residual` (when given) says by how much it misses.
OpenCvCamera opencv_from_camera(const CameraModel& camera, ConversionResidual* residual = nullptr);

// The thesis camera closest to an OpenCV camera whose pixels are `pixel_width_mm` x
// `pixel_height_mm` (OpenCV does not know the pixel size; any positive value reproduces the same
// pixels, with c, xp, yp and the distortion coefficients in the corresponding mm). Exact when the
// OpenCV distortion is zero; otherwise fitted, with `residual` as above.
CameraModel camera_from_opencv(const OpenCvCamera& opencv, double pixel_width_mm,
                               double pixel_height_mm, int id = 0,
                               ConversionResidual* residual = nullptr);

// The nominal pixel size [mm] given to cameras read from OpenCV's model, which carries none: any
// reproduces the same pixels (camera_from_opencv), with c, xp, yp in the matching mm.
inline constexpr double kOpenCvPixelMm = 0.01;

// The camera an OpenCV camera is, exactly: its ideal camera (camera_from_opencv without the
// distortion, exact) with OpenCV's lens kept as it is (CameraModel::opencv_lens). How every
// program reads OpenCV camera files; opencv_from_camera gives the same OpenCV camera back.
CameraModel camera_keeping_opencv_lens(const OpenCvCamera& opencv, double pixel_width_mm,
                                       double pixel_height_mm, int id = 0);

// The camera without distortion that a 3x4 projection matrix P (pixels, x_pixel ~ P (X, 1), in
// the project's pixel convention) describes, through cv::decomposeProjectionMatrix. P may carry
// any scale and sign. Object units are taken as mm.
CameraModel camera_from_projection_matrix(const cv::Matx34d& projection_matrix, cv::Size image_size,
                                          double pixel_width_mm, double pixel_height_mm,
                                          int id = 0);

// The pixel OpenCV's model gives an object point, including K's skew (cv::projectPoints' formula
// otherwise). Points behind the camera still get a (meaningless) pixel, as in OpenCV.
cv::Point2d project_opencv(const OpenCvCamera& opencv, const cv::Point3d& object_point_mm);

}  // namespace syncap::sensor
