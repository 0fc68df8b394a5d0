#include "syncap/segmentation/mask_options.hpp"

#include "syncap/segmentation/masking_options.hpp"

namespace syncap::segmentation {

void add_mask_options(cli::App& app, MediPictureOptions& masking, const std::string& help_prefix) {
  for (const MaskingOptionHelp& m : kMaskingOptions) {
    const std::string option = std::string("--mask-") + m.name;
    const std::string name = m.name;
    app.add_option_function<std::string>(
           option,
           [&masking, option, name](const std::string& v) {
             try {
               apply_masking_option(masking, name, v);
             } catch (const BadValue& e) {
               throw CLI::ValidationError(option, e.what());
             }
           },
           help_prefix + m.meaning + " (default " + masking_option_value(masking, name) + ")")
        ->option_text(m.metavar);
    if (m.old_name != nullptr) app.deprecated_name(std::string("--mask-") + m.old_name, option);
  }
}

}  // namespace syncap::segmentation
