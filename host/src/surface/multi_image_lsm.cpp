#include "surface/multi_image_lsm.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace syncap::surface {
namespace {

// Unknowns shared by every search image: t and the depth's second order over the window,
// d t(k) = 1/2 k^T K k with K = [[kuu, kuv], [kuv, kvv]] in mm per square pixel of the
// reference. Then per search image: a00 a01 a10 a11 r0 r1.
constexpr int kShared = 4;
constexpr int kPerView = 6;
constexpr int kRow = kShared + kPerView;

struct SearchState {
  Eigen::Matrix2d affine;
  double r0 = 0.0, r1 = 1.0;
};

struct SharedState {
  double t = 0.0;
  Eigen::Vector3d curvature = Eigen::Vector3d::Zero();  // kuu, kuv, kvv
  double depth_offset(const Eigen::Vector2d& k) const {
    return 0.5 * curvature(0) * k.x() * k.x() + curvature(1) * k.x() * k.y() +
           0.5 * curvature(2) * k.y() * k.y();
  }
};

// One Gauss-Newton step's normal equations at the current unknowns; false when a window left
// its image.
struct Linearisation {
  Eigen::MatrixXd normal;
  Eigen::VectorXd rhs;  // J^T f
  double squared_sum = 0.0;
  std::vector<double> view_squared;
  double fastest_px_per_mm = 0.0;
  int observations = 0;  // the samples on the search images' object
  // Each search image's residual per window pixel (NaN where left out), image after image.
  std::vector<double> residuals;
};

bool window_inside(const MatchImage& image, const Eigen::Vector2d& centre, double reach) {
  return image.inside(centre.x() - reach, centre.y() - reach) &&
         image.inside(centre.x() + reach, centre.y() + reach);
}

bool linearise(const ScanWindow& window, const std::vector<const MatchingView*>& search,
               const SharedState& shared, const std::vector<SearchState>& states, bool curvature,
               Linearisation& out) {
  const int m = static_cast<int>(search.size());
  const int unknowns = kShared + kPerView * m;
  out.normal.setZero(unknowns, unknowns);
  out.rhs.setZero(unknowns);
  out.squared_sum = 0.0;
  out.view_squared.assign(search.size(), 0.0);
  out.fastest_px_per_mm = 0.0;
  out.observations = 0;
  out.residuals.assign(window.offsets.size() * search.size(), std::nan(""));
  const double largest_offset = 0.5 * shared.curvature.cwiseAbs().sum() * window.half * window.half;
  Eigen::Matrix<double, kRow, 1> row;
  for (int j = 0; j < m; ++j) {
    const auto warp = warp_window(window, *search[j], shared.t);
    if (!warp) return false;
    const SearchState& s = states[j];
    const MatchImage& image = search[j]->image;
    const double reach = window.half * s.affine.cwiseAbs().rowwise().sum().maxCoeff() +
                         largest_offset * warp->per_mm.norm();
    if (!window_inside(image, warp->centre, reach)) return false;
    out.fastest_px_per_mm = std::max(out.fastest_px_per_mm, warp->per_mm.norm());
    // The view's block: t and the curvature, then its own six unknowns.
    Eigen::Matrix<double, kRow, kRow> block = Eigen::Matrix<double, kRow, kRow>::Zero();
    Eigen::Matrix<double, kRow, 1> block_rhs = Eigen::Matrix<double, kRow, 1>::Zero();
    int used = 0;
    for (std::size_t k = 0; k < window.offsets.size(); ++k) {
      const Eigen::Vector2d& o = window.offsets[k];
      // A window pixel deeper along its ray by d t(k) moves along the epipolar direction.
      const Eigen::Vector2d q = warp->centre + s.affine * o + shared.depth_offset(o) * warp->per_mm;
      if (!on_object(*search[j], q)) continue;  // the search view's outline: left out
      ++used;
      const GreySample g = image.sample(q.x(), q.y());
      const double f = s.r0 + s.r1 * g.value - window.grey[k];
      // The observation's weight: both pixels' distance from their outline.
      const double weight = window.weight[k] * weight_at(*search[j], q);
      out.residuals[j * window.offsets.size() + k] = std::sqrt(weight) * f;
      const double gx = s.r1 * g.dx, gy = s.r1 * g.dy;
      const double along = gx * warp->per_mm.x() + gy * warp->per_mm.y();
      row << along, 0.5 * along * o.x() * o.x(), along * o.x() * o.y(), 0.5 * along * o.y() * o.y(),
          gx * o.x(), gx * o.y(), gy * o.x(), gy * o.y(), 1.0, g.value;
      if (!curvature) row.segment<3>(1).setZero();
      block.noalias() += weight * row * row.transpose();
      block_rhs.noalias() += weight * row * f;
      out.view_squared[j] += weight * f * f;
    }
    if (static_cast<double>(used) < kMinShareOnObject * static_cast<double>(window.offsets.size()))
      return false;
    out.observations += used;
    out.squared_sum += out.view_squared[j];
    const int at = kShared + kPerView * j;
    out.normal.topLeftCorner<kShared, kShared>() += block.topLeftCorner<kShared, kShared>();
    out.normal.block(0, at, kShared, kPerView) += block.topRightCorner<kShared, kPerView>();
    out.normal.block(at, 0, kPerView, kShared) += block.bottomLeftCorner<kPerView, kShared>();
    out.normal.block(at, at, kPerView, kPerView) += block.bottomRightCorner<kPerView, kPerView>();
    out.rhs.head<kShared>() += block_rhs.head<kShared>();
    out.rhs.segment(at, kPerView) += block_rhs.tail<kPerView>();
  }
  // Without the curvature, its unknowns are held at zero: unit rows keep the system regular.
  if (!curvature) out.normal.block<3, 3>(1, 1) += Eigen::Matrix3d::Identity();
  return true;
}

// The radiometric start: the search window's mean and spread matched to the template's.
bool start_state(const ScanWindow& window, const MatchingView& search, double t,
                 SearchState& state) {
  const auto warp = warp_window(window, search, t);
  if (!warp) return false;
  state.affine = warp->affine;
  const double reach = window.half * state.affine.cwiseAbs().rowwise().sum().maxCoeff();
  if (!window_inside(search.image, warp->centre, reach)) return false;
  double sw = 0, sww = 0, sg = 0;
  for (std::size_t k = 0; k < window.offsets.size(); ++k) {
    const Eigen::Vector2d q = warp->centre + state.affine * window.offsets[k];
    const double w = search.image.value(q.x(), q.y());
    sw += w, sww += w * w, sg += window.grey[k];
  }
  const double n = static_cast<double>(window.offsets.size());
  const double sd_w = std::sqrt(std::max(0.0, sww / n - (sw / n) * (sw / n)));
  if (sd_w <= 1e-6) return false;
  state.r1 = window.grey_sd / sd_w;
  state.r0 = sg / n - state.r1 * sw / n;
  return true;
}

void apply_step(const Eigen::VectorXd& step, SharedState& shared,
                std::vector<SearchState>& states) {
  shared.t += step(0);
  shared.curvature += step.segment<3>(1);
  for (std::size_t j = 0; j < states.size(); ++j) {
    const auto s = step.segment(kShared + kPerView * static_cast<int>(j), kPerView);
    states[j].affine += Eigen::Map<const Eigen::Matrix<double, 2, 2, Eigen::RowMajor>>(s.data());
    states[j].r0 += s(4);
    states[j].r1 += s(5);
  }
}

// Converged when the step moves the windows by less than the tolerance, or when every unknown
// moved by less than a tenth of its own standard deviation (a window's shape on a weak pattern
// wanders within its noise for many steps while the cost no longer changes).
bool converged(const Eigen::VectorXd& step, const Linearisation& lin, int redundancy, int half,
               const LsmOptions& options) {
  double largest_affine = 0.0;
  for (Eigen::Index at = kShared; at < step.size(); at += kPerView)
    largest_affine = std::max(largest_affine, step.segment<4>(at).cwiseAbs().maxCoeff());
  if (std::abs(step(0)) * lin.fastest_px_per_mm < options.tolerance_px &&
      largest_affine * half < options.tolerance_px)
    return true;
  const double sigma0 = std::sqrt(lin.squared_sum / redundancy);
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(lin.normal);
  const Eigen::VectorXd sigmas =
      sigma0 * ldlt.solve(Eigen::MatrixXd::Identity(step.size(), step.size()))
                   .diagonal()
                   .cwiseMax(0.0)
                   .cwiseSqrt();
  return (step.cwiseAbs().array() <= options.settled_sigmas * sigmas.array()).all();
}

// How much the residuals' correlation between neighbouring pixels inflates the variances: the
// bilinear interpolation and a pattern smooth at the pixel make neighbours' residuals alike,
// so the window holds fewer independent observations than pixels. For a first-order
// autoregressive process along rows and columns with lag-one correlations rho_u, rho_v, the
// variance of a mean grows by (1 + rho) / (1 - rho) in each direction.
double correlation_inflation(const ScanWindow& window, const std::vector<double>& residuals) {
  const int side = 2 * window.half + 1;
  std::vector<int> at(static_cast<std::size_t>(side * side), -1);  // grid cell -> offset index
  for (std::size_t k = 0; k < window.offsets.size(); ++k) {
    const auto& o = window.offsets[k];
    at[static_cast<std::size_t>((o.y() + window.half) * side + o.x() + window.half)] =
        static_cast<int>(k);
  }
  const std::size_t n = window.offsets.size();
  double squares = 0, along_u = 0, along_v = 0;
  for (std::size_t base = 0; base < residuals.size(); base += n) {
    auto value = [&](int x, int y) {
      if (x >= side || y >= side) return std::nan("");
      const int k = at[static_cast<std::size_t>(y * side + x)];
      return k < 0 ? std::nan("") : residuals[base + static_cast<std::size_t>(k)];
    };
    for (int y = 0; y < side; ++y) {
      for (int x = 0; x < side; ++x) {
        const double f = value(x, y);
        if (std::isnan(f)) continue;
        squares += f * f;
        if (const double r = value(x + 1, y); !std::isnan(r)) along_u += f * r;
        if (const double d = value(x, y + 1); !std::isnan(d)) along_v += f * d;
      }
    }
  }
  if (squares <= 0) return 1.0;
  const double rho_u = std::clamp(along_u / squares, 0.0, 0.9);
  const double rho_v = std::clamp(along_v / squares, 0.0, 0.9);
  return (1 + rho_u) / (1 - rho_u) * (1 + rho_v) / (1 - rho_v);
}

}  // namespace

LsmSolution solve_multi_image_lsm(const ScanWindow& window,
                                  const std::vector<const MatchingView*>& search, double t,
                                  const LsmOptions& options) {
  LsmSolution out;
  out.t = t;
  const int m = static_cast<int>(search.size());
  if (m == 0) return out;
  std::vector<SearchState> states(search.size());
  for (int j = 0; j < m; ++j) {
    if (!start_state(window, *search[j], t, states[j])) return out;
  }
  SharedState shared{t, Eigen::Vector3d::Zero()};
  const int unknowns = kShared + kPerView * m;
  const int free_unknowns = unknowns - (options.curvature ? 0 : 3);
  Linearisation lin, next;
  if (!linearise(window, search, shared, states, options.curvature, lin)) return out;
  // Gauss-Newton with Levenberg-Marquardt damping: a step that raises the mean squared
  // residual is taken back and tried shorter. Where no step lowers it any more, the solution
  // is at its minimum (within the interpolation's noise).
  double lambda = 0.0;
  for (out.iterations = 1; out.iterations <= options.max_iterations; ++out.iterations) {
    out.redundancy = lin.observations - free_unknowns;
    if (out.redundancy <= 0) return out;
    Eigen::MatrixXd damped = lin.normal;
    damped.diagonal() *= 1.0 + lambda;
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(damped);
    if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return out;
    const Eigen::VectorXd step = -ldlt.solve(lin.rhs);
    if (!step.allFinite()) return out;
    SharedState tried = shared;
    std::vector<SearchState> tried_states = states;
    apply_step(step, tried, tried_states);
    const bool better = linearise(window, search, tried, tried_states, options.curvature, next) &&
                        next.squared_sum / next.observations <= lin.squared_sum / lin.observations;
    if (!better) {
      lambda = std::max(1e-3, 10.0 * lambda);
      if (lambda > 1e4) {  // no step lowers the residuals: the minimum
        out.converged = true;
        break;
      }
      continue;
    }
    shared = tried;
    states = std::move(tried_states);
    std::swap(lin, next);
    lambda = lambda > 1e-6 ? lambda / 10.0 : 0.0;
    if (std::abs(shared.t - t) * lin.fastest_px_per_mm > options.max_travel_px) return out;
    if (converged(step, lin, out.redundancy, window.half, options)) {
      out.converged = true;
      break;
    }
  }
  if (!out.converged) return out;
  // The statistics at the solution: residuals and cofactors of the final linearisation.
  out.t = shared.t;
  out.redundancy = lin.observations - free_unknowns;
  if (out.redundancy <= 0) {
    out.converged = false;
    return out;
  }
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(lin.normal);
  const Eigen::VectorXd first = ldlt.solve(Eigen::VectorXd::Unit(unknowns, 0));
  out.sigma0 = std::sqrt(lin.squared_sum / out.redundancy);
  out.inflation = options.correlated_residuals ? correlation_inflation(window, lin.residuals) : 1.0;
  out.sigma_t = out.sigma0 * std::sqrt(std::max(0.0, first(0)) * out.inflation);
  out.curvature = shared.curvature;
  return out;
}

}  // namespace syncap::surface
