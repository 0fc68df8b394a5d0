#include "calibration/exports.hpp"

#include <cstdio>

#include "sensor/opencv_camera.hpp"

namespace syncap::calibration {
namespace {

std::string camera_name(int id) {
  char name[16];
  std::snprintf(name, sizeof name, "cam_%02d", id);
  return name;
}

// Full precision, TOML float syntax (always a decimal point or exponent).
std::string toml_number(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  std::string s = text;
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

template <class Values>
std::string toml_array(const Values& values, double scale = 1.0) {
  std::string out = "[";
  for (std::size_t i = 0; i < values.size(); ++i) {
    out += (i ? ", " : "") + toml_number(values[i] * scale);
  }
  return out + "]";
}

std::string toml_camera(const sensor::CameraModel& camera) {
  const sensor::OpenCvCamera cv_camera = sensor::opencv_from_camera(camera);
  const cv::Matx33d& k = cv_camera.camera_matrix;
  std::string out = "[" + camera_name(camera.id) + "]\n";
  out += "name = \"" + std::to_string(camera.id) + "\"\n";
  out += "size = [" + std::to_string(cv_camera.image_size.width) + ", " +
         std::to_string(cv_camera.image_size.height) + "]\n";
  out += "matrix = [" + toml_array(std::vector<double>{k(0, 0), k(0, 1), k(0, 2)}) + ", " +
         toml_array(std::vector<double>{k(1, 0), k(1, 1), k(1, 2)}) + ", " +
         toml_array(std::vector<double>{k(2, 0), k(2, 1), k(2, 2)}) + "]\n";
  const cv::Vec<double, 5>& d = cv_camera.distortion;
  out += "distortions = " + toml_array(std::vector<double>{d[0], d[1], d[2], d[3], d[4]}) + "\n";
  const cv::Vec3d& r = cv_camera.rvec;
  const cv::Vec3d& t = cv_camera.tvec;
  out += "rotation = " + toml_array(std::vector<double>{r[0], r[1], r[2]}) + "\n";
  out += "translation = " + toml_array(std::vector<double>{t[0], t[1], t[2]}, 1e-3) + "\n";
  out += "fisheye = false\n\n";
  return out;
}

}  // namespace

std::string format_opencv_yaml(const std::vector<sensor::CameraModel>& cameras) {
  cv::FileStorage fs("calibration.yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  // A sequence `cameras`, the layout every program that reads OpenCV-style cameras reads
  // (hull/views_io.hpp: syncap hull, syncap match).
  fs << "cameras"
     << "[";
  for (const sensor::CameraModel& camera : cameras) {
    sensor::ConversionResidual residual;
    const sensor::OpenCvCamera c = sensor::opencv_from_camera(camera, &residual);
    fs << "{";
    fs << "id" << camera.id;
    fs << "image_size" << c.image_size;
    fs << "camera_matrix" << cv::Mat(c.camera_matrix);
    fs << "distortion" << cv::Mat(c.distortion);
    fs << "rvec" << cv::Mat(c.rvec);
    fs << "tvec" << cv::Mat(c.tvec);
    fs << "fit_rms_px" << residual.rms_px;
    fs << "}";
  }
  fs << "]";
  return fs.releaseAndGetString();
}

std::string format_calibration_toml(const std::vector<sensor::CameraModel>& cameras,
                                    double error_px) {
  std::string out;
  for (const sensor::CameraModel& camera : cameras) out += toml_camera(camera);
  out += "[metadata]\nadjusted = true\nerror = " + toml_number(error_px) + "\n";
  return out;
}

}  // namespace syncap::calibration
