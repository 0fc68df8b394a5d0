// The latest values of a series (a ring), for quantiles over a run of any length with flat memory.
#pragma once

#include <cstddef>
#include <vector>

namespace syncap::pipeline {

class RecentValues {
 public:
  explicit RecentValues(std::size_t capacity = 10000) : capacity_(capacity) {}
  void add(double value) {
    const std::size_t slot = added_ % capacity_;
    if (slot < values_.size()) {
      values_[slot] = value;
    } else {
      values_.push_back(value);
    }
    ++added_;
  }
  const std::vector<double>& values() const { return values_; }  // in no particular order
  std::size_t added() const { return added_; }

 private:
  std::size_t capacity_;
  std::size_t added_ = 0;
  std::vector<double> values_;
};

// p-quantile (0..1) of `values` (nearest rank); 0 for none.
double quantile(std::vector<double> values, double p);

}  // namespace syncap::pipeline
