// Figures of the comparison; every one can be summed over frames, cameras and phases.
#pragma once

#include <Eigen/Core>
#include <optional>

namespace syncap::compare {

// Centroid errors (blob minus truth), in pixels.
class ErrorStats {
 public:
  void add(const Eigen::Vector2d& error);
  ErrorStats& operator+=(const ErrorStats& other);

  long count() const { return count_; }
  // Root mean square of the error's length; nullopt without errors.
  std::optional<double> rms() const;
  std::optional<double> max() const;
  // Mean error per axis: a systematic offset of the detector or the simulator.
  std::optional<Eigen::Vector2d> bias() const;

 private:
  long count_ = 0;
  double sum_squared_ = 0;
  double max_ = 0;
  Eigen::Vector2d sum_ = Eigen::Vector2d::Zero();
};

// How many truth targets of one kind were there and how many were found, with what error.
struct Detection {
  long targets = 0;
  long matched = 0;
  ErrorStats errors;

  // matched / targets; nullopt without targets.
  std::optional<double> rate() const;
  Detection& operator+=(const Detection& other);
};

// Everything counted for one camera in one frame, and sums of those.
struct Tally {
  Detection counted;  // visible, whole disc inside the image: the figures that decide
  Detection border;   // visible, disc crossing the border: reported only
  long hidden = 0;    // truth targets the camera could not see
  long blobs = 0;
  long false_blobs = 0;  // blobs that matched no visible target

  Tally& operator+=(const Tally& other);
};

// Mean, minimum and maximum of a sampled quantity (the edges' processing time, silhouette IoU).
class Samples {
 public:
  void add(double value);
  Samples& operator+=(const Samples& other);
  long count() const { return count_; }
  std::optional<double> mean() const;
  std::optional<double> min() const;
  std::optional<double> max() const;

 private:
  long count_ = 0;
  double sum_ = 0, min_ = 0, max_ = 0;
};

// Silhouettes against the true masks, over the frames that have a true mask (person phases).
struct SilhouetteTally {
  long expected = 0;  // (frame, camera) with a true mask whose group holds the camera
  long received = 0;  // of those, with a silhouette from the camera
  Samples iou;        // IoU of each received silhouette whose mask or truth is not empty
  // Its area over the true mask's (when that is not empty): below 1, the edge's silhouettes
  // lose the person's outline (too thin), above 1 they take in background (shadow).
  Samples area_ratio;

  SilhouetteTally& operator+=(const SilhouetteTally& other);
};

}  // namespace syncap::compare
