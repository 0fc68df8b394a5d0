#include "motion_files.hpp"

#include <algorithm>
#include <optional>

#include "fitting/motion_export.hpp"
#include "io/bvh_writer.hpp"
#include "io/c3d_writer.hpp"
#include "io/export_error.hpp"
#include "io/trc_writer.hpp"

namespace syncap::tools {

std::vector<std::string> export_motion(const fitting::PoseParameters& parameters,
                                       const outputs::PoseRecord& record,
                                       const std::filesystem::path& dir, const char* name,
                                       std::ostream& err, bool& failed) {
  const auto& poses = record.poses;
  const auto has_pose = [](const auto& entry) { return entry.second.has_value(); };
  if (std::none_of(poses.begin(), poses.end(), has_pose)) {
    err << name << ": no frame has a fitted body: no BVH, C3D or TRC written\n";
    return {};
  }
  const int64_t first = poses.begin()->first, last = poses.rbegin()->first;
  std::vector<std::optional<fitting::PoseVector>> frames(
      static_cast<std::size_t>(last - first + 1));
  for (const auto& [frame, pose] : poses) frames[static_cast<std::size_t>(frame - first)] = pose;
  const double rate = record.rate_hz > 0 ? record.rate_hz : 30.0;
  std::vector<std::string> written;
  try {
    io::write_bvh((dir / "body.bvh").string(), fitting::bvh_motion(parameters, frames, rate));
    written.push_back("body.bvh");
    const tracking::MarkerTrajectories joints =
        fitting::joint_trajectories(parameters, frames, rate, first);
    io::write_c3d((dir / "joints.c3d").string(), joints);
    written.push_back("joints.c3d");
    io::write_trc((dir / "joints.trc").string(), joints);
    written.push_back("joints.trc");
  } catch (const io::ExportError& e) {
    err << name << ": " << e.what() << '\n';
    failed = true;
  }
  return written;
}

std::string written_list(const std::vector<std::string>& written) {
  std::string text;
  for (std::size_t i = 0; i < written.size(); ++i)
    text += (i == 0 ? " (and " : ", ") + written[i] + (i + 1 == written.size() ? ")" : "");
  return text;
}

}  // namespace syncap::tools
