#include "sdl/parser.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <sstream>
#include <system_error>
#include <tuple>
#include <utility>
#include <vector>

#include "sdl/grammar.hpp"
#include "sdl/lexer.hpp"
#include "sdl/sdl.hpp"

namespace syncap::sdl::detail {
namespace {

using scene::ParameterMode;
using scene::ParameterPrior;

constexpr size_t kMaxIncludeDepth = 64;
// Includes read in all, over the whole scene. Files that each include the next twice fan out:
// 40 levels are 2^40 reads, a hang (issue 15); a real scene reads a few dozen.
constexpr size_t kMaxIncludes = 1000;
constexpr int kMaxExpressionDepth = 200;
constexpr int64_t kMaxExactInteger = int64_t{1} << 53;  // doubles hold every integer up to here

std::string in_quotes(const std::string& name) { return "\"" + name + "\""; }

std::string at_text(const Position& p) {
  return *p.file + ":" + std::to_string(p.line) + ":" + std::to_string(p.column);
}

std::string number_text(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

// Where a name was defined or referenced, for the checks after the whole scene is read.
struct NameUse {
  std::string name;
  Position position;
};

struct MeasurementUse {
  NameUse station;
  NameUse point;
  bool has_coordinates = true;
};

class Parser {
 public:
  explicit Parser(const FileReader& reader) : reader_(reader) {}

  scene::Network parse(std::string text, const std::filesystem::path& path,
                       const std::string& identity);

 private:
  struct Source {
    Lexer lexer;
    std::filesystem::path path;
    std::string identity;
  };

  // Tokens, with includes spliced in.
  void advance();
  void include(const Token& keyword);
  bool at_boundary(char symbol);
  bool at_symbol(char symbol) const;
  bool at_word(std::string_view word) const;
  [[noreturn]] void fail(const Position& at, const std::string& message) const;
  [[noreturn]] void fail_expected(const std::string& what) const;
  void expect_symbol(char symbol, const std::string& context);
  std::string expect_identifier(const std::string& what);
  NameUse expect_string(const std::string& what);
  template <typename ItemFunction>
  void block(const std::string& what, ItemFunction item);

  // Expressions.
  double expression();
  double term();
  double factor();
  double finite(double value, const Position& at) const;
  int64_t integer(const std::string& what, int64_t lowest, int64_t highest);
  bool boolean(const std::string& what);

  // Statements.
  void statement();
  void declaration();
  void design();
  void design_tag();
  const DesignTag& match_design_tag(std::string& words);
  void apply_design_tag(const DesignTag& tag, bool negated, const Position& at,
                        const std::string& words);
  void camera_model();
  void sensor(scene::CameraModel& model);
  void station();
  void point();
  void measurements();
  void constraints();
  void residual_test();
  bool parameter(double& value, ParameterPrior& prior, const std::string& owner);
  bool at_prior() const;
  ParameterPrior prior();
  void define(std::map<std::string, Position>& defined, const NameUse& name, const char* what);

  // After the whole scene.
  void check_references() const;

  const FileReader& reader_;
  std::vector<Source> sources_;
  size_t includes_ = 0;                           // read so far
  std::map<std::string, size_t> times_included_;  // by identity
  Token current_;
  int depth_ = 0;
  scene::Network network_;
  std::map<std::string, double> constants_{{"pi", std::numbers::pi},
                                           {"deg", std::numbers::pi / 180.0}};
  std::map<std::string, Position> declared_;
  std::map<std::string, Position> models_, stations_, points_;
  std::vector<NameUse> station_models_;
  std::vector<MeasurementUse> measurement_uses_;
  std::vector<std::pair<NameUse, NameUse>> distance_uses_;
};

// ---------------------------------------------------------------------------------------------
// Tokens

void Parser::advance() {
  while (true) {
    Token token = sources_.back().lexer.next();
    if (token.kind == TokenKind::kEnd && sources_.size() > 1) {
      sources_.pop_back();
      token.kind = TokenKind::kEndOfInclude;
    }
    if (token.kind == TokenKind::kIdentifier && token.text == "include") {
      include(token);
      continue;
    }
    current_ = std::move(token);
    return;
  }
}

// include "file": the file's tokens follow, as if its text stood here.
void Parser::include(const Token& keyword) {
  const Token name = sources_.back().lexer.next();
  if (name.kind != TokenKind::kString) {
    fail(name.position, "expected a file name in quotes after 'include', found " + describe(name));
  }
  if (name.text.empty()) fail(name.position, "include: the file name is empty");
  const std::filesystem::path path =
      (sources_.back().path.parent_path() / std::filesystem::path(name.text)).lexically_normal();
  if (sources_.size() >= kMaxIncludeDepth) {
    fail(keyword.position, "includes nested deeper than " + std::to_string(kMaxIncludeDepth));
  }
  if (++includes_ > kMaxIncludes) {
    std::string most;
    size_t most_times = 0;
    for (const auto& [identity, times] : times_included_) {
      if (times > most_times) std::tie(most, most_times) = std::tie(identity, times);
    }
    fail(keyword.position, "include " + in_quotes(name.text) + ": more than " +
                               std::to_string(kMaxIncludes) + " includes in all (" + most +
                               " was included " + std::to_string(most_times) +
                               " times: do the files include each other more than once?)");
  }
  SourceFile file;
  try {
    file = reader_(path);
  } catch (const std::exception& error) {
    fail(name.position, "include " + in_quotes(name.text) + ": " + error.what());
  }
  ++times_included_[file.identity];
  for (size_t i = 0; i < sources_.size(); ++i) {
    if (sources_[i].identity != file.identity) continue;
    std::string cycle;
    for (size_t j = i; j < sources_.size(); ++j) cycle += sources_[j].path.string() + " -> ";
    fail(keyword.position, "include cycle: " + cycle + path.string());
  }
  sources_.push_back(
      {Lexer(std::move(file.text), std::make_shared<const std::string>(path.string())), path,
       file.identity});
}

// Between statements or block items: passes the ends of included files; true at `symbol` (the
// end of the input for '\0').
bool Parser::at_boundary(char symbol) {
  while (current_.kind == TokenKind::kEndOfInclude) advance();
  return symbol == '\0' ? current_.kind == TokenKind::kEnd : at_symbol(symbol);
}

bool Parser::at_symbol(char symbol) const {
  return current_.kind == TokenKind::kSymbol && current_.text[0] == symbol;
}

bool Parser::at_word(std::string_view word) const {
  return current_.kind == TokenKind::kIdentifier && current_.text == word;
}

void Parser::fail(const Position& at, const std::string& message) const {
  throw ParseError(*at.file, at.line, at.column, message);
}

void Parser::fail_expected(const std::string& what) const {
  fail(current_.position, "expected " + what + ", found " + describe(current_));
}

void Parser::expect_symbol(char symbol, const std::string& context) {
  if (!at_symbol(symbol)) fail_expected(std::string("'") + symbol + "' " + context);
  advance();
}

std::string Parser::expect_identifier(const std::string& what) {
  if (current_.kind != TokenKind::kIdentifier) fail_expected(what);
  std::string text = current_.text;
  advance();
  return text;
}

NameUse Parser::expect_string(const std::string& what) {
  if (current_.kind != TokenKind::kString) fail_expected(what + " in quotes");
  NameUse use{current_.text, current_.position};
  advance();
  return use;
}

// "{" { item } "}": `item` parses one item and fails on anything it does not know.
template <typename ItemFunction>
void Parser::block(const std::string& what, ItemFunction item) {
  const Position open = current_.position;
  expect_symbol('{', "to open " + what);
  while (!at_boundary('}')) {
    if (current_.kind == TokenKind::kEnd) {
      fail(current_.position,
           "expected '}' to close " + what + " (opened at " + at_text(open) + ")");
    }
    item();
  }
  advance();
}

// ---------------------------------------------------------------------------------------------
// Expressions: expression = term { ("+" | "-") term }; term = factor { ("*" | "/") factor };
// factor = ("+" | "-") factor | number | name | "(" expression ")".

double Parser::finite(double value, const Position& at) const {
  if (!std::isfinite(value)) fail(at, "the expression's value is not finite");
  return value;
}

double Parser::expression() {
  double value = term();
  while (at_symbol('+') || at_symbol('-')) {
    const bool plus = at_symbol('+');
    const Position at = current_.position;
    advance();
    const double right = term();
    value = finite(plus ? value + right : value - right, at);
  }
  return value;
}

double Parser::term() {
  double value = factor();
  while (at_symbol('*') || at_symbol('/')) {
    const bool times = at_symbol('*');
    const Position at = current_.position;
    advance();
    const double right = factor();
    if (!times && right == 0.0) fail(at, "division by zero");
    value = finite(times ? value * right : value / right, at);
  }
  return value;
}

double Parser::factor() {
  if (++depth_ > kMaxExpressionDepth) {
    fail(current_.position,
         "expression nested deeper than " + std::to_string(kMaxExpressionDepth) + " levels");
  }
  double value = 0.0;
  if (at_symbol('+') || at_symbol('-')) {
    const bool minus = at_symbol('-');
    advance();
    value = minus ? -factor() : factor();
  } else if (current_.kind == TokenKind::kNumber) {
    value = current_.number;
    advance();
  } else if (current_.kind == TokenKind::kIdentifier) {
    const auto constant = constants_.find(current_.text);
    if (constant == constants_.end()) {
      fail(current_.position, "unknown name '" + current_.text +
                                  "' in an expression: declare it first (declare " + current_.text +
                                  " = ...)");
    }
    value = constant->second;
    advance();
  } else if (at_symbol('(')) {
    advance();
    value = expression();
    expect_symbol(')', "to close the parenthesis");
  } else {
    fail_expected("a number, a declared name or '('");
  }
  --depth_;
  return value;
}

int64_t Parser::integer(const std::string& what, int64_t lowest, int64_t highest) {
  const Position at = current_.position;
  const double value = expression();
  if (value != std::floor(value)) {
    fail(at, what + " must be an integer, found " + number_text(value));
  }
  if (value < static_cast<double>(lowest) || value > static_cast<double>(highest)) {
    fail(at, what + " must be in [" + std::to_string(lowest) + ", " + std::to_string(highest) +
                 "], found " + number_text(value));
  }
  return static_cast<int64_t>(value);
}

bool Parser::boolean(const std::string& what) {
  if (at_word("true") || at_word("false")) {
    const bool value = at_word("true");
    advance();
    return value;
  }
  fail_expected("true or false for " + what);
}

// ---------------------------------------------------------------------------------------------
// Statements

scene::Network Parser::parse(std::string text, const std::filesystem::path& path,
                             const std::string& identity) {
  sources_.push_back(
      {Lexer(std::move(text), std::make_shared<const std::string>(path.string())), path, identity});
  advance();
  while (!at_boundary('\0')) statement();
  check_references();
  return std::move(network_);
}

void Parser::statement() {
  if (at_word("declare")) return declaration();
  if (at_word("design")) return design();
  if (at_word("camera_model")) return camera_model();
  if (at_word("station")) return station();
  if (at_word("point")) return point();
  if (at_word("measurements")) return measurements();
  if (at_word("constraints")) return constraints();
  if (at_word("residual_test")) return residual_test();
  fail_expected(
      "a statement (include, declare, design, camera_model, station, point, measurements, "
      "constraints, residual_test)");
}

// declare NAME = expression
void Parser::declaration() {
  advance();
  const Position at = current_.position;
  const std::string name = expect_identifier("a name after 'declare'");
  if (name == "true" || name == "false" || name == "pi" || name == "deg" || name == "declare") {
    fail(at, "'" + name + "' is reserved and cannot be declared");
  }
  if (const auto previous = declared_.find(name); previous != declared_.end()) {
    fail(at, "'" + name + "' is already declared at " + at_text(previous->second));
  }
  expect_symbol('=', "after 'declare " + name + "'");
  constants_[name] = expression();
  declared_.emplace(name, at);
}

void Parser::design() {
  advance();
  block("the design block", [this] { design_tag(); });
}

// The i-th word of a tag's words ("OUTPUT ITERATIONS", 1 -> "ITERATIONS"); empty past the end.
std::string_view nth_word(std::string_view words, size_t i) {
  for (size_t k = 0; k < i && !words.empty(); ++k) {
    const size_t space = words.find(' ');
    words = space == std::string_view::npos ? std::string_view() : words.substr(space + 1);
  }
  return words.substr(0, words.find(' '));
}

// [ "NO" ] TAG [ value ], TAG one of kDesignTags.
void Parser::design_tag() {
  const bool negated = at_word("NO");
  if (negated) advance();
  const Position at = current_.position;
  std::string words;
  const DesignTag& tag = match_design_tag(words);
  apply_design_tag(tag, negated, at, words);
}

// Reads a tag's words one by one, narrowing the candidates, until one tag is complete; `words`
// collects what was read. No tag's words begin another's.
const DesignTag& Parser::match_design_tag(std::string& words) {
  std::vector<const DesignTag*> candidates;
  for (const DesignTag& tag : kDesignTags) candidates.push_back(&tag);
  for (size_t i = 0;; ++i) {
    std::vector<const DesignTag*> matching;
    std::vector<std::string_view> expected;
    for (const DesignTag* tag : candidates) {
      const std::string_view word = nth_word(tag->words, i);
      if (std::find(expected.begin(), expected.end(), word) == expected.end()) {
        expected.push_back(word);
      }
      if (current_.kind == TokenKind::kIdentifier && current_.text == word) matching.push_back(tag);
    }
    if (matching.empty()) {
      std::string list;
      for (const std::string_view word : expected)
        list += (list.empty() ? "" : ", ") + std::string(word);
      if (i == 0) fail_expected("a design tag (" + list + ") or '}'");
      fail_expected("one of " + list + " after '" + words + "'");
    }
    words += (words.empty() ? "" : " ") + current_.text;
    advance();
    for (const DesignTag* tag : matching) {
      if (tag->words == words) return *tag;
    }
    candidates = std::move(matching);
  }
}

void Parser::apply_design_tag(const DesignTag& tag, bool negated, const Position& at,
                              const std::string& words) {
  scene::DesignOptions& d = network_.design;
  constexpr int64_t kMaxInt = std::numeric_limits<int>::max();
  switch (tag.kind) {
    case TagKind::kFlag:
      d.*(tag.flag) = !negated;
      return;
    case TagKind::kOutputIterations:
      d.output_iterations = !negated;
      d.output_iterations_inline = at_word("INLINE") && !negated;
      if (at_word("INLINE")) advance();
      return;
    case TagKind::kExactIterations:
      d.exact_iterations.reset();
      if (!negated) d.exact_iterations = static_cast<int>(integer(words, 0, kMaxInt));
      return;
    default:
      break;
  }
  if (negated) fail(at, "NO cannot precede " + words + " (give it a value instead)");
  if (tag.kind == TagKind::kMaxIterations) {
    d.max_iterations = static_cast<int>(integer(words, 0, kMaxInt));
  } else if (tag.kind == TagKind::kCount) {
    d.*(tag.count) = static_cast<int>(integer(words, 0, kMaxInt));
  } else if (tag.kind == TagKind::kConvergenceTolerance) {
    d.convergence_tolerance = expression();
  } else {
    d.simulation_seed =
        static_cast<uint32_t>(integer(words, 0, std::numeric_limits<uint32_t>::max()));
  }
}

void Parser::define(std::map<std::string, Position>& defined, const NameUse& name,
                    const char* what) {
  const auto [previous, inserted] = defined.emplace(name.name, name.position);
  if (!inserted) {
    fail(name.position, std::string(what) + " " + in_quotes(name.name) + " is already defined at " +
                            at_text(previous->second));
  }
}

bool Parser::at_prior() const { return at_word("free") || at_word("fixed") || at_word("sigma"); }

// "free" | "fixed" | "sigma" expression
ParameterPrior Parser::prior() {
  if (at_word("free") || at_word("fixed")) {
    const bool fixed = at_word("fixed");
    advance();
    return fixed ? ParameterPrior::fixed() : ParameterPrior::free();
  }
  advance();  // sigma
  return ParameterPrior::observed(expression());
}

// After the parameter's name: ( "=" expression [ prior ] | prior ). True when a value was given.
bool Parser::parameter(double& value, ParameterPrior& prior_out, const std::string& owner) {
  const std::string name = current_.text;
  advance();
  const bool has_value = at_symbol('=');
  if (has_value) {
    advance();
    value = expression();
  } else if (!at_prior()) {
    fail_expected("'=' or free, fixed, sigma after " + name + " in " + owner);
  }
  if (at_prior()) prior_out = prior();
  return has_value;
}

template <size_t N>
int name_index(const std::array<std::string_view, N>& names, const Token& token) {
  if (token.kind != TokenKind::kIdentifier) return -1;
  for (size_t i = 0; i < N; ++i) {
    if (names[i] == token.text) return static_cast<int>(i);
  }
  return -1;
}

// camera_model NAME { sensor { ... } PARAMETER ... }
void Parser::camera_model() {
  advance();
  const NameUse name = expect_string("the camera model's name");
  define(models_, name, "camera_model");
  scene::CameraModel model;
  model.name = name.name;
  const std::string owner = "camera_model " + in_quotes(name.name);
  block(owner, [&] {
    if (at_word("sensor")) return sensor(model);
    const int i = name_index(kInteriorNames, current_);
    if (i < 0) fail_expected("sensor, c, xp, yp, k1, k2, k3, p1, p2, sc, sh or '}' in " + owner);
    auto values = sensor::interior_block(model.interior);
    parameter(values[static_cast<size_t>(i)], model.priors[static_cast<size_t>(i)], owner);
    model.interior = sensor::interior_from_block(values.data());
  });
  network_.models.push_back(std::move(model));
}

// sensor { width = n height = n pixel_width = mm pixel_height = mm }
void Parser::sensor(scene::CameraModel& model) {
  advance();
  const std::string owner = "the sensor of camera_model " + in_quotes(model.name);
  block(owner, [&] {
    const std::string field =
        expect_identifier("width, height, pixel_width, pixel_height or '}' in " + owner);
    if (field != "width" && field != "height" && field != "pixel_width" &&
        field != "pixel_height") {
      fail_expected("width, height, pixel_width, pixel_height or '}' in " + owner + " (not '" +
                    field + "')");
    }
    expect_symbol('=', "after " + field);
    sensor::SensorGeometry& s = model.sensor;
    constexpr int64_t kMaxPixels = std::numeric_limits<int>::max();
    if (field == "width") s.width_px = static_cast<int>(integer("width", 0, kMaxPixels));
    if (field == "height") s.height_px = static_cast<int>(integer("height", 0, kMaxPixels));
    if (field == "pixel_width") s.pixel_width_mm = expression();
    if (field == "pixel_height") s.pixel_height_mm = expression();
  });
}

// station NAME { camera_id = n  model = "M"  PARAMETER ... }
void Parser::station() {
  advance();
  const NameUse name = expect_string("the station's name");
  define(stations_, name, "station");
  scene::Station station;
  station.name = name.name;
  NameUse model{"", name.position};
  const std::string owner = "station " + in_quotes(name.name);
  block(owner, [&] {
    if (at_word("camera_id") || at_word("model")) {
      const bool is_model = at_word("model");
      advance();
      expect_symbol('=', is_model ? "after model" : "after camera_id");
      if (is_model) {
        model = expect_string("the camera model's name");
      } else {
        station.camera_id =
            static_cast<int>(integer("camera_id", -1, std::numeric_limits<int>::max()));
      }
      return;
    }
    const int i = name_index(kExteriorNames, current_);
    if (i < 0) {
      fail_expected("camera_id, model, X0, Y0, Z0, omega, phi, kappa or '}' in " + owner);
    }
    auto values = sensor::exterior_block(station.exterior);
    if (parameter(values[static_cast<size_t>(i)], station.priors[static_cast<size_t>(i)], owner)) {
      station.has_approximation = true;
    }
    station.exterior = sensor::exterior_from_block(values.data());
  });
  station.model = model.name;
  station_models_.push_back(model);
  network_.stations.push_back(std::move(station));
}

// point NAME { X = x  Y = y  Z = z | xyz = <x, y, z> [prior] ... }
void Parser::point() {
  advance();
  const NameUse name = expect_string("the point's name");
  define(points_, name, "point");
  scene::ObjectPoint point;
  point.name = name.name;
  const std::string owner = "point " + in_quotes(name.name);
  block(owner, [&] {
    const int i = name_index(kPointNames, current_);
    if (i >= 0) {
      if (parameter(point.xyz[static_cast<size_t>(i)], point.priors[static_cast<size_t>(i)],
                    owner)) {
        point.has_approximation = true;
      }
      return;
    }
    if (!at_word("xyz")) fail_expected("X, Y, Z, xyz or '}' in " + owner);
    advance();
    if (at_symbol('=')) {
      advance();
      expect_symbol('<', "to open the vector <X, Y, Z> of " + owner);
      for (size_t k = 0; k < 3; ++k) {
        point.xyz[k] = expression();
        if (k < 2) expect_symbol(',', "between the coordinates of " + owner);
      }
      expect_symbol('>', "to close the vector <X, Y, Z> of " + owner);
      point.has_approximation = true;
    } else if (!at_prior()) {
      fail_expected("'=' or free, fixed, sigma after xyz in " + owner);
    }
    if (at_prior()) point.priors.fill(prior());
  });
  network_.points.push_back(std::move(point));
}

// measurements { sigma = px  frame = n  "STATION" "POINT" [ <u, v> ] ... }
void Parser::measurements() {
  advance();
  double sigma_px = scene::ImageMeasurement{}.sigma_px;
  int64_t frame = -1;
  block("the measurements block", [&] {
    if (at_word("sigma") || at_word("frame")) {
      const bool is_sigma = at_word("sigma");
      advance();
      expect_symbol('=', is_sigma ? "after sigma" : "after frame");
      if (is_sigma) {
        sigma_px = expression();
      } else {
        frame = integer("frame", -kMaxExactInteger, kMaxExactInteger);
      }
      return;
    }
    if (current_.kind != TokenKind::kString) {
      fail_expected(
          "\"STATION\" \"POINT\" <u, v>, sigma = ..., frame = ... or '}' in measurements");
    }
    MeasurementUse use;
    use.station = expect_string("the station's name");
    use.point = expect_string("the point's name after the station's");
    scene::ImageMeasurement m;
    m.station = use.station.name;
    m.point = use.point.name;
    m.sigma_px = sigma_px;
    m.frame_number = frame;
    use.has_coordinates = at_symbol('<');
    if (use.has_coordinates) {
      advance();
      m.u = expression();
      expect_symbol(',', "between u and v");
      m.v = expression();
      expect_symbol('>', "to close <u, v>");
    }
    measurement_uses_.push_back(std::move(use));
    network_.measurements.push_back(std::move(m));
  });
}

// constraints { distance "A" "B" = mm [ sigma mm ] ... }
void Parser::constraints() {
  advance();
  block("the constraints block", [&] {
    if (!at_word("distance")) fail_expected("distance or '}' in the constraints block");
    advance();
    scene::DistanceConstraint d;
    NameUse a = expect_string("the first point's name after distance");
    NameUse b = expect_string("the second point's name");
    d.point_a = a.name;
    d.point_b = b.name;
    expect_symbol('=', "before the distance [mm]");
    d.distance = expression();
    if (at_word("sigma")) {
      advance();
      d.sigma = expression();
    }
    distance_uses_.emplace_back(std::move(a), std::move(b));
    network_.distances.push_back(std::move(d));
  });
}

// residual_test { alpha_variance = a  alpha_goodness = a  critical_snooping = w
//                 iterative_rejection = true|false  max_rejections = n
//                 snoop_with_a_posteriori_sigma0 = true|false  reject_per_point = true|false }
void Parser::residual_test() {
  advance();
  scene::ResidualTest& t = network_.residual_test;
  block("the residual_test block", [&] {
    const std::string expected =
        "alpha_variance, alpha_goodness, critical_snooping, iterative_rejection, max_rejections, "
        "snoop_with_a_posteriori_sigma0, reject_per_point or '}' in the residual_test block";
    if (current_.kind != TokenKind::kIdentifier) fail_expected(expected);
    const std::string field = current_.text;
    if (field != "alpha_variance" && field != "alpha_goodness" && field != "critical_snooping" &&
        field != "iterative_rejection" && field != "max_rejections" &&
        field != "snoop_with_a_posteriori_sigma0" && field != "reject_per_point") {
      fail_expected(expected);
    }
    advance();
    expect_symbol('=', "after " + field);
    if (field == "alpha_variance") t.alpha_variance = expression();
    if (field == "alpha_goodness") t.alpha_goodness = expression();
    if (field == "critical_snooping") t.critical_snooping = expression();
    if (field == "iterative_rejection") t.iterative_rejection = boolean(field);
    if (field == "reject_per_point") t.reject_per_point = boolean(field);
    if (field == "snoop_with_a_posteriori_sigma0") {
      t.snoop_with_a_posteriori_sigma0 = boolean(field);
    }
    if (field == "max_rejections") {
      t.max_rejections =
          static_cast<int>(integer("max_rejections", 0, std::numeric_limits<int>::max()));
    }
  });
}

// Every name a station, measurement or constraint uses must be defined somewhere in the scene
// (before or after the use, in any included file).
void Parser::check_references() const {
  for (size_t s = 0; s < station_models_.size(); ++s) {
    const NameUse& use = station_models_[s];
    if (!models_.contains(use.name)) {
      fail(use.position, "station " + in_quotes(network_.stations[s].name) + ": no camera_model " +
                             in_quotes(use.name) + " in the scene");
    }
  }
  for (const MeasurementUse& use : measurement_uses_) {
    if (!stations_.contains(use.station.name)) {
      fail(use.station.position,
           "measurement: no station " + in_quotes(use.station.name) + " in the scene");
    }
    if (!points_.contains(use.point.name)) {
      fail(use.point.position,
           "measurement: no point " + in_quotes(use.point.name) + " in the scene");
    }
    if (!use.has_coordinates && !network_.design.simulate) {
      fail(use.point.position,
           "measurement without <u, v>: give the coordinates, or SIMULATE in the design block");
    }
  }
  for (const auto& [a, b] : distance_uses_) {
    for (const NameUse* use : {&a, &b}) {
      if (!points_.contains(use->name)) {
        fail(use->position, "distance: no point " + in_quotes(use->name) + " in the scene");
      }
    }
  }
}

}  // namespace

SourceFile read_source_file(const std::filesystem::path& path) {
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error) throw std::runtime_error("cannot open " + path.string() + ": " + error.message());
  if (!std::filesystem::is_regular_file(status)) {
    throw std::runtime_error("cannot read " + path.string() + ": not a regular file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path.string());
  std::ostringstream text;
  text << in.rdbuf();
  const auto canonical = std::filesystem::weakly_canonical(path, error);
  return {error ? path.lexically_normal().string() : canonical.string(), text.str()};
}

scene::Network parse(std::string text, const std::filesystem::path& path,
                     const std::string& identity, const FileReader& reader) {
  Parser parser(reader);
  return parser.parse(std::move(text), path, identity);
}

}  // namespace syncap::sdl::detail

namespace syncap::sdl {

scene::Network parse_string(std::string_view text, const std::string& name) {
  const std::filesystem::path path(name);
  std::error_code error;
  const auto canonical = std::filesystem::weakly_canonical(path, error);
  return detail::parse(std::string(text), path, error ? name : canonical.string(),
                       detail::read_source_file);
}

scene::Network parse_file(const std::filesystem::path& path) {
  detail::SourceFile file;
  try {
    file = detail::read_source_file(path);
  } catch (const std::exception& error) {
    throw ParseError(path.string(), 0, 0, error.what());
  }
  return detail::parse(std::move(file.text), path, file.identity, detail::read_source_file);
}

}  // namespace syncap::sdl
