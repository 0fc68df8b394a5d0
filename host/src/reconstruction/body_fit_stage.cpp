#include "reconstruction/body_fit_stage.hpp"

#include "pipeline/frame_work.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "syncap/body_frame_t.hpp"
#include "util/printf_string.hpp"

namespace syncap::reconstruction {

BodyFitStage::BodyFitStage(const body::Skeleton& skeleton, BodyFitStageOptions options)
    : parameters_(skeleton),
      joint_names_(parameters_.reported_joint_names()),
      options_(options),
      tracker_(parameters_, options_.tracker) {}

void BodyFitStage::process(pipeline::FrameWork& work) {
  if (!work.hull) return;  // no silhouettes in this group: nothing to say about the body
  ++stats_.frames;
  pipeline::BodyFitSummary body;
  if (!work.group.trigger) body.flags |= body_frame_t::FLAG_NO_TRIGGER;
  const std::vector<Eigen::Vector3d>& surface = work.hull->surface_mm;
  body.points = static_cast<int>(surface.size());
  if (surface.size() < static_cast<std::size_t>(fitting::kPoseParameterCount)) {
    body.flags |= body_frame_t::FLAG_NO_HULL;
    ++stats_.no_hull;
  } else {
    std::vector<fitting::SurfacePoint> points;
    points.reserve(surface.size());
    for (const Eigen::Vector3d& p : surface) points.push_back({p, options_.point_sigma_mm});
    if (options_.restart_every > 0 && work.group.frame_number % options_.restart_every == 0)
      tracker_.stop();
    const auto begin = std::chrono::steady_clock::now();
    fit(work.group.frame_number, points, body);
    body.fit_us =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - begin).count();
    stats_.fit_us.add(body.fit_us);
  }
  work.body = std::move(body);
}

void BodyFitStage::fit(int64_t frame_number, std::span<const fitting::SurfacePoint> points,
                       pipeline::BodyFitSummary& body) {
  try {
    if (tracker_.tracking()) {
      const fitting::TrackedFrame tracked = tracker_.track(points);
      ++stats_.tracked;
      if (tracked.predicted) body.flags |= body_frame_t::FLAG_TRACKED;
      if (!tracked.lost) {
        describe(tracked.fit, body);
        return;
      }
      // Lost: the same frame's hull starts the body again, so that the frame still gets a pose.
      body.flags |= body_frame_t::FLAG_LOST;
      ++stats_.lost;
      stats_.last_problem = util::printf_string(
          "frame %lld: track lost (%d of %zu points kept), started again",
          static_cast<long long>(frame_number), tracked.fit.points, points.size());
    }
    start(frame_number, points, body);
  } catch (const std::exception& e) {  // fit_surface's checks: a point that is not finite
    body.flags |= body_frame_t::FLAG_NO_HULL;
    ++stats_.no_hull;
    stats_.last_problem = "frame " + std::to_string(frame_number) + ": " + e.what();
  }
}

int BodyFitStage::retry_frames(double start_ms) const {
  int frames = options_.start_retry_frames;
  if (options_.start_budget_ms > 0)
    frames = std::max(frames, static_cast<int>(std::ceil(start_ms / options_.start_budget_ms)));
  return frames;
}

void BodyFitStage::start(int64_t frame_number, std::span<const fitting::SurfacePoint> points,
                         pipeline::BodyFitSummary& body) {
  if (frame_number > failed_start_frame_ && frame_number < next_start_frame_) {
    body.flags |= body_frame_t::FLAG_NO_START;
    ++stats_.start_waits;
    return;
  }
  // The start's cost in this thread's CPU time, not the wall clock's: the interval to the next
  // attempt, and so which frames are fitted, must not depend on what else the machine runs.
  const double begin_us = pipeline::thread_cpu_us();
  const fitting::BodyStart start = fitting::start_body(parameters_, points, options_.start);
  if (!start.found) {
    body.flags |= body_frame_t::FLAG_NO_START;
    ++stats_.no_start;
    failed_start_frame_ = frame_number;
    next_start_frame_ = frame_number + retry_frames(1e-3 * (pipeline::thread_cpu_us() - begin_us));
    stats_.last_problem =
        util::printf_string("frame %lld: no start: %s; next attempt at frame %lld",
                            static_cast<long long>(frame_number), start.why_not.c_str(),
                            static_cast<long long>(next_start_frame_));
    return;
  }
  tracker_.start(start.fit.x);
  body.flags |= body_frame_t::FLAG_STARTED;
  ++stats_.starts;
  describe(start.fit, body);
}

void BodyFitStage::describe(const fitting::SurfaceFit& fit, pipeline::BodyFitSummary& body) const {
  body.parameters.assign(fit.x.begin(), fit.x.end());
  body.rms_mm = fit.rms_mm;
  body.points_kept = fit.points;
  std::vector<Eigen::Matrix3d> rotations;
  std::vector<Eigen::Vector3d> positions;
  parameters_.nodes(fit.x.data(), rotations, positions);
  body.joint_names = joint_names_;
  body.joints_mm.clear();
  for (const int node : parameters_.reported_nodes())
    body.joints_mm.push_back(positions[static_cast<std::size_t>(node)]);
  body.sigma0 = fit.precision.sigma0;
  body.parameter_sigmas.clear();
  body.joint_sigmas_mm.clear();
  if (fit.precision.valid) {
    body.parameter_sigmas.assign(fit.precision.sigmas.begin(), fit.precision.sigmas.end());
    body.joint_sigmas_mm = fit.precision.joint_sigmas_mm;
  }
}

std::string BodyFitStage::summary() const {
  const BodyFitStageStats& s = stats_;
  std::string line = util::printf_string(
      "host body: %ld frames with a hull, %ld without points to fit, %ld starts (%ld found no "
      "body), %ld frames tracked, %ld lost; fit time p50 %.1f ms, p99 %.1f ms\n",
      s.frames, s.no_hull, s.starts, s.no_start, s.tracked, s.lost,
      pipeline::quantile(s.fit_us.values(), 0.5) * 1e-3,
      pipeline::quantile(s.fit_us.values(), 0.99) * 1e-3);
  if (s.start_waits > 0)
    line += util::printf_string(
        "host body: %ld frames waited for the next start (after a start that found no body, "
        "the next %d frames or more, so that starts cost at most %.0f ms a frame)\n",
        s.start_waits, options_.start_retry_frames, options_.start_budget_ms);
  if (!s.last_problem.empty()) line += "host body: last problem: " + s.last_problem + "\n";
  return line;
}

}  // namespace syncap::reconstruction
