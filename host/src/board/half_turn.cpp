#include "board/half_turn.hpp"

#include <algorithm>
#include <array>

#include "hull/polyhedral_hull.hpp"
#include "hull/reprojection.hpp"
#include "hull/silhouette.hpp"
#include "util/printf_string.hpp"

namespace syncap::board {
namespace {

struct Score {
  double mean_iou = -1.0;  // -1: no hull (an empty intersection or one that failed)
  std::vector<double> ious;
};

hull::HullView view_of(const BoardPose& pose, const cv::Mat& mask) {
  hull::HullView v;
  v.camera = pose.camera;
  v.name = util::printf_string("camera %d", v.camera.id);
  v.mask = mask;
  v.silhouette = hull::silhouette_from_mask(mask);
  return v;
}

Score score(const std::vector<std::array<BoardPose, 2>>& poses, const std::vector<cv::Mat>& masks,
            const std::vector<bool>& reversed) {
  std::vector<hull::HullView> views;
  for (std::size_t i = 0; i < poses.size(); ++i)
    views.push_back(view_of(poses[i][reversed[i] ? 1 : 0], masks[i]));
  Score s;
  try {
    const hull::Mesh mesh = hull::polyhedral_visual_hull(views);
    s.mean_iou = 0.0;
    for (const hull::HullView& v : views) {
      s.ious.push_back(hull::mask_iou(hull::render_mask(mesh, v.camera), v.mask));
      s.mean_iou += s.ious.back() / static_cast<double>(views.size());
    }
  } catch (const hull::HullError&) {  // empty, or cut by the working ball: this order is wrong
  }
  return s;
}

// Camera k's two turns against the hull of the others (which does not depend on k's turn): the
// share of its projection inside k's mask with k's chosen turn and with the other. Needs two
// others.
std::array<double, 2> leave_one_out(const std::vector<std::array<BoardPose, 2>>& poses,
                                    const std::vector<cv::Mat>& masks,
                                    const std::vector<bool>& reversed, std::size_t k) {
  std::vector<hull::HullView> others;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (i != k) others.push_back(view_of(poses[i][reversed[i] ? 1 : 0], masks[i]));
  }
  try {
    const hull::Mesh mesh = hull::polyhedral_visual_hull(others);
    // The share of the others' hull's projection inside k's mask: a mask that calls too much
    // foreground (shadows, moved furniture) lowers neither turn's share, unlike an IoU.
    const auto inside = [&](bool turned) {
      const cv::Mat drawn = hull::render_mask(mesh, poses[k][turned ? 1 : 0].camera);
      const double area = cv::countNonZero(drawn);
      return area > 0 ? cv::countNonZero(drawn & masks[k]) / area : 0.0;
    };
    return {inside(reversed[k]), inside(!reversed[k])};
  } catch (const hull::HullError&) {
    return {0.0, 0.0};
  }
}

}  // namespace

HalfTurn resolve_half_turn(const std::vector<std::array<BoardPose, 2>>& poses,
                           const std::vector<cv::Mat>& masks) {
  HalfTurn h;
  h.reversed.assign(poses.size(), false);
  Score best;
  // Every combination of the first kExhaustiveCameras cameras' turns (camera 0's fixed): one
  // camera turned alone against the others is no guide (on a real studio the right answer turned
  // three of four, and each single turn from the start scored worse).
  const std::size_t exhaustive = std::min(poses.size(), kExhaustiveCameras);
  for (unsigned bits = 0; bits < (1u << (exhaustive - 1)); ++bits) {
    std::vector<bool> trial(poses.size(), false);
    for (std::size_t i = 1; i < exhaustive; ++i) trial[i] = (bits >> (i - 1)) & 1u;
    const Score s = score(poses, masks, trial);
    ++h.hulls_built;
    if (s.mean_iou > best.mean_iou) {
      h.runner_up_iou = best.mean_iou;
      best = s;
      h.reversed = trial;
    } else {
      h.runner_up_iou = std::max(h.runner_up_iou, s.mean_iou);
    }
  }
  // The cameras after those, one at a time against the hull of the chosen ones.
  for (std::size_t i = exhaustive; i < poses.size(); ++i) {
    std::vector<bool> trial = h.reversed;
    trial[i] = true;
    const Score s = score(poses, masks, trial);
    ++h.hulls_built;
    if (s.mean_iou > best.mean_iou) {
      best = s;
      h.reversed = trial;
    }
  }
  if (best.mean_iou < 0.0) {
    throw hull::HullError(
        "the board's half turn: no order of the cameras' corners gives a hull of the masks (do "
        "they show one person at the same instant?)");
  }
  h.mean_iou = best.mean_iou;
  h.view_ious = best.ious;
  // Each camera checked alone against the others' hull: turned where the other turn fits it
  // better, then the margin by which the chosen one wins.
  if (poses.size() >= 3) {
    h.margin = 1.0;
    for (std::size_t k = 1; k < poses.size(); ++k) {
      std::array<double, 2> fit = leave_one_out(poses, masks, h.reversed, k);
      if (fit[1] > fit[0]) {
        h.reversed[k] = !h.reversed[k];
        std::swap(fit[0], fit[1]);
      }
      h.camera_margins.push_back(fit[0] - fit[1]);
      h.margin = std::min(h.margin, fit[0] - fit[1]);
    }
  }
  return h;
}

}  // namespace syncap::board
