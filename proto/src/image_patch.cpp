#include "syncap/proto/image_patch.hpp"

#include <algorithm>
#include <functional>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <stdexcept>

namespace syncap::proto {
namespace {

constexpr int kMaxSensorSide = 8192;

std::vector<uchar> png_of(const cv::Mat& tile, int compression) {
  std::vector<uchar> png;
  cv::imencode(".png", tile, png, {cv::IMWRITE_PNG_COMPRESSION, compression});
  return png;
}

// The sent pixels: the mask widened by the margin, inside the image.
cv::Mat widened(const cv::Mat& mask, int margin_px) {
  cv::Mat wide = mask != 0;
  if (margin_px <= 0) return wide;
  const cv::Mat disc =
      cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * margin_px + 1, 2 * margin_px + 1));
  cv::dilate(wide, wide, disc);
  return wide;
}

image_patch_t part_of(int camera_id, int64_t frame_number, cv::Size sensor, cv::Point tile_origin,
                      std::vector<uchar> png) {
  image_patch_t part{};
  part.camera_id = static_cast<int16_t>(camera_id);
  part.frame_number = frame_number;
  part.image_width = static_cast<int16_t>(sensor.width);
  part.image_height = static_cast<int16_t>(sensor.height);
  part.tile_x = static_cast<int16_t>(tile_origin.x);
  part.tile_y = static_cast<int16_t>(tile_origin.y);
  part.encoding = image_patch_t::ENCODING_PNG;
  part.data_size = static_cast<int16_t>(png.size());
  part.data.assign(png.begin(), png.end());
  return part;
}

// Cuts one column of the patch into runs of rows whose PNG fits a part. The next run's height
// is guessed from the last one's bytes per row, and shrunk until it fits.
void encode_column(const cv::Mat& column, cv::Point column_origin, int compression,
                   const std::function<void(cv::Point, std::vector<uchar>)>& emit) {
  const double budget = image_patch_t::MAX_DATA;
  double bytes_per_row = column.cols + 8.0;  // uncompressed until measured
  for (int y = 0; y < column.rows;) {
    int rows = std::clamp(static_cast<int>(0.95 * budget / bytes_per_row), 1, column.rows - y);
    std::vector<uchar> png = png_of(column.rowRange(y, y + rows), compression);
    while (png.size() > budget) {
      if (rows == 1)
        throw std::logic_error("image patch: one row of " + std::to_string(column.cols) +
                               " pixels does not fit a part");
      rows = std::max(1, static_cast<int>(rows * 0.9 * budget / static_cast<double>(png.size())));
      png = png_of(column.rowRange(y, y + rows), compression);
    }
    bytes_per_row = std::max(1.0, static_cast<double>(png.size()) / rows);
    emit(column_origin + cv::Point(0, y), std::move(png));
    y += rows;
  }
}

std::string where(const image_patch_t& part) {
  return "image patch of camera " + std::to_string(part.camera_id) + " frame " +
         std::to_string(part.frame_number) + " part " + std::to_string(part.part_index) + "/" +
         std::to_string(part.part_count);
}

// The size a PNG's header (its IHDR chunk) announces; nothing for data that is no PNG.
std::optional<cv::Size> png_size(const std::vector<uint8_t>& data) {
  static constexpr uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (data.size() < 24 || !std::equal(std::begin(kSignature), std::end(kSignature), data.begin()))
    return std::nullopt;
  const auto be32 = [&](std::size_t at) {
    return (uint32_t{data[at]} << 24) | (uint32_t{data[at + 1]} << 16) |
           (uint32_t{data[at + 2]} << 8) | uint32_t{data[at + 3]};
  };
  const uint32_t width = be32(16), height = be32(20);
  if (width > 1u << 20 || height > 1u << 20) return cv::Size(-1, -1);
  return cv::Size(static_cast<int>(width), static_cast<int>(height));
}

// The tile of one part, checked against the patch's sensor; throws naming the part. The PNG's
// announced size is checked before it is decoded: a forged header must not make the host
// allocate gigabytes.
cv::Mat decode_tile(const image_patch_t& part, cv::Size sensor) {
  if (part.encoding != image_patch_t::ENCODING_PNG)
    throw std::runtime_error(where(part) + ": unknown encoding " + std::to_string(part.encoding));
  if (part.data_size < 0 || static_cast<std::size_t>(part.data_size) != part.data.size())
    throw std::runtime_error(where(part) + ": data_size " + std::to_string(part.data_size) +
                             " for " + std::to_string(part.data.size()) + " bytes");
  const std::optional<cv::Size> announced = png_size(part.data);
  if (!announced) throw std::runtime_error(where(part) + ": not an 8-bit grey PNG");
  if (announced->width < 1 || announced->height < 1 ||
      part.tile_x + announced->width > sensor.width ||
      part.tile_y + announced->height > sensor.height || part.tile_x < 0 || part.tile_y < 0)
    throw std::runtime_error(where(part) + ": a " + std::to_string(announced->width) + "x" +
                             std::to_string(announced->height) + " tile at (" +
                             std::to_string(part.tile_x) + ", " + std::to_string(part.tile_y) +
                             ") outside the " + std::to_string(sensor.width) + "x" +
                             std::to_string(sensor.height) + " image");
  cv::Mat tile;
  try {
    tile = cv::imdecode(cv::Mat(1, static_cast<int>(part.data.size()), CV_8UC1,
                                const_cast<uint8_t*>(part.data.data())),
                        cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception&) {
    tile.release();
  }
  if (tile.empty() || tile.type() != CV_8UC1 || tile.size() != *announced)
    throw std::runtime_error(where(part) + ": not an 8-bit grey PNG");
  return tile;
}

}  // namespace

std::vector<image_patch_t> encode_image_patch(int camera_id, int64_t frame_number,
                                              const cv::Mat& image, const cv::Mat& mask,
                                              cv::Point origin, cv::Size sensor_size,
                                              const PatchEncoding& options) {
  if (image.type() != CV_8UC1 || mask.type() != CV_8UC1 || image.size() != mask.size())
    throw std::invalid_argument("image patch: needs an 8-bit grey image and a mask of its size");
  const cv::Size sensor = sensor_size.empty() ? image.size() : sensor_size;
  const cv::Mat sent = widened(mask, options.margin_px);
  const cv::Rect box = cv::boundingRect(sent);
  if (box.empty()) return {};
  cv::Mat patch = cv::Mat::zeros(box.size(), CV_8UC1);
  image(box).copyTo(patch, sent(box));

  std::vector<image_patch_t> parts;
  const auto emit = [&](cv::Point tile_origin, std::vector<uchar> png) {
    parts.push_back(
        part_of(camera_id, frame_number, sensor, origin + box.tl() + tile_origin, std::move(png)));
  };
  for (int x = 0; x < patch.cols; x += kMaxTileWidth) {
    const cv::Mat column = patch.colRange(x, std::min(patch.cols, x + kMaxTileWidth));
    encode_column(column, {x, 0}, options.png_compression, emit);
  }
  for (std::size_t i = 0; i < parts.size(); ++i) {
    parts[i].part_index = static_cast<int16_t>(i);
    parts[i].part_count = static_cast<int16_t>(parts.size());
  }
  return parts;
}

ImagePatch decode_image_patch(std::span<const image_patch_t> parts) {
  ImagePatch patch;
  if (parts.empty()) return patch;
  const image_patch_t& first = parts.front();
  patch.camera_id = first.camera_id;
  patch.frame_number = first.frame_number;
  patch.part_count = first.part_count;
  const cv::Size sensor(first.image_width, first.image_height);
  if (sensor.width < 1 || sensor.height < 1 || sensor.width > kMaxSensorSide ||
      sensor.height > kMaxSensorSide) {
    patch.errors.push_back(where(first) + ": sensor size " + std::to_string(sensor.width) + "x" +
                           std::to_string(sensor.height) + " outside 1..8192");
    return patch;
  }
  patch.image = cv::Mat::zeros(sensor, CV_8UC1);
  patch.known = cv::Mat::zeros(sensor, CV_8UC1);
  for (const image_patch_t& part : parts) {
    try {
      if (part.image_width != first.image_width || part.image_height != first.image_height)
        throw std::runtime_error(where(part) + ": sensor size differs from the first part's");
      const cv::Mat tile = decode_tile(part, sensor);
      const cv::Rect rect(part.tile_x, part.tile_y, tile.cols, tile.rows);
      tile.copyTo(patch.image(rect));
      patch.known(rect).setTo(255);
      ++patch.parts_received;
    } catch (const std::runtime_error& e) {
      patch.errors.push_back(e.what());
    }
  }
  return patch;
}

}  // namespace syncap::proto
