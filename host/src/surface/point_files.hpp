// Matched surface points as files: the CSV that syncap-hil-surface-check and people read (one
// row a point, with its sigma, its reference ray and its cameras) and an ASCII PLY for viewers.
// `syncap match` and the host's live surface stage write the same files.
#pragma once

#include <filesystem>
#include <vector>

#include "surface/scan_line.hpp"
#include "surface/surface_matcher.hpp"

namespace syncap::surface {

// The camera id of each view, by view index (MatchedPoint::reference and ::search index them).
std::vector<int> camera_ids(const std::vector<MatchingView>& views);

// Columns x,y,z,sigma_ray_mm,sigma_normal_mm,sncc,sigma0,iterations,reference_camera,u,v,
// origin_x..z,dir_x..z,nx..nz,sweep_t_mm,search_cameras (space-separated ids). Throws
// std::runtime_error naming the file when it cannot be written.
void write_points_csv(const std::filesystem::path& file, const std::vector<MatchedPoint>& points,
                      const std::vector<int>& camera_ids);

// Vertices with their normal (the hull's) and sigma (along the normal, mm).
void write_points_ply(const std::filesystem::path& file, const std::vector<MatchedPoint>& points);

}  // namespace syncap::surface
