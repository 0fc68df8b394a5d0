// syncap-hil-surface-check: `syncap match`'s points of one rendered frame against the true body
// (hil/compare/README.md).
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "surface_check.hpp"
#include "surface_limits.hpp"
#include "syncap/cli/options.hpp"
#include "true_body.hpp"

namespace {

struct Options {
  std::string points, truth, json, errors;
  long frame = -1;
  double blunder_mm = 5.0;
  syncap::compare::SurfaceLimits limits;
};

void add_limit_options(CLI::App& app, syncap::compare::SurfaceLimits& l) {
  using syncap::cli::number_in;
  app.add_option("--max-rms-mm", l.max_rms_mm, "pass: RMS on the true normal at most MM")
      ->check(number_in(0, 1e6))
      ->option_text("MM");
  app.add_option("--min-points", l.min_points, "pass: at least N points")->option_text("N");
  app.add_option("--max-blunder-fraction", l.max_blunder_fraction,
                 "pass: blunders at most this share of the points (0.01 = 1 %)")
      ->check(number_in(0, 1))
      ->option_text("F");
  app.add_option("--max-rms-error-over-sigma", l.max_rms_error_over_sigma,
                 "pass: RMS of error/sigma at most R (the sigmas near honest)")
      ->check(number_in(0, 1e6))
      ->option_text("R");
  app.add_option("--min-within-3-sigma", l.min_within_3_sigma,
                 "pass: at least this share of the points within 3 sigma (0.9 = 90 %)")
      ->check(number_in(0, 1))
      ->option_text("F");
  app.add_option("--min-gain-over-gc3", l.min_gain_over_gc3,
                 "pass: least squares at least X times more precise than the GC3 peaks")
      ->check(number_in(0, 1e6))
      ->option_text("X");
}

}  // namespace

int main(int argc, char** argv) {
  using namespace syncap;
  Options o;
  cli::App app("syncap-hil-surface-check",
               "usage: syncap-hil-surface-check --points points.csv --truth DIR --frame N\n"
               "The surface points of `syncap match` on one frame of a syncap-sim render against\n"
               "the true body (DIR/truth/body.jsonl): each point's error along its ray from the\n"
               "ray's first true hit, on the true normal, and over its sigma.\n",
               "With a --max-*/--min-* limit it ends with PASS or FAIL: the limits missed. Exit "
               "status: 0 done (and passed), 1 a limit missed, 2 usage error or unreadable "
               "input (named).");
  app.add_option("--points", o.points, "syncap match's points.csv")->required();
  app.add_option("--truth", o.truth, "the render folder (DIR/truth/body.jsonl)")->required();
  app.add_option("--frame", o.frame, "the frame the points were matched on")->required();
  app.add_option("--blunder-mm", o.blunder_mm,
                 "a blunder: |error on the normal| > max(5 sigma, this) (default 5)");
  app.add_option("--json", o.json, "also write the figures as JSON")->option_text("FILE");
  app.add_option("--errors", o.errors,
                 "write each point's errors (CSV, in points.csv's order: along the ray, on the "
                 "normal, sigma on the normal, the GC3 peak's on the normal)")
      ->option_text("FILE");
  add_limit_options(app, o.limits);
  if (const auto status = cli::parse_main(app, argc, argv)) return *status;
  try {
    const auto bodies =
        compare::read_true_bodies(std::filesystem::path(o.truth) / "truth" / "body.jsonl");
    const auto body = bodies.find(o.frame);
    if (body == bodies.end() || body->second.ellipsoids.empty()) {
      std::fprintf(stderr, "syncap-hil-surface-check: %s: no body for frame %ld\n", o.truth.c_str(),
                   o.frame);
      return 2;
    }
    const auto points = compare::read_surface_points(o.points);
    std::vector<compare::PointError> each;
    const compare::SurfaceErrors e =
        compare::check_surface(points, body->second, o.blunder_mm, &each);
    if (!o.errors.empty()) {
      std::ofstream out(o.errors);
      out << "error_ray_mm,error_normal_mm,sigma_normal_mm,sweep_error_normal_mm\n";
      for (const auto& p : each)
        out << p.ray_mm << ',' << p.normal_mm << ',' << p.sigma_normal_mm << ','
            << p.sweep_normal_mm << '\n';
    }
    std::printf(
        "frame %ld: %zu points, %zu off the body, %zu blunders (%.2f %%); without them: RMS on "
        "the normal %.3f mm, RMS error/sigma %.2f; within 3 sigma %.1f %%; median sigma %.3f "
        "mm; the GC3 peaks' RMS %.3f mm\n",
        o.frame, e.points, e.off_body, e.blunders, e.points ? 100.0 * e.blunders / e.points : 0.0,
        e.rms_normal_mm, e.rms_normalised, 100.0 * e.within_3_sigma, e.median_sigma_normal_mm,
        e.sweep_rms_normal_mm);
    const auto& q = e.rms_normalised_by_sigma;
    std::printf(
        "frame %ld: RMS error/sigma by quarter of the sigmas, smallest first: %.2f %.2f %.2f "
        "%.2f\n",
        o.frame, q[0], q[1], q[2], q[3]);
    if (!o.json.empty()) {
      const nlohmann::json j{{"frame", o.frame},
                             {"points", e.points},
                             {"off_body", e.off_body},
                             {"blunders", e.blunders},
                             {"rms_normal_mm", e.rms_normal_mm},
                             {"rms_normalised", e.rms_normalised},
                             {"within_3_sigma", e.within_3_sigma},
                             {"median_sigma_normal_mm", e.median_sigma_normal_mm},
                             {"sweep_rms_normal_mm", e.sweep_rms_normal_mm},
                             {"rms_normalised_by_sigma", e.rms_normalised_by_sigma}};
      std::ofstream(o.json) << j.dump() << '\n';
    }
    if (!o.limits.any()) return 0;
    std::printf("frame %ld: least squares %.3f mm, their GC3 peaks %.3f mm: %.1fx\n", o.frame,
                e.rms_normal_mm, e.sweep_rms_normal_mm,
                e.rms_normal_mm > 0 ? e.sweep_rms_normal_mm / e.rms_normal_mm : 0.0);
    const std::vector<std::string> failed = compare::surface_failures(e, o.limits);
    std::string verdict = failed.empty() ? "PASS" : "FAIL: ";
    for (std::size_t i = 0; i < failed.size(); ++i) verdict += (i ? "; " : "") + failed[i];
    std::printf("frame %ld: %s\n", o.frame, verdict.c_str());
    return failed.empty() ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "syncap-hil-surface-check: %s\n", e.what());
    return 2;
  }
}
