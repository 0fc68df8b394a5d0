#include "sensor/opencv_camera.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <vector>

#include "sensor/rotation.hpp"

namespace syncap::sensor {
namespace {

// The distortion fit and the residual use (kGridSteps + 1)^2 pixels spread over the whole image,
// corners included: where the distortion is largest is where it must fit.
constexpr int kGridSteps = 24;
// Depth [mm] at which a sample ray is turned into an object point to re-project it.
constexpr double kSampleDepth_mm = 1000.0;

std::vector<Eigen::Vector2d> image_grid(const cv::Size& size) {
  std::vector<Eigen::Vector2d> grid;
  for (int i = 0; i <= kGridSteps; ++i) {
    for (int j = 0; j <= kGridSteps; ++j) {
      grid.emplace_back(-0.5 + size.width * static_cast<double>(j) / kGridSteps,
                        -0.5 + size.height * static_cast<double>(i) / kGridSteps);
    }
  }
  return grid;
}

ConversionResidual summarise(const std::vector<double>& distances_px) {
  ConversionResidual r;
  double sum_squares = 0.0;
  for (double d : distances_px) {
    sum_squares += d * d;
    r.max_px = std::max(r.max_px, d);
  }
  r.samples = static_cast<int>(distances_px.size());
  r.rms_px = r.samples > 0 ? std::sqrt(sum_squares / r.samples) : 0.0;
  return r;
}

// The thesis' sensor frame (x' right, y' up, looking along -z') to OpenCV's (x right, y down,
// looking along +z): a half turn about x.
const Eigen::Matrix3d kFlipYZ = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();

// A 2x2 rotation as a 3x3 rotation about the optical axis.
Eigen::Matrix3d about_optical_axis(const Eigen::Matrix2d& q) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
  m.topLeftCorner<2, 2>() = q;
  return m;
}

Eigen::Matrix3d eigen_from_matx(const cv::Matx33d& m) {
  Eigen::Matrix3d e;
  cv::cv2eigen(m, e);
  return e;
}

cv::Matx33d matx_from_eigen(const Eigen::Matrix3d& e) {
  cv::Matx33d m;
  cv::eigen2cv(e, m);
  return m;
}

// OpenCV's distortion of ideal normalised coordinates (cv::projectPoints, 5 coefficients): the
// lens with K = I.
Eigen::Vector2d opencv_distort(const cv::Vec<double, 5>& d, const Eigen::Vector2d& n) {
  return OpenCvLens{Eigen::Matrix3d::Identity(), {d[0], d[1], d[2], d[3], d[4]}}.distort(n);
}

Eigen::Vector2d pixel_from_normalised(const Eigen::Matrix3d& k, const Eigen::Vector2d& n) {
  return (k * n.homogeneous()).head<2>();
}

Eigen::Vector2d normalised_from_pixel(const Eigen::Matrix3d& k, const Eigen::Vector2d& pixel) {
  return (k.inverse() * pixel.homogeneous()).head<2>();
}

// Least squares with every column scaled to unit norm first: the monomials r², r⁴, r⁶ differ by
// orders of magnitude.
Eigen::VectorXd solve_least_squares(Eigen::MatrixXd a, const Eigen::VectorXd& b) {
  Eigen::VectorXd scale(a.cols());
  for (Eigen::Index j = 0; j < a.cols(); ++j) {
    scale[j] = a.col(j).norm() > 0.0 ? 1.0 / a.col(j).norm() : 1.0;
    a.col(j) *= scale[j];
  }
  return a.colPivHouseholderQr().solve(b).cwiseProduct(scale);
}

// The linear part of the thesis' image formation, normalised OpenCV-frame coordinates (x/z, y/z)
// to pixels: u = M (x/z, y/z) + pp with M = c / (1 - sc - sh²) [[1, sh], [sh, 1 - sc]] scaled by
// row by 1/mu_x, 1/mu_y (eqs 4.9, 4.10 without lens distortion, 4.13). M = K2 Q, K2 upper
// triangular (OpenCV's K with skew), Q a rotation about the optical axis.
struct LinearImaging {
  Eigen::Matrix3d camera_matrix;  // K
  Eigen::Matrix2d axis_rotation;  // Q
};

LinearImaging linear_imaging(const CameraModel& camera) {
  const InteriorOrientation& in = camera.interior;
  const SensorGeometry& s = camera.sensor;
  const double scale = in.c / (1.0 - in.sc - in.sh * in.sh);
  Eigen::Matrix2d m;
  m << scale / s.pixel_width_mm, scale * in.sh / s.pixel_width_mm,
      scale * in.sh / s.pixel_height_mm, scale * (1.0 - in.sc) / s.pixel_height_mm;
  // RQ by one Givens rotation: Q's second row is M's second row normalised.
  const double norm = m.row(1).norm();
  const double sin_q = m(1, 0) / norm, cos_q = m(1, 1) / norm;
  Eigen::Matrix2d q;
  q << cos_q, -sin_q, sin_q, cos_q;
  const Eigen::Matrix2d k2 = m * q.transpose();
  LinearImaging l;
  l.camera_matrix << k2(0, 0), k2(0, 1), sensor_centre_u(s) + in.xp / s.pixel_width_mm,  //
      0.0, k2(1, 1), sensor_centre_v(s) - in.yp / s.pixel_height_mm,                     //
      0.0, 0.0, 1.0;
  l.axis_rotation = q;
  return l;
}

// Fits OpenCV's k1, k2, p1, p2, k3 to pairs of ideal normalised coordinates and the pixels the
// thesis model gives them; rows are weighted by fx, fy so that the misfit is about in pixels.
cv::Vec<double, 5> fit_opencv_distortion(const std::vector<Eigen::Vector2d>& ideal,
                                         const std::vector<Eigen::Vector2d>& pixels,
                                         const Eigen::Matrix3d& k) {
  const Eigen::Index n = static_cast<Eigen::Index>(ideal.size());
  Eigen::MatrixXd a(2 * n, 5);
  Eigen::VectorXd b(2 * n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double x = ideal[i].x(), y = ideal[i].y(), r2 = x * x + y * y;
    const Eigen::Vector2d distorted = normalised_from_pixel(k, pixels[i]);
    // Columns k1, k2, p1, p2, k3: OpenCV's order.
    a.row(2 * i) << x * r2, x * r2 * r2, 2 * x * y, r2 + 2 * x * x, x * r2 * r2 * r2;
    a.row(2 * i + 1) << y * r2, y * r2 * r2, r2 + 2 * y * y, 2 * x * y, y * r2 * r2 * r2;
    b[2 * i] = distorted.x() - x;
    b[2 * i + 1] = distorted.y() - y;
    a.row(2 * i) *= k(0, 0);
    b[2 * i] *= k(0, 0);
    a.row(2 * i + 1) *= k(1, 1);
    b[2 * i + 1] *= k(1, 1);
  }
  const Eigen::VectorXd d = solve_least_squares(a, b);
  return {d[0], d[1], d[2], d[3], d[4]};
}

// Fits the thesis' k1, k2, k3, p1, p2 (sc, sh come from K) to pairs of measured reduced
// coordinates (x̄', ȳ') and the undistorted (x' - xp, y' - yp) eq 4.10 must give them; rows are
// weighted by 1/mu so that the misfit is about in pixels.
void fit_thesis_distortion(const std::vector<Eigen::Vector2d>& measured,
                           const std::vector<Eigen::Vector2d>& undistorted, CameraModel& camera) {
  InteriorOrientation& in = camera.interior;
  const Eigen::Index n = static_cast<Eigen::Index>(measured.size());
  Eigen::MatrixXd a(2 * n, 5);
  Eigen::VectorXd b(2 * n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double x = measured[i].x(), y = measured[i].y(), r2 = x * x + y * y;
    a.row(2 * i) << x * r2, x * r2 * r2, x * r2 * r2 * r2, r2 + 2 * x * x, 2 * x * y;
    a.row(2 * i + 1) << y * r2, y * r2 * r2, y * r2 * r2 * r2, 2 * x * y, r2 + 2 * y * y;
    b[2 * i] = undistorted[i].x() - (x - in.sc * x + in.sh * y);
    b[2 * i + 1] = undistorted[i].y() - (y + in.sh * x);
    a.row(2 * i) /= camera.sensor.pixel_width_mm;
    b[2 * i] /= camera.sensor.pixel_width_mm;
    a.row(2 * i + 1) /= camera.sensor.pixel_height_mm;
    b[2 * i + 1] /= camera.sensor.pixel_height_mm;
  }
  const Eigen::VectorXd d = solve_least_squares(a, b);
  in.k1 = d[0];
  in.k2 = d[1];
  in.k3 = d[2];
  in.p1 = d[3];
  in.p2 = d[4];
}

// Whether the camera's distortion is an OpenCV lens alone, defined through the camera's own K:
// then OpenCV's model holds it exactly and no fit is needed. (A lens whose K was edited apart
// from the camera's is fitted like any other distortion.)
bool lens_is_exact(const CameraModel& camera, const Eigen::Matrix3d& k) {
  if (has_lens_correction(camera.interior) || !camera.opencv_lens) return false;
  return (camera.opencv_lens->camera_matrix - k).norm() <= 1e-9 * k.norm();
}

}  // namespace

CameraModel camera_keeping_opencv_lens(const OpenCvCamera& opencv, double pixel_width_mm,
                                       double pixel_height_mm, int id) {
  OpenCvCamera ideal = opencv;
  ideal.distortion = cv::Vec<double, 5>::all(0.0);
  CameraModel camera = camera_from_opencv(ideal, pixel_width_mm, pixel_height_mm, id);
  if (cv::norm(opencv.distortion) != 0.0) {
    const cv::Vec<double, 5>& d = opencv.distortion;
    camera.opencv_lens =
        OpenCvLens{eigen_from_matx(opencv.camera_matrix), {d[0], d[1], d[2], d[3], d[4]}};
  }
  return camera;
}

cv::Point2d project_opencv(const OpenCvCamera& opencv, const cv::Point3d& object_point_mm) {
  cv::Matx33d r;
  cv::Rodrigues(opencv.rvec, r);
  const cv::Vec3d p = r * cv::Vec3d(object_point_mm) + opencv.tvec;
  const Eigen::Vector2d distorted =
      opencv_distort(opencv.distortion, Eigen::Vector2d(p[0] / p[2], p[1] / p[2]));
  const Eigen::Vector2d pixel =
      pixel_from_normalised(eigen_from_matx(opencv.camera_matrix), distorted);
  return {pixel.x(), pixel.y()};
}

OpenCvCamera opencv_from_camera(const CameraModel& camera, ConversionResidual* residual) {
  const LinearImaging linear = linear_imaging(camera);
  // Object to OpenCV camera frame: the thesis' sensor frame R^T (X - X0), flipped, then turned
  // about the axis by Q so that K is upper triangular.
  const Eigen::Matrix3d r_cv =
      about_optical_axis(linear.axis_rotation) * kFlipYZ * camera.rotation().transpose();
  const Eigen::Vector3d t_cv = -r_cv * camera.projection_centre();

  OpenCvCamera opencv;
  opencv.image_size = {camera.sensor.width_px, camera.sensor.height_px};
  opencv.camera_matrix = matx_from_eigen(linear.camera_matrix);
  cv::Rodrigues(matx_from_eigen(r_cv), opencv.rvec);
  opencv.tvec = {t_cv.x(), t_cv.y(), t_cv.z()};

  // Samples: the rays of a grid of pixels, by the thesis' (closed-form) back-projection.
  std::vector<Eigen::Vector2d> ideal, pixels;
  for (const Eigen::Vector2d& pixel : image_grid(opencv.image_size)) {
    const Eigen::Vector3d ray = r_cv * camera.back_project(pixel).direction;
    if (!(ray.z() > 0.0)) continue;  // a fold of the thesis' correction: no forward ray
    ideal.push_back(ray.head<2>() / ray.z());
    pixels.push_back(pixel);
  }
  if (lens_is_exact(camera, linear.camera_matrix)) {
    // The same K and coefficients: exact by construction (the samples would only measure the
    // pixels beyond the lens' fold, which no ray reaches in either model).
    const auto& d = camera.opencv_lens->distortion;
    opencv.distortion = {d[0], d[1], d[2], d[3], d[4]};
    if (residual != nullptr) *residual = {0.0, 0.0, static_cast<int>(pixels.size())};
    return opencv;
  }
  if (camera.has_distortion()) {
    opencv.distortion = fit_opencv_distortion(ideal, pixels, linear.camera_matrix);
  }
  if (residual != nullptr) {
    std::vector<double> distances;
    for (std::size_t i = 0; i < ideal.size(); ++i) {
      const Eigen::Vector2d converted =
          pixel_from_normalised(linear.camera_matrix, opencv_distort(opencv.distortion, ideal[i]));
      distances.push_back((converted - pixels[i]).norm());
    }
    *residual = summarise(distances);
  }
  return opencv;
}

CameraModel camera_from_opencv(const OpenCvCamera& opencv, double pixel_width_mm,
                               double pixel_height_mm, int id, ConversionResidual* residual) {
  CameraModel camera;
  camera.id = id;
  camera.sensor = {opencv.image_size.width, opencv.image_size.height, pixel_width_mm,
                   pixel_height_mm};
  const Eigen::Matrix3d k = eigen_from_matx(opencv.camera_matrix);

  // diag(mu) K2 = S Q^T with S symmetric (the thesis' affinity, see linear_imaging): the polar
  // decomposition; in 2-D the rotation's angle is atan2(n10 - n01, n00 + n11).
  const Eigen::Matrix2d n =
      Eigen::Vector2d(pixel_width_mm, pixel_height_mm).asDiagonal() * k.topLeftCorner<2, 2>();
  const double angle = std::atan2(n(1, 0) - n(0, 1), n(0, 0) + n(1, 1));
  Eigen::Matrix2d q_transposed;
  q_transposed << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  const Eigen::Matrix2d s = n * q_transposed.transpose();
  const double a = s(0, 0), b = 0.5 * (s(0, 1) + s(1, 0)), d = s(1, 1);
  InteriorOrientation& in = camera.interior;
  in.sh = b / a;
  in.sc = 1.0 - d / a;
  in.c = (a * d - b * b) / a;
  in.xp = (k(0, 2) - sensor_centre_u(camera.sensor)) * pixel_width_mm;
  in.yp = -(k(1, 2) - sensor_centre_v(camera.sensor)) * pixel_height_mm;

  cv::Matx33d r_cv_matx;
  cv::Rodrigues(opencv.rvec, r_cv_matx);
  const Eigen::Matrix3d r_cv = eigen_from_matx(r_cv_matx);
  // r_cv = Q3 F R^T (opencv_from_camera), so R = r_cv^T Q3 F.
  const Eigen::Matrix3d r =
      r_cv.transpose() * about_optical_axis(q_transposed.transpose()) * kFlipYZ;
  const RotationAngles angles = angles_from_rotation(r);
  const Eigen::Vector3d centre =
      -r_cv.transpose() * Eigen::Vector3d(opencv.tvec[0], opencv.tvec[1], opencv.tvec[2]);
  camera.exterior = {centre.x(), centre.y(), centre.z(), angles.omega, angles.phi, angles.kappa};

  // Samples: ideal normalised coordinates near those of a pixel grid, with the pixel OpenCV's
  // model gives each (exact pairs, no iterative undistortion needed).
  std::vector<Eigen::Vector2d> ideal, pixels;
  for (const Eigen::Vector2d& pixel : image_grid(opencv.image_size)) {
    ideal.push_back(normalised_from_pixel(k, pixel));
    pixels.push_back(pixel_from_normalised(k, opencv_distort(opencv.distortion, ideal.back())));
  }
  const Eigen::Matrix3d sensor_from_opencv = r.transpose() * r_cv.transpose();
  const auto ray_of = [&](const Eigen::Vector2d& normalised) -> Eigen::Vector3d {
    return r_cv.transpose() * normalised.homogeneous().normalized();
  };
  if (cv::norm(opencv.distortion) != 0.0) {
    std::vector<Eigen::Vector2d> measured, undistorted;
    for (std::size_t i = 0; i < ideal.size(); ++i) {
      const Eigen::Vector3d q = sensor_from_opencv * ideal[i].homogeneous();
      undistorted.emplace_back(-in.c * q.x() / q.z(), -in.c * q.y() / q.z());
      measured.push_back(camera.image_from_pixel(pixels[i]) - Eigen::Vector2d(in.xp, in.yp));
    }
    fit_thesis_distortion(measured, undistorted, camera);
  }
  if (residual != nullptr) {
    std::vector<double> distances;
    for (std::size_t i = 0; i < ideal.size(); ++i) {
      const Projection p = camera.project(centre + kSampleDepth_mm * ray_of(ideal[i]));
      distances.push_back(p.ok() ? (p.pixel - pixels[i]).norm()
                                 : std::numeric_limits<double>::infinity());
    }
    *residual = summarise(distances);
  }
  return camera;
}

CameraModel camera_from_projection_matrix(const cv::Matx34d& projection_matrix, cv::Size image_size,
                                          double pixel_width_mm, double pixel_height_mm, int id) {
  // P is defined up to scale and sign; with det(P's left 3x3) > 0 the camera has K with a
  // positive diagonal and a proper rotation.
  cv::Matx34d p = projection_matrix;
  if (cv::determinant(p.get_minor<3, 3>(0, 0)) < 0.0) p = -p;
  cv::Mat k_mat, r_mat, centre_h;
  cv::decomposeProjectionMatrix(p, k_mat, r_mat, centre_h);
  Eigen::Matrix3d k, r;
  cv::cv2eigen(k_mat, k);
  cv::cv2eigen(r_mat, r);
  // RQ leaves the signs of K's diagonal open: move negative ones into R (K D D R, D = D^-1).
  for (int i = 0; i < 3; ++i) {
    if (k(i, i) < 0.0) {
      k.col(i) *= -1.0;
      r.row(i) *= -1.0;
    }
  }
  k /= k(2, 2);
  Eigen::Vector4d c_h;
  cv::cv2eigen(centre_h, c_h);
  const Eigen::Vector3d centre = c_h.head<3>() / c_h[3];

  OpenCvCamera opencv;
  opencv.image_size = image_size;
  opencv.camera_matrix = matx_from_eigen(k);
  cv::Rodrigues(matx_from_eigen(r), opencv.rvec);
  const Eigen::Vector3d t = -r * centre;
  opencv.tvec = {t.x(), t.y(), t.z()};
  return camera_from_opencv(opencv, pixel_width_mm, pixel_height_mm, id);
}

}  // namespace syncap::sensor
