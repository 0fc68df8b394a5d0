#include "syncap/cli/config_file.hpp"

#include <yaml-cpp/yaml.h>

#include <utility>
#include <vector>

#include "syncap/cli/options.hpp"

namespace syncap::cli {
namespace {

// "FILE:LINE:COLUMN" of a YAML node (yaml-cpp counts from 0).
std::string place(const std::string& file, const YAML::Mark& mark) {
  return file + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1);
}

std::optional<bool> truth(const std::string& text) {
  if (text == "true" || text == "yes" || text == "on") return true;
  if (text == "false" || text == "no" || text == "off") return false;
  return std::nullopt;
}

// The top-level keys whose value is a section of the rig file, not an option's value.
bool is_rig_section(const std::string& key) {
  return key == "host" || key == "edges" || key == "trigger" || key == "cameras";
}

class Reader {
 public:
  Reader(std::string program, std::string file, const AppFactory& make_app)
      : program_(std::move(program)),
        file_(std::move(file)),
        names_(make_app()),
        make_app_(make_app) {}

  // One `key: value`. `shared`: a rig file's top-level key, taken only where the program has
  // that option; otherwise the key must be one.
  void add(const YAML::Node& key, const YAML::Node& value, bool shared) {
    if (!key.IsScalar()) throw error(key, "a key must be text");
    const std::string given = key.Scalar();
    const std::string where = place(file_, key.Mark()) + ": key '" + given + "'";
    // An old name is taken as its new one (App::deprecated_name).
    const auto* ours = dynamic_cast<const App*>(names_.get());
    const std::string name = ours ? ours->current_name("--" + given).substr(2) : given;
    const CLI::Option* option = names_->get_option_no_throw("--" + name);
    if (option == nullptr || name == "help" || name == "config") {
      if (shared) return;
      throw ConfigError(program_ + ": " + where + ": " +
                        (name == "config"
                             ? "a config file cannot include another"
                             : "unknown key (keys are " + program_ + "'s long options)"));
    }
    if (!value.IsScalar()) throw ConfigError(program_ + ": " + where + ": expected a single value");
    std::vector<std::string> arg{"--" + name + "=" + value.Scalar()};
    if (option->get_expected_max() == 0) {  // a flag: true turns it on, false leaves it off
      const std::optional<bool> on = truth(value.Scalar());
      if (!on)
        throw ConfigError(program_ + ": " + where + " '" + value.Scalar() +
                          "': expected true or false");
      if (!*on) return;
      arg = {"--" + name};
    }
    check_alone(arg, name, where);
    arguments_.push_back(arg.front());
  }

  void add_map(const YAML::Node& map, bool shared, const char* what) {
    if (!map.IsMap()) throw error(map, std::string("expected `key: value` lines ") + what);
    for (const auto& entry : map) add(entry.first, entry.second, shared);
  }

  ConfigError error(const YAML::Node& node, const std::string& what) const {
    return ConfigError(program_ + ": " + place(file_, node.Mark()) + ": " + what);
  }

  // An argument the rig implies (not a key of the file).
  void add_argument(std::string argument) { arguments_.push_back(std::move(argument)); }

  std::vector<std::string> take() { return std::move(arguments_); }

 private:
  // The value converted and checked by the option itself, on a scratch parser: a required
  // option missing there is the rest of the command line's business.
  void check_alone(const std::vector<std::string>& arg, const std::string& name,
                   const std::string& where) {
    const std::unique_ptr<CLI::App> scratch = make_app_();
    std::vector<std::string> reversed(arg.rbegin(), arg.rend());
    try {
      scratch->parse(reversed);
    } catch (const CLI::RequiredError&) {
    } catch (const CLI::CallForHelp&) {
    } catch (const CLI::Error& e) {
      // CLI11 names the option ("--threshold: '300' is not ..."): the key says it here.
      std::string what = e.what();
      const std::string prefix = "--" + name + ": ";
      if (what.starts_with(prefix)) what = what.substr(prefix.size());
      throw ConfigError(program_ + ": " + where + ": " + what);
    }
  }

  std::string program_;
  std::string file_;
  std::unique_ptr<CLI::App> names_;
  const AppFactory& make_app_;
  std::vector<std::string> arguments_;
};

YAML::Node load(const std::string& program, const std::string& file) {
  try {
    return YAML::LoadFile(file);
  } catch (const YAML::BadFile&) {
    throw ConfigError(program + ": --config " + file + ": cannot be read");
  } catch (const YAML::ParserException& e) {
    throw ConfigError(program + ": " + place(file, e.mark) + ": " + e.msg);
  }
}

bool is_rig_file(const YAML::Node& root) {
  for (const auto& entry : root) {
    if (entry.first.IsScalar() && is_rig_section(entry.first.Scalar()) && !entry.second.IsScalar())
      return true;
  }
  return false;
}

// The rig's cameras with their ids, in the file's order, each checked once: a map with a
// `camera-id` 0..99. Empty when the rig lists none.
std::vector<std::pair<int, YAML::Node>> rig_cameras(const YAML::Node& cameras, Reader& reader) {
  std::vector<std::pair<int, YAML::Node>> out;
  if (!cameras) return out;
  if (!cameras.IsSequence()) throw reader.error(cameras, "cameras: expected a list of cameras");
  for (const YAML::Node& camera : cameras) {
    if (!camera.IsMap()) throw reader.error(camera, "a camera: expected `key: value` lines");
    const YAML::Node camera_id = camera["camera-id"];
    if (!camera_id) throw reader.error(camera, "a camera without its camera-id");
    const std::optional<long long> value =
        camera_id.IsScalar() ? whole_number(camera_id.Scalar(), 0, 99) : std::nullopt;
    if (!value) throw reader.error(camera_id, "camera-id: expected a camera id 0..99");
    out.emplace_back(static_cast<int>(*value), camera);
  }
  return out;
}

// The rig's camera ids, "0,1,2", as the value of the part's camera list option.
void add_camera_ids(const std::vector<std::pair<int, YAML::Node>>& cameras, const RigPart& part,
                    Reader& reader) {
  std::string ids;
  for (const auto& [id, camera] : cameras) ids += (ids.empty() ? "" : ",") + std::to_string(id);
  if (!ids.empty()) reader.add_argument(part.camera_ids_option + "=" + ids);
}

void read_rig(const YAML::Node& root, const RigPart& part, Reader& reader) {
  for (const auto& entry : root) {
    if (!entry.first.IsScalar() || !is_rig_section(entry.first.Scalar()))
      reader.add(entry.first, entry.second, /*shared=*/true);
  }
  const std::vector<std::pair<int, YAML::Node>> cameras = rig_cameras(root["cameras"], reader);
  if (!part.camera_ids_option.empty()) add_camera_ids(cameras, part, reader);
  if (const YAML::Node section = root[part.section]) reader.add_map(section, false, "");
  if (!part.camera_id) return;
  for (const auto& [id, camera] : cameras) {
    if (id != *part.camera_id) continue;
    for (const auto& entry : camera) {
      // Where the camera's edge runs: the deployment's, not an option of the edge.
      if (entry.first.IsScalar() && entry.first.Scalar() == "board") continue;
      reader.add(entry.first, entry.second, /*shared=*/false);
    }
  }
}

}  // namespace

std::optional<std::string> config_path(std::span<const std::string> args) {
  std::optional<std::string> path;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--config" && i + 1 < args.size())
      path = args[++i];
    else if (args[i].starts_with("--config="))
      path = args[i].substr(9);
  }
  return path;
}

std::vector<std::string> config_arguments(const std::string& program, const std::string& file,
                                          const RigPart& part, const AppFactory& make_app) {
  const YAML::Node root = load(program, file);
  Reader reader(program, file, make_app);
  if (root.IsNull()) return {};  // an empty file
  if (!root.IsMap())
    throw reader.error(root, "expected `key: value` lines (the long option names)");
  if (is_rig_file(root)) {
    read_rig(root, part, reader);
  } else {
    reader.add_map(root, false, "(the long option names)");
  }
  return reader.take();
}

std::vector<std::string> with_config(const std::string& program, std::span<const std::string> args,
                                     const RigPart& part, const AppFactory& make_app) {
  std::vector<std::string> all;
  if (const std::optional<std::string> file = config_path(args))
    all = config_arguments(program, *file, part, make_app);
  all.insert(all.end(), args.begin(), args.end());
  return all;
}

}  // namespace syncap::cli
