// Options from a YAML file, as every program takes them with --config FILE (docs/reference/
// cli.md, "Config files and the rig file"): each key is a long option's name without the dashes
// and its value the option's, and the command line overrides the file.
//
// A file is either a program's own (flat `key: value` lines), or the rig file that describes a
// whole installation (docs/guide/rig.md): top-level `key: value` lines every program takes where
// it has that option (the calibration, the command key), a section per program (`trigger:`,
// `edges:`, `host:`) and the cameras (`cameras:`, one entry per camera with its `camera-id`, the
// `board` it runs on, and its edge's options).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace syncap::cli {

// A config file that cannot be used: what() names the program, FILE:LINE:COLUMN and the key.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What a program takes from a rig file: its section, and for an edge its camera's entry.
struct RigPart {
  RigPart(std::string section_name, std::optional<int> camera = std::nullopt,
          std::string camera_ids = {})
      : section(std::move(section_name)),
        camera_id(camera),
        camera_ids_option(std::move(camera_ids)) {}
  std::string section;           // "host", "edges", "trigger"
  std::optional<int> camera_id;  // the `cameras` entry with this camera-id (an edge's)
  // The option that takes the list of camera ids ("--camera-ids" for the host): given the ids of
  // the rig's cameras before the section's keys (which may override it). Empty: none.
  std::string camera_ids_option;
};

// A fresh parser with the program's options, bound to scratch variables: each entry of the file
// is checked on one (its value converted and validated alone) so that a bad value is named with
// its file, line and key.
using AppFactory = std::function<std::unique_ptr<CLI::App>()>;

// The FILE of the last `--config FILE` / `--config=FILE` in `args`; nothing without.
std::optional<std::string> config_path(std::span<const std::string> args);

// The file's entries as command-line arguments (`--key=value`, or `--key` for a flag that is
// true), to be parsed before the command line. Throws ConfigError naming FILE:LINE:COLUMN and
// the key for a file that cannot be read or parsed, a key that is not an option (in a flat file
// or the program's section), a value that is not a single one, or a value the option refuses.
std::vector<std::string> config_arguments(const std::string& program, const std::string& file,
                                          const RigPart& part, const AppFactory& make_app);

// The whole rule: the arguments of --config's file (when given) and then `args`, so that the
// command line overrides the file. Throws ConfigError as config_arguments does.
std::vector<std::string> with_config(const std::string& program, std::span<const std::string> args,
                                     const RigPart& part, const AppFactory& make_app);

}  // namespace syncap::cli
