#include "sensor/opencv_camera_file.hpp"

#include <opencv2/calib3d.hpp>
#include <opencv2/core/persistence.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <initializer_list>
#include <string>

#include "sensor/camera_file.hpp"
#include "util/file_extension.hpp"
#include "util/printf_string.hpp"

namespace syncap::sensor {
namespace {

// The numbers of a node: a sequence ([1, 2, 3]) or an OpenCV matrix (!!opencv-matrix, data).
std::vector<double> numbers_of(const cv::FileNode& node) {
  const cv::FileNode data = node.isMap() ? node["data"] : node;
  std::vector<double> v;
  if (data.isSeq()) {
    for (const cv::FileNode& n : data) {
      if (!n.isReal() && !n.isInt()) return {};
      v.push_back(static_cast<double>(n));
    }
  } else if (data.isReal() || data.isInt()) {
    v.push_back(static_cast<double>(data));
  }
  return v;
}

// The first of `names` a camera's map holds, with `counts` numbers; an error naming the file,
// the camera and the field otherwise. `required` false: empty when none of the names is there.
std::vector<double> field(const cv::FileNode& camera, std::initializer_list<const char*> names,
                          std::initializer_list<std::size_t> counts, const std::string& where,
                          bool required = true) {
  for (const char* name : names) {
    if (camera[name].empty()) continue;
    std::vector<double> v = numbers_of(camera[name]);
    if (std::ranges::find(counts, v.size()) == counts.end() ||
        !std::ranges::all_of(v, [](double x) { return std::isfinite(x); })) {
      std::string sizes;
      for (const std::size_t n : counts) sizes += (sizes.empty() ? "" : " or ") + std::to_string(n);
      throw CameraFileError(util::printf_string("%s: %s must hold %s finite numbers", where.c_str(),
                                                name, sizes.c_str()));
    }
    return v;
  }
  if (!required) return {};
  throw CameraFileError(where + ": " + *names.begin() + " is missing");
}

// A camera's map. `with_pose` false: the intrinsics alone (R and t ignored, the image size
// optional: 0 x 0 when absent).
sensor::OpenCvCamera opencv_camera_of(const cv::FileNode& node, const std::string& where,
                                      bool with_pose = true) {
  sensor::OpenCvCamera c;
  std::vector<double> size = field(node, {"image_size"}, {2}, where, false);
  if (size.empty() && !with_pose && node["image_width"].empty()) size = {0, 0};
  if (size.empty())
    size = {field(node, {"image_width"}, {1}, where)[0],
            field(node, {"image_height"}, {1}, where)[0]};
  const bool no_size = !with_pose && size[0] == 0 && size[1] == 0;
  if (no_size) size = {1, 1};
  if (size[0] < 1 || size[1] < 1 || size[0] != std::floor(size[0]) ||
      size[1] != std::floor(size[1]))
    throw CameraFileError(where + ": the image size must be two whole numbers of pixels >= 1");
  c.image_size =
      no_size ? cv::Size() : cv::Size(static_cast<int>(size[0]), static_cast<int>(size[1]));
  const std::vector<double> k = field(node, {"K", "camera_matrix", "CameraMatrix"}, {9}, where);
  for (int i = 0; i < 9; ++i) c.camera_matrix.val[i] = k[i];
  if (k[0] <= 0 || k[4] <= 0 || k[3] != 0 || k[6] != 0 || k[7] != 0 || k[8] != 1)
    throw CameraFileError(where + ": K must be [fx s cx; 0 fy cy; 0 0 1] with fx, fy > 0");
  const std::vector<double> d =
      field(node, {"distortion", "dist_coeffs", "D", "distortion_coefficients", "DistortionCoeffs"},
            {4, 5}, where, false);
  for (std::size_t i = 0; i < d.size(); ++i) c.distortion[static_cast<int>(i)] = d[i];
  if (k[1] != 0 && cv::norm(c.distortion) > 0)
    throw CameraFileError(where +
                          ": a skewed K with lens distortion is not supported (OpenCV's own "
                          "undistortion ignores the skew)");
  if (!with_pose) return c;
  const std::vector<double> r = field(node, {"R", "rvec"}, {9, 3}, where);
  if (r.size() == 3) {
    c.rvec = {r[0], r[1], r[2]};
  } else {
    const cv::Matx33d rotation(r.data());
    if (cv::norm(rotation.t() * rotation - cv::Matx33d::eye()) > 1e-6 ||
        cv::determinant(rotation) < 0)
      throw CameraFileError(where + ": R is not a rotation (orthonormal, determinant +1)");
    cv::Rodrigues(rotation, c.rvec);
  }
  const std::vector<double> t = field(node, {"t", "tvec"}, {3}, where);
  c.tvec = {t[0], t[1], t[2]};
  return c;
}

}  // namespace

std::vector<OpenCvCameraEntry> read_opencv_camera_file(const std::filesystem::path& path) {
  cv::FileStorage file;
  try {
    file.open(path.string(), cv::FileStorage::READ);
  } catch (const cv::Exception& e) {
    throw CameraFileError(path.string() + ": not a readable YAML or JSON camera file: " + e.msg);
  }
  const cv::FileNode list = file.isOpened() ? file["cameras"] : cv::FileNode();
  if (!list.isSeq() || list.size() == 0)
    throw CameraFileError(path.string() + ": expected a non-empty sequence 'cameras'");
  std::vector<OpenCvCameraEntry> entries;
  int index = 0;
  for (const cv::FileNode& node : list) {
    const std::string where = util::printf_string("%s: camera %d", path.string().c_str(), index);
    if (!node.isMap())
      throw CameraFileError(where + ": expected a map of K, distortion, R, t, image size");
    const int id = node["id"].isInt() ? static_cast<int>(node["id"]) : index;
    entries.push_back({id, opencv_camera_of(node, where)});
    ++index;
  }
  return entries;
}

std::vector<OpenCvCameraEntry> read_opencv_intrinsics(const std::filesystem::path& path) {
  cv::FileStorage file;
  try {
    file.open(path.string(), cv::FileStorage::READ);
  } catch (const cv::Exception& e) {
    throw CameraFileError(path.string() +
                          ": not a readable YAML, JSON or XML camera file: " + e.msg);
  }
  if (!file.isOpened()) throw CameraFileError(path.string() + ": cannot open for reading");
  const cv::FileNode list = file["cameras"];
  std::vector<OpenCvCameraEntry> entries;
  if (!list.isSeq()) {
    entries.push_back({0, opencv_camera_of(file.root(), path.string(), false)});
    return entries;
  }
  int index = 0;
  for (const cv::FileNode& node : list) {
    const std::string where = util::printf_string("%s: camera %d", path.string().c_str(), index);
    const int id = node["id"].isInt() ? static_cast<int>(node["id"]) : index;
    entries.push_back({id, opencv_camera_of(node, where, false)});
    ++index;
  }
  if (entries.empty()) throw CameraFileError(path.string() + ": the sequence 'cameras' is empty");
  return entries;
}

bool is_opencv_camera_file(const std::filesystem::path& path) {
  const std::string ext = util::lower_extension(path);
  if (ext == ".yaml" || ext == ".yml") return true;
  if (ext != ".json") return false;
  try {
    const cv::FileStorage probe(path.string(), cv::FileStorage::READ);
    return probe.isOpened() && probe["cameras"].isSeq() && probe["cameras"].size() > 0 &&
           (!probe["cameras"][0]["K"].empty() || !probe["cameras"][0]["camera_matrix"].empty());
  } catch (const cv::Exception&) {
    return false;
  }
}

}  // namespace syncap::sensor
