// The observations `syncap calibrate` starts from: per frame number and camera, the bright spots
// (blobs) the camera saw, in pixels, and each camera's image size. Four sources fill them:
//
// - blob frames (blob_frame_t) of the edges, live or from an LCM log: grouped by frame number
//   through grouping::FrameGrouper (parts joined), every blob kept with its area and flags so that
//   the wand identification can tell targets from reflections;
// - CSV, `frame,camera,x,y[,point]` (pixels, one line a spot, a header line optional): without
//   `point` the spots are blobs to identify; with it they are already identified (the target's
//   index on the wand from end A, or 0 for an LED);
// - a MultiCamSelfCal folder (`points.dat`: 3 rows x, y, 1 per camera and a column per frame,
//   NaN where unseen; `Res.dat`: width height per camera; `camera_order.txt`: names): one
//   identified point (an LED) per frame and camera. Its camera ids are 0.. in file order.
//
// Pixels as everywhere in syncap: (0, 0) is the centre of the top-left pixel, x right, y down.
// MultiCamSelfCal keeps the same convention for its input (the flydra data's x, y are the blob
// centroids of the camera images).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "grouping/frame_grouper.hpp"
#include "syncap/blob_frame_t.hpp"
#include "syncap/trigger_t.hpp"

namespace syncap::calibration {

// A bright spot in one image.
struct Spot {
  double x = 0.0;  // [px]
  double y = 0.0;
  double area = 0.0;  // [px], 0 when unknown (CSV, MultiCamSelfCal)
  int flags = 0;      // blob_t::FLAG_*
  int target = -1;    // identified target index on the wand (0 = end A; LED: 0); -1: unknown
};

struct ImageSize {
  int width = 0;
  int height = 0;
};

// What the cameras saw, by frame number, then camera id.
struct Observations {
  std::string source;                       // "lcmlog:run.lcmlog", ... for messages and reports
  std::map<int, ImageSize> image_sizes;     // by camera id
  std::map<std::string, int> camera_names;  // MultiCamSelfCal names -> id (empty otherwise)
  std::map<int64_t, std::map<int, std::vector<Spot>>> frames;
  long incomplete_groups = 0;  // frame groups that lacked a camera (blob frames only)

  long spot_count() const;
  std::set<int> cameras() const;
};

// Bad input, the message naming the file and line (and column) or the camera and frame.
class ObservationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

Observations read_csv_observations(const std::filesystem::path& file);
// `text` is the CSV itself, `source` its name in messages.
Observations parse_csv_observations(const std::string& text, const std::string& source);

Observations read_mcsc_observations(const std::filesystem::path& folder);
// The texts of a MultiCamSelfCal folder's three files.
struct McscFiles {
  std::string camera_order;  // camera_order.txt
  std::string res;           // Res.dat
  std::string points;        // points.dat
};
// The same on the files' texts; `folder` names them in messages.
Observations parse_mcsc_observations(const McscFiles& files, const std::filesystem::path& folder);

// Collects blob frames (and triggers) as they arrive, live or from a log, into Observations.
// `cameras`: the camera ids to wait for in each frame group; empty: every camera seen (groups are
// then handed out when `max_lag_frames` newer frames arrived, or at finish()).
class BlobFrameCollector {
 public:
  BlobFrameCollector(std::string source, std::set<int> cameras, int max_lag_frames = 30);

  void add_trigger(const trigger_t& trigger);
  // A blob frame (or one part of it). Returns false for a part the grouper rejects (late,
  // inconsistent): counted in problems(), the message kept.
  bool add_blob_frame(const blob_frame_t& part);
  // Hands out every group still held; call once at the end.
  Observations finish();

  long frame_groups() const { return groups_; }
  const std::vector<std::string>& problems() const { return problems_; }

 private:
  void take(std::vector<grouping::FrameGroup> groups);

  grouping::FrameGrouper grouper_;
  Observations observations_;
  long groups_ = 0;
  std::vector<std::string> problems_;
};

}  // namespace syncap::calibration
