#include "fitting/body_tracker.hpp"

#include <stdexcept>

namespace syncap::fitting {

BodyTracker::BodyTracker(const PoseParameters& parameters, BodyTrackerOptions options)
    : parameters_(parameters), options_(options) {}

void BodyTracker::start(const PoseVector& pose) {
  last_ = pose;
  before_last_.reset();
  ++counters_.starts;
}

TrackedFrame BodyTracker::track(std::span<const SurfacePoint> points) {
  if (!last_) throw std::logic_error("fitting: BodyTracker::track before start()");
  TrackedFrame frame;
  PoseVector begin = *last_;
  if (before_last_) {
    for (std::size_t i = 0; i < begin.size(); ++i)
      begin[i] = 2.0 * (*last_)[i] - (*before_last_)[i];
    frame.predicted = true;
  }
  frame.fit = fit_surface(parameters_, points, begin, options_.fit);
  ++counters_.frames;
  const double kept = static_cast<double>(frame.fit.points) / static_cast<double>(points.size());
  if (kept < options_.min_points_kept) {
    frame.lost = true;
    ++counters_.lost;
    stop();
    return frame;
  }
  before_last_ = last_;
  last_ = frame.fit.x;
  return frame;
}

}  // namespace syncap::fitting
