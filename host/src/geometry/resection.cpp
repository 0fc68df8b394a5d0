#include "geometry/resection.hpp"

#include <opencv2/calib3d.hpp>

namespace syncap::geometry {

std::optional<Resection> resect(const std::vector<Eigen::Vector3d>& object_points,
                                const std::vector<Eigen::Vector2d>& directions,
                                const ResectionOptions& options) {
  const std::size_t n = std::min(object_points.size(), directions.size());
  if (static_cast<int>(n) < options.min_points) return std::nullopt;
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (std::size_t i = 0; i < n; ++i) {
    object.emplace_back(object_points[i].x(), object_points[i].y(), object_points[i].z());
    image.emplace_back(directions[i].x(), -directions[i].y());  // OpenCV's y points down
  }
  cv::Mat rvec, tvec;
  std::vector<int> inliers;
  if (!cv::solvePnPRansac(object, image, cv::Mat::eye(3, 3, CV_64F), cv::Mat(), rvec, tvec, false,
                          options.iterations, static_cast<float>(options.inlier_threshold),
                          options.confidence, inliers, cv::SOLVEPNP_EPNP) ||
      static_cast<int>(inliers.size()) < options.min_inliers) {
    return std::nullopt;
  }
  cv::Mat r_cv_mat;
  cv::Rodrigues(rvec, r_cv_mat);
  Eigen::Matrix3d r_cv;
  Eigen::Vector3d t;
  for (int i = 0; i < 3; ++i) {
    t(i) = tvec.at<double>(i);
    for (int j = 0; j < 3; ++j) r_cv(i, j) = r_cv_mat.at<double>(i, j);
  }
  // R_cv = F R^T and t = -R_cv X0, with F = diag(1, -1, -1).
  const Eigen::Matrix3d f = Eigen::Vector3d(1, -1, -1).asDiagonal();
  Resection r;
  r.rotation = r_cv.transpose() * f;
  r.centre = -r_cv.transpose() * t;
  r.inliers = std::move(inliers);
  return r;
}

}  // namespace syncap::geometry
