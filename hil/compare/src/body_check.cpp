#include "body_check.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "input_error.hpp"
#include "io/frame_json.hpp"
#include "pipeline/recent_values.hpp"
#include "true_body.hpp"
#include "util/printf_string.hpp"

namespace syncap::compare {
namespace {

namespace fs = std::filesystem;
using Joints = std::map<std::string, Eigen::Vector3d>;

// body_frame_t's flags (proto/msg/body_frame_t.lcm).
constexpr int kStarted = 1, kLost = 4, kNoHull = 8, kNoStart = 16;

// A joint's angle between its two bones: the joint, and the far ends of the bones.
struct JointAngle {
  const char* joint;
  const char* from;  // the first bone runs from here to the joint
  const char* to;    // the second from the joint to here
};
constexpr JointAngle kAngles[] = {
    {"l_hip", "vt10", "l_knee"},          {"r_hip", "vt10", "r_knee"},
    {"l_knee", "l_hip", "l_ankle"},       {"r_knee", "r_hip", "r_ankle"},
    {"l_shoulder", "vl5", "l_elbow"},     {"r_shoulder", "vl5", "r_elbow"},
    {"l_elbow", "l_shoulder", "l_wrist"}, {"r_elbow", "r_shoulder", "r_wrist"}};

std::optional<double> angle_deg(const Joints& j, const JointAngle& a) {
  const auto at = j.find(a.joint), from = j.find(a.from), to = j.find(a.to);
  if (at == j.end() || from == j.end() || to == j.end()) return std::nullopt;
  const Eigen::Vector3d u = at->second - from->second, v = to->second - at->second;
  return std::acos(std::clamp(u.normalized().dot(v.normalized()), -1.0, 1.0)) * 180.0 /
         std::numbers::pi;
}

void score(const Joints& fitted, const Joints& truth, long frame, BodyCheck& check) {
  double sum = 0;
  for (const auto& [name, p] : fitted) {
    const auto t = truth.find(name);
    if (t == truth.end())
      throw InputError("frame " + std::to_string(frame) + ": the truth has no joint '" + name +
                       "'");
    const double e = (p - t->second).norm();
    check.joint_errors_mm[name].push_back(e);
    sum += e * e;
  }
  check.frame_rms_mm.push_back(std::sqrt(sum / static_cast<double>(fitted.size())));
  for (const JointAngle& a : kAngles) {
    const auto fit = angle_deg(fitted, a), real = angle_deg(truth, a);
    if (fit && real) check.angle_errors_deg[a.joint].push_back(std::abs(*fit - *real));
  }
}

// The frame's errors over the sigmas its record predicts (scaled as the joints were moved).
void score_precision(const io::FrameRecord& r, const Joints& fitted, const Joints& truth,
                     double scale, BodyCheck& check) {
  const pipeline::BodyFitSummary& b = *r.body;
  if (b.joint_sigmas_mm.size() != b.joint_names.size()) return;
  check.sigma0.push_back(b.sigma0);
  for (std::size_t j = 0; j < b.joint_names.size(); ++j) {
    const double sigma = scale * b.joint_sigmas_mm[j];
    const double error = (fitted.at(b.joint_names[j]) - truth.at(b.joint_names[j])).norm();
    check.joint_sigmas_mm.push_back(sigma);
    check.normalized_errors.push_back(sigma > 0 ? error / (std::sqrt(3.0) * sigma) : 0.0);
  }
}

double mean(const std::vector<double>& v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

}  // namespace

double BodyCheck::rms_mm() const {
  double sum = 0;
  long n = 0;
  for (const auto& [name, errors] : joint_errors_mm)
    for (const double e : errors) sum += e * e, ++n;
  return n > 0 ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
}

double BodyCheck::mean_angle_error_deg() const {
  std::vector<double> all;
  for (const auto& [name, errors] : angle_errors_deg)
    all.insert(all.end(), errors.begin(), errors.end());
  return mean(all);
}

double BodyCheck::sigma_ratio() const {
  double squares = 0;
  for (const double z : normalized_errors) squares += z * z;
  return normalized_errors.empty()
             ? 0.0
             : std::sqrt(squares / static_cast<double>(normalized_errors.size()));
}

BodyCheck check_body(const fs::path& truth_dir, const fs::path& groups_file,
                     const std::optional<Similarity>& to_truth) {
  std::map<long, Joints> truth;
  for (auto& [frame, body] : read_true_bodies(truth_dir / "truth" / "body.jsonl"))
    truth[frame] = std::move(body.joints_mm);
  std::vector<io::FrameRecord> records;
  try {
    records = io::read_frame_lines(groups_file);
  } catch (const io::FrameLineError& e) {
    throw InputError(e.what());
  }
  BodyCheck check;
  for (const io::FrameRecord& r : records) {
    const auto true_joints = truth.find(static_cast<long>(r.frame));
    if (!r.body || true_joints == truth.end() || true_joints->second.empty()) continue;
    ++check.frames;
    const int flags = r.body->flags;
    check.starts += (flags & kStarted) ? 1 : 0;
    check.lost += (flags & kLost) ? 1 : 0;
    check.no_start += (flags & kNoStart) ? 1 : 0;
    check.no_hull += (flags & kNoHull) ? 1 : 0;
    if (r.body->joints_mm.empty()) continue;
    ++check.fitted;
    Joints fitted;
    for (std::size_t j = 0; j < r.body->joints_mm.size(); ++j)
      fitted[r.body->joint_names[j]] =
          to_truth ? to_truth->apply(r.body->joints_mm[j]) : r.body->joints_mm[j];
    score(fitted, true_joints->second, static_cast<long>(r.frame), check);
    score_precision(r, fitted, true_joints->second, to_truth ? to_truth->scale : 1.0, check);
    if (flags & kStarted)
      check.starts_rms_mm.emplace_back(static_cast<long>(r.frame), check.frame_rms_mm.back());
  }
  return check;
}

std::string format_body_check(const BodyCheck& c) {
  // Quantiles by nearest rank, as the host's own summaries.
  const auto quantile = [&c](double p) { return pipeline::quantile(c.frame_rms_mm, p); };
  std::string out = util::printf_string(
      "body: %ld frames with a true body, %ld fitted (%ld starts, %ld lost, %ld found no body, "
      "%ld without a hull); joint-centre RMS %.1f mm (per frame median %.1f, p95 %.1f, max "
      "%.1f); joint-angle error mean %.1f deg",
      c.frames, c.fitted, c.starts, c.lost, c.no_start, c.no_hull, c.rms_mm(), quantile(0.5),
      quantile(0.95), quantile(1.0), c.mean_angle_error_deg());
  for (const char* pair : {"hip", "knee", "shoulder", "elbow"}) {
    std::vector<double> both;
    for (const char* side : {"l_", "r_"}) {
      const auto it = c.angle_errors_deg.find(std::string(side) + pair);
      if (it != c.angle_errors_deg.end())
        both.insert(both.end(), it->second.begin(), it->second.end());
    }
    out += util::printf_string(", %ss %.1f", pair, mean(both));
  }
  out += "\nbody: joints, mean error worst first:";
  std::vector<std::pair<double, std::string>> joints;
  for (const auto& [name, errors] : c.joint_errors_mm) joints.emplace_back(mean(errors), name);
  std::sort(joints.rbegin(), joints.rend());
  for (const auto& [error, name] : joints)
    out += util::printf_string(" %s %.1f", name.c_str(), error);
  out += " (mm)\n";
  if (!c.normalized_errors.empty()) {
    const long within = std::count_if(c.normalized_errors.begin(), c.normalized_errors.end(),
                                      [](double z) { return z <= 3.0; });
    out += util::printf_string(
        "body: precision: joint sigma median %.1f mm (p95 %.1f), sigma0 median %.2f; error / "
        "predicted sigma RMS %.2f (1: honest), within 3 sigma %.1f %%\n",
        pipeline::quantile(c.joint_sigmas_mm, 0.5), pipeline::quantile(c.joint_sigmas_mm, 0.95),
        pipeline::quantile(c.sigma0, 0.5), c.sigma_ratio(),
        100.0 * static_cast<double>(within) / static_cast<double>(c.normalized_errors.size()));
  }
  if (c.starts_rms_mm.empty()) return out;
  std::vector<double> rms;
  for (const auto& [frame, error] : c.starts_rms_mm) rms.push_back(error);
  const long good = std::count_if(rms.begin(), rms.end(), [](double e) { return e <= 50.0; });
  out += util::printf_string(
      "body: automatic starts: %zu, joint RMS within 50 mm in %ld (%.0f %%), median %.1f mm, max "
      "%.1f mm",
      rms.size(), good, 100.0 * static_cast<double>(good) / static_cast<double>(rms.size()),
      pipeline::quantile(rms, 0.5), pipeline::quantile(rms, 1.0));
  std::vector<std::pair<long, double>> worst = c.starts_rms_mm;
  std::sort(worst.begin(), worst.end(),
            [](const auto& a, const auto& b) { return a.second > b.second; });
  for (std::size_t i = 0; i < worst.size() && i < 3 && worst[i].second > 50.0; ++i)
    out += util::printf_string("%s frame %ld %.0f mm", i == 0 ? "; worst:" : ",", worst[i].first,
                               worst[i].second);
  return out + "\n";
}

}  // namespace syncap::compare
