// What every marker export accepts (io/c3d_writer.hpp, io/trc_writer.hpp): the checks shared by
// the C3D and TRC writers, so that both refuse the same input with the same words.
#pragma once

#include <cstddef>
#include <string>

#include "tracking/marker_trajectories.hpp"

namespace syncap::io {

// Longest label the exports accept: keeps each C3D label parameter (255 labels) under the signed
// 16-bit offset that C3D readers follow to the next parameter.
inline constexpr std::size_t kMaxLabelLength = 127;

// Throws ExportError naming `path` when the trajectories cannot be exported as they are: no frame
// or no marker, rate not positive, a row not one sample per label, a present sample with a
// non-finite coordinate or a residual that is negative or not finite, a label that is empty,
// repeated, longer than kMaxLabelLength, or holds a character other than printable ASCII, or
// starts or ends with a space (C3D drops trailing spaces).
void check_exportable(const tracking::MarkerTrajectories& trajectories, const std::string& path);

}  // namespace syncap::io
