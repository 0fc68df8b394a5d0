#include "statistics.hpp"

#include <algorithm>
#include <cmath>

namespace syncap::compare {

void ErrorStats::add(const Eigen::Vector2d& error) {
  ++count_;
  sum_squared_ += error.squaredNorm();
  max_ = std::max(max_, error.norm());
  sum_ += error;
}

ErrorStats& ErrorStats::operator+=(const ErrorStats& other) {
  count_ += other.count_;
  sum_squared_ += other.sum_squared_;
  max_ = std::max(max_, other.max_);
  sum_ += other.sum_;
  return *this;
}

std::optional<double> ErrorStats::rms() const {
  if (count_ == 0) return std::nullopt;
  return std::sqrt(sum_squared_ / static_cast<double>(count_));
}

std::optional<double> ErrorStats::max() const {
  if (count_ == 0) return std::nullopt;
  return max_;
}

std::optional<Eigen::Vector2d> ErrorStats::bias() const {
  if (count_ == 0) return std::nullopt;
  return Eigen::Vector2d(sum_ / static_cast<double>(count_));
}

std::optional<double> Detection::rate() const {
  if (targets == 0) return std::nullopt;
  return static_cast<double>(matched) / static_cast<double>(targets);
}

Detection& Detection::operator+=(const Detection& other) {
  targets += other.targets;
  matched += other.matched;
  errors += other.errors;
  return *this;
}

Tally& Tally::operator+=(const Tally& other) {
  counted += other.counted;
  border += other.border;
  hidden += other.hidden;
  blobs += other.blobs;
  false_blobs += other.false_blobs;
  return *this;
}

void Samples::add(double value) {
  max_ = count_ == 0 ? value : std::max(max_, value);
  min_ = count_ == 0 ? value : std::min(min_, value);
  ++count_;
  sum_ += value;
}

std::optional<double> Samples::mean() const {
  if (count_ == 0) return std::nullopt;
  return sum_ / static_cast<double>(count_);
}

std::optional<double> Samples::max() const {
  if (count_ == 0) return std::nullopt;
  return max_;
}

std::optional<double> Samples::min() const {
  if (count_ == 0) return std::nullopt;
  return min_;
}

Samples& Samples::operator+=(const Samples& other) {
  if (other.count_ == 0) return *this;
  max_ = count_ == 0 ? other.max_ : std::max(max_, other.max_);
  min_ = count_ == 0 ? other.min_ : std::min(min_, other.min_);
  count_ += other.count_;
  sum_ += other.sum_;
  return *this;
}

SilhouetteTally& SilhouetteTally::operator+=(const SilhouetteTally& other) {
  expected += other.expected;
  received += other.received;
  iou += other.iou;
  area_ratio += other.area_ratio;
  return *this;
}

}  // namespace syncap::compare
