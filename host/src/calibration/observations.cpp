#include "calibration/observations.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace syncap::calibration {
namespace {

// Larger than any sensor; keeps a Res.dat size within int (issue 15: 3e12 was cast to int).
constexpr int kMaxImageSide = 100000;

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ObservationError(file.string() + ": cannot open for reading");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw ObservationError(file.string() + ": read error");
  return text.str();
}

std::vector<std::string> split(const std::string& line, char separator) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, separator)) fields.push_back(field);
  if (!line.empty() && line.back() == separator) fields.emplace_back();
  return fields;
}

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

// A CSV line's fields with their columns (1-based, of the field's first character).
struct Field {
  std::string text;
  int column = 1;
};

std::vector<Field> csv_fields(const std::string& line) {
  std::vector<Field> fields;
  int column = 1;
  for (const std::string& raw : split(line, ',')) {
    fields.push_back({trimmed(raw), column});
    column += static_cast<int>(raw.size()) + 1;
  }
  return fields;
}

bool parse_double(const std::string& text, double& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtod(text.c_str(), &end);
  return errno == 0 && end == text.c_str() + text.size() && std::isfinite(value);
}

bool parse_integer(const std::string& text, long long& value) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  value = std::strtoll(text.c_str(), &end, 10);
  return errno == 0 && end == text.c_str() + text.size();
}

}  // namespace

long Observations::spot_count() const {
  long n = 0;
  for (const auto& [frame, cameras] : frames) {
    for (const auto& [camera, spots] : cameras) n += static_cast<long>(spots.size());
  }
  return n;
}

std::set<int> Observations::cameras() const {
  std::set<int> ids;
  for (const auto& [id, size] : image_sizes) ids.insert(id);
  for (const auto& [frame, cameras] : frames) {
    for (const auto& [camera, spots] : cameras) ids.insert(camera);
  }
  return ids;
}

Observations parse_csv_observations(const std::string& text, const std::string& source) {
  Observations obs;
  obs.source = "csv:" + source;
  std::istringstream in(text);
  std::string line;
  int line_number = 0;
  int fields_per_line = 0;  // 4 or 5, fixed by the first data line
  while (std::getline(in, line)) {
    ++line_number;
    if (trimmed(line).empty() || trimmed(line)[0] == '#') continue;
    const std::vector<Field> fields = csv_fields(line);
    const auto where = [&](const Field& f) {
      return source + ":" + std::to_string(line_number) + ":" + std::to_string(f.column) + ": ";
    };
    long long frame = 0;
    const bool header = !parse_integer(fields[0].text, frame);
    if (header && line_number == 1 && fields[0].text == "frame") continue;
    if (fields.size() != 4 && fields.size() != 5) {
      throw ObservationError(source + ":" + std::to_string(line_number) +
                             ": expected frame,camera,x,y[,point], got " +
                             std::to_string(fields.size()) + " fields");
    }
    if (fields_per_line == 0) fields_per_line = static_cast<int>(fields.size());
    if (static_cast<int>(fields.size()) != fields_per_line) {
      throw ObservationError(source + ":" + std::to_string(line_number) + ": " +
                             std::to_string(fields.size()) + " fields where earlier lines have " +
                             std::to_string(fields_per_line));
    }
    if (header) throw ObservationError(where(fields[0]) + "frame must be an integer");
    long long camera = 0;
    if (!parse_integer(fields[1].text, camera) || camera < 0 || camera > 99) {
      throw ObservationError(where(fields[1]) + "camera must be an integer from 0 to 99");
    }
    Spot spot;
    if (!parse_double(fields[2].text, spot.x)) {
      throw ObservationError(where(fields[2]) + "x must be a number [px]");
    }
    if (!parse_double(fields[3].text, spot.y)) {
      throw ObservationError(where(fields[3]) + "y must be a number [px]");
    }
    if (fields.size() == 5) {
      long long target = 0;
      if (!parse_integer(fields[4].text, target) || target < 0 || target > 9) {
        throw ObservationError(where(fields[4]) + "point must be an integer from 0 to 9");
      }
      spot.target = static_cast<int>(target);
    }
    obs.frames[frame][static_cast<int>(camera)].push_back(spot);
  }
  if (obs.frames.empty()) throw ObservationError(source + ": no observations");
  return obs;
}

Observations read_csv_observations(const std::filesystem::path& file) {
  return parse_csv_observations(read_text(file), file.string());
}

Observations read_mcsc_observations(const std::filesystem::path& folder) {
  if (!std::filesystem::is_directory(folder)) {
    throw ObservationError(folder.string() + ": not a MultiCamSelfCal folder (not a directory)");
  }
  return parse_mcsc_observations({read_text(folder / "camera_order.txt"),
                                  read_text(folder / "Res.dat"), read_text(folder / "points.dat")},
                                 folder);
}

Observations parse_mcsc_observations(const McscFiles& files, const std::filesystem::path& folder) {
  const std::string where = folder.string();
  Observations obs;
  obs.source = "mcsc:" + where;

  // camera_order.txt: one name a line; Res.dat: "width height" a line, same order.
  std::vector<std::string> names;
  {
    std::istringstream in(files.camera_order);
    std::string line;
    while (std::getline(in, line)) {
      if (!trimmed(line).empty()) names.push_back(trimmed(line));
    }
  }
  const std::string res_file = (folder / "Res.dat").string();
  std::istringstream res(files.res);
  std::string line;
  int line_number = 0;
  std::vector<ImageSize> sizes;
  while (std::getline(res, line)) {
    ++line_number;
    if (trimmed(line).empty()) continue;
    std::istringstream fields(line);
    double w = 0, h = 0;
    if (!(fields >> w >> h) || !(w >= 1 && w <= kMaxImageSide) || !(h >= 1 && h <= kMaxImageSide) ||
        w != std::floor(w) || h != std::floor(h)) {
      throw ObservationError(res_file + ":" + std::to_string(line_number) +
                             ": expected the image width and height in pixels (1 to " +
                             std::to_string(kMaxImageSide) + ")");
    }
    sizes.push_back({static_cast<int>(w), static_cast<int>(h)});
  }
  if (sizes.empty()) throw ObservationError(res_file + ": no cameras");
  if (!names.empty() && names.size() != sizes.size()) {
    throw ObservationError(where + ": camera_order.txt names " + std::to_string(names.size()) +
                           " cameras, Res.dat has " + std::to_string(sizes.size()));
  }
  const int cameras = static_cast<int>(sizes.size());
  for (int c = 0; c < cameras; ++c) {
    obs.image_sizes[c] = sizes[static_cast<size_t>(c)];
    if (!names.empty()) obs.camera_names[names[static_cast<size_t>(c)]] = c;
  }

  // points.dat: rows x_0, y_0, 1, x_1, y_1, 1, ...; a column per frame.
  const std::string points_file = (folder / "points.dat").string();
  std::istringstream points(files.points);
  std::vector<std::vector<double>> rows;
  line_number = 0;
  while (std::getline(points, line)) {
    ++line_number;
    if (trimmed(line).empty()) continue;
    std::istringstream fields(line);
    std::vector<double> row;
    std::string token;
    while (fields >> token) {
      double value = 0;
      if (token == "nan" || token == "NaN" || token == "NAN") {
        value = std::nan("");
      } else if (!parse_double(token, value)) {
        throw ObservationError(points_file + ":" + std::to_string(line_number) + ": value " +
                               std::to_string(row.size() + 1) + " ('" + token +
                               "') is not a number");
      }
      row.push_back(value);
    }
    if (!rows.empty() && row.size() != rows[0].size()) {
      throw ObservationError(points_file + ":" + std::to_string(line_number) + ": " +
                             std::to_string(row.size()) + " frames where line 1 has " +
                             std::to_string(rows[0].size()));
    }
    rows.push_back(std::move(row));
  }
  if (static_cast<int>(rows.size()) != 3 * cameras) {
    throw ObservationError(points_file + ": " + std::to_string(rows.size()) +
                           " rows, expected 3 per camera of Res.dat (" +
                           std::to_string(3 * cameras) + ")");
  }
  const size_t frames = rows[0].size();
  for (int c = 0; c < cameras; ++c) {
    const auto& xs = rows[static_cast<size_t>(3 * c)];
    const auto& ys = rows[static_cast<size_t>(3 * c + 1)];
    for (size_t f = 0; f < frames; ++f) {
      if (std::isnan(xs[f]) || std::isnan(ys[f])) continue;
      Spot spot;
      spot.x = xs[f];
      spot.y = ys[f];
      spot.target = 0;
      obs.frames[static_cast<int64_t>(f)][c].push_back(spot);
    }
  }
  if (obs.frames.empty()) throw ObservationError(points_file + ": no point seen by any camera");
  return obs;
}

BlobFrameCollector::BlobFrameCollector(std::string source, std::set<int> cameras,
                                       int max_lag_frames)
    : grouper_(std::move(cameras), max_lag_frames) {
  observations_.source = std::move(source);
}

void BlobFrameCollector::add_trigger(const trigger_t& trigger) {
  if (!grouper_.add_trigger(trigger)) problems_.push_back(grouper_.error());
  take(grouper_.pop_ready());
}

bool BlobFrameCollector::add_blob_frame(const blob_frame_t& part) {
  const bool ok = grouper_.add_blob_part(part);
  if (!ok) problems_.push_back(grouper_.error());
  take(grouper_.pop_ready());
  return ok;
}

Observations BlobFrameCollector::finish() {
  take(grouper_.flush());
  return std::move(observations_);
}

void BlobFrameCollector::take(std::vector<grouping::FrameGroup> groups) {
  for (grouping::FrameGroup& group : groups) {
    ++groups_;
    if (!group.missing_cameras.empty()) ++observations_.incomplete_groups;
    auto& frame = observations_.frames[group.frame_number];
    for (const auto& [camera, blob_frame] : group.blobs) {
      observations_.image_sizes[camera] = {blob_frame.image_width, blob_frame.image_height};
      std::vector<Spot>& spots = frame[camera];
      for (const blob_t& blob : blob_frame.blobs) {
        Spot spot;
        spot.x = blob.x;
        spot.y = blob.y;
        spot.area = blob.area;
        spot.flags = blob.flags;
        spots.push_back(spot);
      }
    }
    if (frame.empty()) observations_.frames.erase(group.frame_number);
  }
}

}  // namespace syncap::calibration
