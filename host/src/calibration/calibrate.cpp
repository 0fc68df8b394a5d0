#include "calibration/calibrate.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "calibration/stages.hpp"
#include "calibration/verdict.hpp"
#include "estimators/bootstrap.hpp"
#include "util/printf_string.hpp"

namespace syncap::calibration {
namespace {

// The thesis finds the interior orientation stable from about 40 wand positions on (Table 4.3).
constexpr size_t kStableFrames = 40;

std::string camera_name(int id) {
  std::ostringstream name;
  name << "camera" << (id < 10 ? "0" : "") << id;
  return name.str();
}

std::string point_name(int64_t frame, int target, bool led) {
  return "f" + std::to_string(frame) + (led ? "" : "t" + std::to_string(target));
}

void say(const CalibrationOptions& options, const std::string& line) {
  if (options.progress) options.progress(line);
}

// The frames used: those where at least two cameras identified the wand, evenly thinned to
// max_frames.
std::vector<int64_t> frames_to_use(const Identification& identification, int max_frames) {
  std::vector<int64_t> frames;
  for (const auto& [frame, cameras] : identification.frames) {
    if (cameras.size() >= 2) frames.push_back(frame);
  }
  return evenly_spread(std::move(frames), max_frames);
}

bool same_sensor(const sensor::SensorGeometry& a, const sensor::SensorGeometry& b) {
  return a.width_px == b.width_px && a.height_px == b.height_px &&
         a.pixel_width_mm == b.pixel_width_mm && a.pixel_height_mm == b.pixel_height_mm;
}

// The frames the adjustment uses and those held out of it as check points.
struct FrameSplit {
  std::vector<int64_t> adjusted;
  std::vector<int64_t> held_out;
};

FrameSplit split_frames(const Identification& identification, const CalibrationOptions& options) {
  FrameSplit out;
  const std::vector<int64_t> all = frames_to_use(identification, options.max_frames);
  out.held_out = check_frames(all, options.check_point_share);
  const std::set<int64_t> held(out.held_out.begin(), out.held_out.end());
  for (int64_t f : all) {
    if (!held.count(f)) out.adjusted.push_back(f);
  }
  return out;
}

const auto& kInteriorNames = sensor::InteriorBlock::kNames;
const char* kInteriorUnits[] = {"mm",    "mm",    "mm",    "mm^-2", "mm^-4",
                                "mm^-6", "mm^-1", "mm^-1", "1",     "1"};
const auto& kExteriorNames = sensor::ExteriorBlock::kNames;
const char* kExteriorUnits[] = {"mm", "mm", "mm", "rad", "rad", "rad"};

const char* mode_name(scene::ParameterMode mode) {
  switch (mode) {
    case scene::ParameterMode::kFixed:
      return "fixed";
    case scene::ParameterMode::kObserved:
      return "observed";
    case scene::ParameterMode::kFree:
      break;
  }
  return "free";
}

// `scaled`: the network has a scale (a wand); without one (an LED) positions are in the
// arbitrary units of the start's first base, not mm.
ReportCamera report_camera(const sensor::CameraModel& camera, const scene::CameraModel& model,
                           const estimators::ModelResult& m, const estimators::StationResult& s,
                           bool scaled) {
  ReportCamera c;
  c.camera = camera;
  const auto interior = sensor::interior_block(m.interior);
  for (int i = 0; i < sensor::InteriorBlock::kSize; ++i) {
    c.parameters.push_back({kInteriorNames[i], interior[static_cast<size_t>(i)],
                            m.interior_sigma[static_cast<size_t>(i)], kInteriorUnits[i],
                            mode_name(model.priors[static_cast<size_t>(i)].mode)});
  }
  const auto exterior = sensor::exterior_block(s.exterior);
  for (int i = 0; i < sensor::ExteriorBlock::kSize; ++i) {
    c.parameters.push_back({kExteriorNames[i], exterior[static_cast<size_t>(i)],
                            s.exterior_sigma[static_cast<size_t>(i)],
                            i < 3 && !scaled ? "units" : kExteriorUnits[i], "free"});
  }
  for (int i : m.estimated_interior) c.correlation_names.push_back(kInteriorNames[i]);
  c.correlation = m.interior_correlation;
  c.rms_px = s.rms_px;
  c.observations = s.measurements;
  c.rejected = s.rejected;
  return c;
}

// The adjusted wand lengths, one per frame with both end points adjusted.
std::vector<double> adjusted_wand_lengths(const scene::Network& network,
                                          const estimators::BundleAdjustmentResult& r,
                                          const std::vector<int64_t>& frames,
                                          const WandSpec& wand) {
  std::map<std::string, size_t> index;
  for (size_t p = 0; p < network.points.size(); ++p) index[network.points[p].name] = p;
  std::vector<double> lengths;
  if (wand.led) return lengths;
  for (int64_t frame : frames) {
    const auto a = index.find(point_name(frame, 0, false));
    const auto b = index.find(point_name(frame, wand.targets - 1, false));
    if (a == index.end() || b == index.end()) continue;
    const auto& pa = r.points[a->second];
    const auto& pb = r.points[b->second];
    if (!pa.adjusted || !pb.adjusted) continue;
    lengths.push_back(
        std::hypot(pa.xyz[0] - pb.xyz[0], pa.xyz[1] - pb.xyz[1], pa.xyz[2] - pb.xyz[2]));
  }
  return lengths;
}
// The parametric bootstrap's interior sigmas beside the linearised ones in the report.
// `nominal`: the camera models the calibration started from.
void add_bootstrap(CalibrationResult& out, const CalibrationOptions& options,
                   const std::vector<scene::CameraModel>& nominal) {
  say(options, "bootstrap: " + std::to_string(options.bootstrap_samples) + " re-adjustments ...");
  estimators::BootstrapOptions bootstrap;
  bootstrap.samples = options.bootstrap_samples;
  // Each sample goes the calibration's whole way from its own observations to the second stage.
  bootstrap.restart = [&options, &nominal](scene::Network sample) {
    for (size_t m = 0; m < sample.models.size() && m < nominal.size(); ++m) {
      sample.models[m].interior = nominal[m].interior;
    }
    scene::Network second = second_stage_start(std::move(sample), options).network;
    prepare_stage(second, options, {true, true});
    return second;
  };
  const estimators::BootstrapResult b =
      estimators::bootstrap_precision(out.network, out.adjustment, bootstrap);
  out.report.bootstrap_samples = b.samples;
  for (size_t s = 0; s < out.report.cameras.size(); ++s) {
    const size_t m = model_index(out.network, s);
    if (m >= b.interior_sigma.size()) continue;
    auto& parameters = out.report.cameras[s].parameters;
    for (int i = 0; i < sensor::InteriorBlock::kSize && i < static_cast<int>(parameters.size());
         ++i) {
      parameters[static_cast<size_t>(i)].bootstrap_sigma =
          b.interior_sigma[m][static_cast<size_t>(i)];
    }
  }
  say(options, "bootstrap: " + std::to_string(b.samples) + " converged, " +
                   std::to_string(b.failed) + " did not");
}

void fill_report(CalibrationResult& out, const Observations& observations,
                 const CalibrationOptions& options, const std::vector<int64_t>& frames) {
  const auto& r = out.adjustment;
  const scene::Network& network = out.network;
  CalibrationReport& report = out.report;
  report.input = observations.source;
  std::map<std::string, int> camera_of_station;
  for (size_t s = 0; s < network.stations.size(); ++s) {
    camera_of_station[network.stations[s].name] = network.stations[s].camera_id;
    const size_t m = model_index(network, s);
    report.cameras.push_back(report_camera(out.cameras[s], network.models[m], r.models[m],
                                           r.stations[s],
                                           !options.wand.led || options.scale_from.has_value()));
  }
  for (size_t m = 0; m < network.measurements.size(); ++m) {
    const auto& meas = network.measurements[m];
    const auto& res = r.measurements[m];
    const double w = std::abs(res.w_u) > std::abs(res.w_v) ? res.w_u : res.w_v;
    report.residuals.push_back({camera_of_station[meas.station], meas.frame_number, meas.u, meas.v,
                                res.residual_u, res.residual_v, w,
                                res.status != estimators::MeasurementStatus::kAccepted});
  }
  for (const auto& p : r.points) {
    if (p.adjusted) report.points.emplace_back(p.xyz[0], p.xyz[1], p.xyz[2]);
  }
  report.wand_lengths_mm = adjusted_wand_lengths(network, r, frames, options.wand);
  report.wand_length_mm = options.wand.led ? 0.0 : options.wand.length_mm;
  report.sigma0 = r.sigma0;
  report.observations = r.observations;
  report.unknowns = r.unknowns;
  report.redundancy = r.redundancy;
  report.iterations = r.iterations;
  report.converged = r.converged;
  report.outliers_removed = static_cast<long>(r.rejected.size());
  if (r.tests_computed) {
    const auto& v = r.variance_test;
    report.tests.push_back(
        {"variance factor (chi-square, two-tailed)", v.variance_factor, v.lower, v.upper, v.passed,
         "sigma0^2 against its interval for redundancy " + std::to_string(v.redundancy)});
    const auto& g = r.goodness_of_fit;
    std::ostringstream detail;
    detail << g.samples << " standardised residuals in " << g.bins
           << " classes; Kolmogorov-Smirnov distance " << g.ks_distance << ", p " << g.ks_p_value;
    report.tests.push_back({"goodness of fit (chi-square of the standardised residuals)",
                            g.statistic, 0.0, g.critical, g.passed, detail.str()});
  }
  std::istringstream identification(format_identification(out.identification));
  for (std::string line; std::getline(identification, line);) report.messages.push_back(line);
  if (observations.incomplete_groups > 0) {
    report.messages.push_back(std::to_string(observations.incomplete_groups) +
                              " frame groups lacked a camera");
  }
  for (const std::string& m : r.messages) report.messages.push_back(m);
  if (options.wand.led && !options.scale_from) {
    report.messages.push_back(
        "no scale (one LED): positions (X0, Y0, Z0, the points) are in arbitrary units, those of "
        "the start's first base, not mm; angles and the interior orientation are not affected");
  }
  if (options.bootstrap_samples < 2 && (options.wand.led || frames.size() < kStableFrames)) {
    report.messages.push_back(
        "weak network (" +
        (options.wand.led ? std::string("one LED a frame")
                          : std::to_string(frames.size()) + " wand positions") +
        "): its minima are several and its linearised sigmas can understate the errors several "
        "times; --bootstrap 30 gives sigmas that cover them (docs/design/calibration.md)");
  }
}

sensor::CalibrationQuality quality_of(const CalibrationResult& out, const CalibrationOptions& o) {
  const auto& r = out.adjustment;
  sensor::CalibrationQuality q;
  q.sigma0_px = r.sigma0 * o.sigma_px;
  double square_sum = 0;
  long accepted = 0;
  for (const auto& m : r.measurements) {
    if (m.status != estimators::MeasurementStatus::kAccepted) continue;
    square_sum += m.residual_u * m.residual_u + m.residual_v * m.residual_v;
    ++accepted;
  }
  q.rms_px = accepted ? std::sqrt(square_sum / (2.0 * accepted)) : 0.0;
  for (const auto& s : r.stations) q.per_camera_rms_px[s.camera_id] = s.rms_px;
  q.observations = accepted;
  q.outliers_removed = static_cast<long>(r.rejected.size());
  const auto& lengths = out.report.wand_lengths_mm;
  if (!o.wand.led && !lengths.empty()) {
    double sum = 0, sum2 = 0;
    for (double l : lengths) sum += l;
    const double mean = sum / static_cast<double>(lengths.size());
    for (double l : lengths) sum2 += (l - mean) * (l - mean);
    q.wand_length_mean_mm = mean;
    q.wand_length_sd_mm =
        lengths.size() > 1 ? std::sqrt(sum2 / static_cast<double>(lengths.size() - 1)) : 0.0;
  }
  return q;
}

void check_options(const CalibrationOptions& options) {
  const WandSpec& wand = options.wand;
  if (options.scale_from && !wand.led) {
    throw CalibrationError("calibrate: --scale-from is for an LED; the wand gives the scale");
  }
  if (options.scale_from && !(options.scale_from->distance_mm > 0)) {
    throw CalibrationError("calibrate: --scale-from needs a distance > 0 mm");
  }
  if (!wand.led) {
    if (!(wand.length_mm > 0)) throw CalibrationError("calibrate: the wand length must be > 0 mm");
    if (wand.targets != 2 && wand.targets != 3) {
      throw CalibrationError("calibrate: a wand has 2 or 3 targets, not " +
                             std::to_string(wand.targets));
    }
    if (wand.targets == 3 && !(wand.middle_ratio > 0.05 && wand.middle_ratio < 0.95)) {
      throw CalibrationError("calibrate: the middle target's ratio must lie in (0.05, 0.95)");
    }
  }
  if (!(options.field_of_view_deg > 5 && options.field_of_view_deg < 170)) {
    throw CalibrationError("calibrate: the field of view must lie in (5, 170) degrees");
  }
  if (options.bootstrap_samples < 0 || options.bootstrap_samples == 1) {
    throw CalibrationError("calibrate: --bootstrap needs at least 2 re-adjustments, not " +
                           std::to_string(options.bootstrap_samples));
  }
  if (!(options.sigma_px > 0)) throw CalibrationError("calibrate: sigma_px must be > 0");
}

// The start search's choice (start_search.hpp) becomes the network's interior start values.
void choose_start(scene::Network& network, const CalibrationOptions& options,
                  CalibrationResult& out) {
  out.start_search = search_start(network, options);
  const std::vector<std::string> lines = describe(out.start_search);
  if (!lines.empty()) say(options, lines.back());
  if (out.start_search.chosen < 0) {
    say(options, "start search: every start failed; the calibration starts from " +
                     std::to_string(options.field_of_view_deg) + " deg");
    return;
  }
  const StartCandidate& best =
      out.start_search.candidates[static_cast<size_t>(out.start_search.chosen)];
  for (size_t m = 0; m < network.models.size() && m < best.interiors.size(); ++m) {
    network.models[m].interior = best.interiors[m];
  }
}

// The final adjustment with data snooping: the base model, then the groups the data carry
// (model_selection.hpp). Returns the options of the model adjusted.
CalibrationOptions adjust_final(scene::Network& network, const CalibrationOptions& options,
                                CalibrationResult& out) {
  CalibrationOptions model = options;
  const std::vector<int> requested = requested_interior(options);
  model.free_interior = selects_model(options) ? base_model(requested) : requested;
  out.adjustment = adjust_stage(network, model, {true, true});
  out.model.base = model.free_interior;
  out.model.final = model.free_interior;
  if (!selects_model(options) || !out.adjustment.converged) return model;
  out.model = select_model(network, out.adjustment, options);
  for (const GroupTest& t : out.model.tests) say(options, "model: " + t.text);
  if (out.model.final == out.model.base) return model;
  model.free_interior = out.model.final;
  network = estimators::with_adjusted_values(std::move(network), out.adjustment);
  out.adjustment = adjust_stage(network, model, {true, true});
  return model;
}

// The verdict into the quality block (cameras.json) and at the top of the report, with the
// start search and the check points.
void add_verdict(CalibrationResult& out) {
  const std::vector<std::string> search = describe(out.start_search);
  out.report.start_search = search;
  out.report.halves = out.halves.text;
  out.report.model_selection = {"estimated " + interior_names(out.model.final)};
  for (const GroupTest& t : out.model.tests) out.report.model_selection.push_back(t.text);
  const CheckPointResult& c = out.check_points;
  if (c.frames > 0) {
    out.report.check_points = util::printf_string(
        "%d frames held out, %ld points, %ld image points predicted: median distance %.4f px "
        "(the fit's %.4f px), RMS %.4f px (the fit's %.4f px); %ld rays beyond %.2f px",
        c.frames, c.points, c.measurements, c.median_px, c.fit_median_px, c.rms_px,
        out.quality.rms_px, c.outliers, c.outlier_bound_px);
  }
  out.quality.verdict = verdict_name(out.verdict);
  out.report.verdict = verdict_name(out.verdict);
  for (const Finding& f : out.findings) {
    out.quality.verdict_reasons.push_back(f.text);
    out.report.verdict_reasons.push_back(std::string(verdict_name(f.severity)) + ": " + f.text);
  }
}

// The adjusted cameras with their standard deviations.
std::vector<sensor::CameraModel> cameras_of(const scene::Network& network,
                                            const estimators::BundleAdjustmentResult& r) {
  std::vector<sensor::CameraModel> cameras;
  for (size_t s = 0; s < network.stations.size(); ++s) {
    const auto& m = r.models[model_index(network, s)];
    const auto& st = r.stations[s];
    sensor::CameraModel camera;
    camera.id = st.camera_id;
    camera.sensor = network.models[model_index(network, s)].sensor;
    camera.interior = m.interior;
    camera.exterior = st.exterior;
    if (r.covariance_computed) {
      camera.std_devs =
          sensor::CameraStdDevs{sensor::interior_from_block(m.interior_sigma.data()),
                                sensor::exterior_from_block(st.exterior_sigma.data())};
    }
    cameras.push_back(camera);
  }
  return cameras;
}

// Scales row and column `at` of the camera covariance, and the model's interior covariance when
// the column is one of its interior values, so that the variance becomes `sigma`^2.
void set_camera_sigma(estimators::BundleAdjustmentResult& r, int at, double sigma) {
  Eigen::MatrixXd& c = r.camera_covariance;
  if (at >= c.rows() || !(c(at, at) > 0)) return;
  const double f = sigma / std::sqrt(c(at, at));
  c.row(at) *= f;
  c.col(at) *= f;
  const int m = at / sensor::InteriorBlock::kSize;
  if (m >= static_cast<int>(r.models.size())) return;
  const int k = at % sensor::InteriorBlock::kSize;
  r.models[m].interior_covariance.row(k) *= f;
  r.models[m].interior_covariance.col(k) *= f;
}

// The whole's sigmas with the halves' excess added (halves_excess): the systematic part of the
// error that the halves show and no covariance of one calibration can see. Returns the largest
// factor a camera constant's sigma grew by.
double widen_by_halves(CalibrationResult& out) {
  const HalvesExcess e = halves_excess(out.halves, out.cameras);
  if (e.interior_variance.empty()) return 1.0;
  estimators::BundleAdjustmentResult& r = out.adjustment;
  const int interiors = static_cast<int>(r.models.size()) * sensor::InteriorBlock::kSize;
  std::vector<std::array<double, 10>> model_excess(r.models.size(), std::array<double, 10>{});
  for (size_t s = 0; s < r.stations.size(); ++s) {
    auto& excess = model_excess[model_index(out.network, s)];
    for (size_t k = 0; k < excess.size(); ++k)
      excess[k] = std::max(excess[k], e.interior_variance[s][k]);
  }
  double widest = 1.0;
  for (size_t m = 0; m < r.models.size(); ++m) {
    for (int k = 0; k < sensor::InteriorBlock::kSize; ++k) {
      double& sigma = r.models[m].interior_sigma[static_cast<size_t>(k)];
      if (!(sigma > 0)) continue;
      const double widened = std::sqrt(sigma * sigma + model_excess[m][static_cast<size_t>(k)]);
      if (k == sensor::InteriorBlock::kC) widest = std::max(widest, widened / sigma);
      sigma = widened;
      set_camera_sigma(r, static_cast<int>(m) * sensor::InteriorBlock::kSize + k, widened);
    }
  }
  for (size_t s = 0; s < r.stations.size(); ++s) {
    for (int k = 0; k < 3; ++k) {
      double& sigma = r.stations[s].exterior_sigma[static_cast<size_t>(k)];
      sigma = std::sqrt(sigma * sigma + e.centre_variance[s]);
      set_camera_sigma(r, interiors + static_cast<int>(s) * sensor::ExteriorBlock::kSize + k,
                       sigma);
    }
  }
  out.cameras = cameras_of(out.network, r);
  for (size_t s = 0; s < out.report.cameras.size() && s < r.stations.size(); ++s) {
    auto& parameters = out.report.cameras[s].parameters;
    const auto& m = r.models[model_index(out.network, s)];
    for (int k = 0; k < sensor::InteriorBlock::kSize; ++k)
      parameters[static_cast<size_t>(k)].sigma = m.interior_sigma[static_cast<size_t>(k)];
    for (int k = 0; k < 3; ++k) {
      parameters[static_cast<size_t>(sensor::InteriorBlock::kSize + k)].sigma =
          r.stations[s].exterior_sigma[static_cast<size_t>(k)];
    }
  }
  return widest;
}

// The checks of verdict.hpp on a finished result: the held-out frames predicted, the two halves
// calibrated alone (`model`: the final model's options, `nominal`: the models' start), the
// verdict.
void check(CalibrationResult& out, const Observations& observations,
           const CalibrationOptions& model, const std::vector<int64_t>& frames,
           const std::vector<scene::CameraModel>& nominal) {
  // Held-out rays farther than this from their point are blunders, not prediction errors.
  const double bound_px = std::max(1.0, 8.0 * out.adjustment.sigma0 * model.sigma_px);
  out.check_points =
      predict_check_points(out.cameras, out.identification, out.check_frames, bound_px);
  out.check_points.fit_median_px = median_residual_px(out.adjustment, false);
  if (model.compare_halves && frames.size() >= 2 * kStableFrames && out.adjustment.converged) {
    say(model, "halves: calibrating the first and the second half of the frames alone ...");
    std::vector<sensor::InteriorOrientation> start;
    for (const scene::CameraModel& m : nominal) start.push_back(m.interior);
    out.halves = compare_halves(observations, frames, model, start);
    const double widest = widen_by_halves(out);
    if (widest > 1.0 + 1e-9) {
      out.halves.text += util::printf_string(
          "; the sigmas include the part of it the halves' own sigmas do not explain (c's up to "
          "%.2fx)",
          widest);
    }
    say(model, "halves: " + out.halves.text);
  }
  out.findings = judge(out);
  out.verdict = worst(out.findings);
  add_verdict(out);
}

}  // namespace

bool selects_model(const CalibrationOptions& options) {
  return options.select_model.value_or(options.wand.led);
}

double principal_point_sigma(const CalibrationOptions& options) {
  return options.principal_point_sigma_share.value_or(options.wand.led ? 0.03 : 0.0);
}

size_t model_index(const scene::Network& network, size_t station) {
  const std::string& name = network.stations.at(station).model;
  for (size_t m = 0; m < network.models.size(); ++m) {
    if (network.models[m].name == name) return m;
  }
  throw CalibrationError("calibrate: station " + network.stations[station].name +
                         " has no camera model " + name);
}

scene::Network build_network(const Observations& observations, const Identification& identification,
                             const CalibrationOptions& options) {
  check_options(options);
  const WandSpec& wand = options.wand;
  scene::Network network;
  std::map<int, std::string> station_of;
  for (int id : observations.cameras()) {
    const auto size = observations.image_sizes.find(id);
    if (size == observations.image_sizes.end() || size->second.width <= 0) {
      throw CalibrationError("calibrate: camera " + std::to_string(id) + " of " +
                             observations.source + " has no image size");
    }
    const auto pixel = options.pixel_size_mm_by_camera.find(id);
    const double mu =
        pixel == options.pixel_size_mm_by_camera.end() ? options.pixel_size_mm : pixel->second;
    scene::CameraModel model;
    model.name = options.shared_interior ? "cameras" : camera_name(id);
    model.sensor = {size->second.width, size->second.height, mu, mu};
    model.interior = options.start_interiors.empty()
                         ? start_interior(model.sensor, options.field_of_view_deg)
                         : options.start_interiors.at(network.models.size());
    if (!options.shared_interior || network.models.empty()) {
      network.models.push_back(model);
    } else if (!same_sensor(network.models.front().sensor, model.sensor)) {
      throw CalibrationError("calibrate: camera " + std::to_string(id) + " of " +
                             observations.source +
                             " has another image or pixel size than the first camera; a shared "
                             "interior orientation needs identical cameras");
    }
    scene::Station station;
    station.name = camera_name(id);
    station.camera_id = id;
    station.model = model.name;
    network.stations.push_back(station);
    station_of[id] = station.name;
  }
  if (network.stations.size() < 2) {
    throw CalibrationError("calibrate: " + observations.source + " has " +
                           std::to_string(network.stations.size()) +
                           " camera(s); a calibration needs at least 2");
  }
  const std::vector<double> offsets = wand.offsets_mm();
  const int targets = wand.point_count();
  for (int64_t frame : split_frames(identification, options).adjusted) {
    const auto& cameras = identification.frames.at(frame);
    std::vector<bool> has_point(static_cast<size_t>(targets), false);
    for (int t = 0; t < targets; ++t) {
      int rays = 0;
      for (const auto& [camera, positions] : cameras) {
        if (static_cast<int>(positions.size()) > t && positions[static_cast<size_t>(t)]) ++rays;
      }
      if (rays < 2) continue;
      has_point[static_cast<size_t>(t)] = true;
      scene::ObjectPoint point;
      point.name = point_name(frame, t, wand.led);
      network.points.push_back(point);
      for (const auto& [camera, positions] : cameras) {
        if (static_cast<int>(positions.size()) <= t || !positions[static_cast<size_t>(t)]) continue;
        const Eigen::Vector2d& p = *positions[static_cast<size_t>(t)];
        network.measurements.push_back(
            {station_of.at(camera), point.name, p.x(), p.y(), options.sigma_px, frame});
      }
    }
    for (int t = 1; t < targets; ++t) {
      if (!has_point[static_cast<size_t>(t - 1)] || !has_point[static_cast<size_t>(t)]) continue;
      network.distances.push_back(
          {point_name(frame, t - 1, false), point_name(frame, t, false),
           offsets[static_cast<size_t>(t)] - offsets[static_cast<size_t>(t - 1)],
           options.wand_sigma_mm});
    }
  }
  // A camera with nothing to contribute is named here, with what its identification found.
  std::map<std::string, long> per_station;
  for (const auto& m : network.measurements) ++per_station[m.station];
  for (const auto& [id, name] : station_of) {
    if (per_station[name] > 0) continue;
    const auto stats = identification.cameras.find(id);
    std::string why = "it reported no frames";
    if (stats != identification.cameras.end()) {
      const auto& s = stats->second;
      why = "of its " + std::to_string(s.frames) + " frames " + std::to_string(s.identified) +
            " had the wand identified (" + std::to_string(s.missing) + " missing, " +
            std::to_string(s.ambiguous) + " ambiguous), none shared with another camera";
    }
    throw CalibrationError("calibrate: camera " + std::to_string(id) + " has no usable " +
                           (wand.led ? "point" : "wand targets") + ": " + why);
  }
  return network;
}

CalibrationResult calibrate(const Observations& observations, const CalibrationOptions& options) {
  check_options(options);
  CalibrationResult out;
  say(options, "observations: " + std::to_string(observations.frames.size()) + " frames, " +
                   std::to_string(observations.cameras().size()) + " cameras, " +
                   std::to_string(observations.spot_count()) + " spots");
  out.identification = identify_targets(observations, options.wand, options.identification);
  {
    std::istringstream lines(format_identification(out.identification));
    for (std::string line; std::getline(lines, line);) say(options, "identified " + line);
  }
  scene::Network network = build_network(observations, out.identification, options);
  const FrameSplit split = split_frames(out.identification, options);
  const std::vector<int64_t>& frames = split.adjusted;
  out.check_frames = split.held_out;
  say(options, "network: " + std::to_string(network.stations.size()) + " cameras, " +
                   std::to_string(network.points.size()) + " points, " +
                   std::to_string(network.measurements.size()) + " measurements, " +
                   std::to_string(network.distances.size()) + " distances");

  if (!options.start_fields_of_view_deg.empty() && options.start_interiors.empty()) {
    // Searched with the base model: the further groups trade off against c on a weak network.
    CalibrationOptions base = options;
    if (selects_model(options)) base.free_interior = base_model(requested_interior(options));
    choose_start(network, base, out);
  }
  const std::vector<scene::CameraModel> nominal = network.models;  // the bootstrap restarts there
  SecondStageStart second = second_stage_start(std::move(network), options);
  out.start = second.start;
  say(options, "start values: root " + second.start.root + ", " +
                   std::to_string(second.start.triangulated_points) + " points triangulated" +
                   (second.start.resected.empty()
                        ? std::string()
                        : ", " + std::to_string(second.start.resected.size()) + " resected"));
  say(options, "adjustment 1/2 (c, xp, yp, exterior): " + std::to_string(second.first.iterations) +
                   " iterations, sigma0 " + std::to_string(second.first.sigma0));
  network = std::move(second.network);
  const CalibrationOptions model_options = adjust_final(network, options, out);
  say(options, "adjustment 2/2 (all interior values, data snooping): " +
                   std::to_string(out.adjustment.adjustments) + " adjustments, " +
                   std::to_string(out.adjustment.rejected.size()) + " outliers removed, sigma0 " +
                   std::to_string(out.adjustment.sigma0));
  if (options.scale_from && out.adjustment.converged) {
    const double s = scale_for(out.adjustment, *options.scale_from);
    apply_scale(s, out.adjustment, network);
    say(options, util::printf_string("scale: x %.6g from cameras %d and %d, %.1f mm apart", s,
                                     options.scale_from->camera_a, options.scale_from->camera_b,
                                     options.scale_from->distance_mm));
  }
  out.network = std::move(network);

  out.cameras = cameras_of(out.network, out.adjustment);
  for (size_t m = 0; m < out.network.measurements.size(); ++m) {
    out.measurements_of_point[out.network.measurements[m].point].push_back(m);
  }
  fill_report(out, observations, options, frames);
  if (options.bootstrap_samples > 1 && out.adjustment.converged) {
    add_bootstrap(out, model_options, nominal);
  }
  out.quality = quality_of(out, options);
  check(out, observations, model_options, frames, nominal);
  say(options, std::string("verdict: ") + verdict_name(out.verdict));
  return out;
}

}  // namespace syncap::calibration
