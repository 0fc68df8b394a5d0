// The medi-picture options as syncap-edge takes them, `--mask-NAME VALUE` for every option of
// kMaskingOptions (their old names with a notice), shared by the programs that mask as the edge
// does (syncap-edge, syncap-mask).
#pragma once

#include <string>

#include "syncap/cli/options.hpp"
#include "syncap/segmentation/medi_picture.hpp"

namespace syncap::segmentation {

// Adds the options to `app`, each applied to `masking` as it is parsed and checked by
// apply_masking_option (a bad value is a CLI::ValidationError naming the option). The help
// shows `help_prefix`, the meaning and the default `masking` has now.
void add_mask_options(cli::App& app, MediPictureOptions& masking, const std::string& help_prefix);

}  // namespace syncap::segmentation
