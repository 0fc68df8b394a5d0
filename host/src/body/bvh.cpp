#include "body/bvh.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace syncap::body {
namespace {

struct Token {
  std::string_view text;
  int line = 0;
};

std::vector<std::string_view> split_lines(std::string_view text) {
  std::vector<std::string_view> lines;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    std::string_view line = text.substr(0, end);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    if (end == std::string_view::npos) break;
    text.remove_prefix(end + 1);
  }
  return lines;
}

// Whitespace-separated words; braces are words of their own even when glued to a name.
std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    const auto c = static_cast<unsigned char>(line[i]);
    if (std::isspace(c)) {
      ++i;
    } else if (c == '{' || c == '}') {
      words.push_back(line.substr(i++, 1));
    } else {
      std::size_t j = i;
      while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j])) &&
             line[j] != '{' && line[j] != '}') {
        ++j;
      }
      words.push_back(line.substr(i, j - i));
      i = j;
    }
  }
  return words;
}

bool equals_ignoring_case(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

bool parse_number(std::string_view word, double& value) {
  if (!word.empty() && word.front() == '+') word.remove_prefix(1);
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  return error == std::errc() && end == word.data() + word.size() && std::isfinite(value);
}

bool parse_channel(std::string_view word, BvhChannel& channel) {
  static constexpr std::pair<std::string_view, BvhChannel> kNames[] = {
      {"Xposition", BvhChannel::kXposition}, {"Yposition", BvhChannel::kYposition},
      {"Zposition", BvhChannel::kZposition}, {"Xrotation", BvhChannel::kXrotation},
      {"Yrotation", BvhChannel::kYrotation}, {"Zrotation", BvhChannel::kZrotation}};
  for (const auto& [name, c] : kNames) {
    if (equals_ignoring_case(word, name)) {
      channel = c;
      return true;
    }
  }
  return false;
}

std::string quoted(std::string_view word) { return "'" + std::string(word) + "'"; }

class Parser {
 public:
  Parser(std::string_view text, std::string source)
      : lines_(split_lines(text)), source_(std::move(source)) {}

  Bvh parse() {
    bvh_.source = source_;
    tokenize_hierarchy();
    parse_hierarchy();
    parse_motion();
    return std::move(bvh_);
  }

 private:
  [[noreturn]] void fail(int line, const std::string& problem) const {
    throw BvhError(source_, line, problem);
  }
  int last_line() const { return std::max(1, static_cast<int>(lines_.size())); }

  // Tokens of everything before the MOTION line; motion_line_ is that line (0-based).
  void tokenize_hierarchy() {
    for (motion_line_ = 0; motion_line_ < lines_.size(); ++motion_line_) {
      const auto words = split_words(lines_[motion_line_]);
      if (!words.empty() && words.front() == "MOTION") return;
      for (auto w : words) tokens_.push_back({w, static_cast<int>(motion_line_) + 1});
    }
  }
  int end_of_hierarchy_line() const {
    return motion_line_ < lines_.size() ? static_cast<int>(motion_line_) + 1 : last_line();
  }

  bool at_end() const { return next_ >= tokens_.size(); }
  const Token& peek() const { return tokens_[next_]; }
  Token take(const char* expected) {
    if (at_end())
      fail(end_of_hierarchy_line(), std::string("expected ") + expected + ", got " +
                                        (motion_line_ < lines_.size() ? "MOTION" : "end of file"));
    return tokens_[next_++];
  }
  double take_number(const char* what) {
    const Token t = take(what);
    double v = 0;
    if (!parse_number(t.text, v))
      fail(t.line, std::string("expected ") + what + ", got " + quoted(t.text));
    return v;
  }

  void parse_hierarchy() {
    const Token first = take("HIERARCHY");
    if (first.text != "HIERARCHY")
      fail(first.line, "expected HIERARCHY, got " + quoted(first.text));
    const Token root = take("ROOT");
    if (root.text != "ROOT") fail(root.line, "expected ROOT, got " + quoted(root.text));
    parse_joint(root, -1);
    if (!at_end()) {
      const Token t = peek();
      if (t.text == "}") fail(t.line, "unbalanced braces: '}' closes no joint");
      if (t.text == "ROOT") fail(t.line, "a second ROOT is not supported");
      fail(t.line, "unexpected " + quoted(t.text) + " after the ROOT joint");
    }
    if (motion_line_ >= lines_.size()) fail(last_line(), "no MOTION section");
  }

  // The joint's name is the rest of its line: some exporters put spaces in names.
  std::string take_name(const Token& keyword) {
    std::string name;
    while (!at_end() && peek().line == keyword.line && peek().text != "{") {
      if (!name.empty()) name += ' ';
      name += take("name").text;
    }
    if (name.empty()) fail(keyword.line, std::string(keyword.text) + " without a name");
    return name;
  }

  void expect_open(const std::string& what) {
    const Token t = take("'{'");
    if (t.text != "{") fail(t.line, "expected '{' after " + what + ", got " + quoted(t.text));
  }

  void parse_joint(const Token& keyword, int parent) {
    BvhJoint joint;
    joint.name = take_name(keyword);
    joint.parent = parent;
    joint.line = keyword.line;
    expect_open(std::string(keyword.text) + " " + joint.name);
    const int index = static_cast<int>(bvh_.joints.size());
    bvh_.joints.push_back(joint);
    bool has_offset = false;
    while (true) {
      if (at_end()) {
        fail(end_of_hierarchy_line(), "unbalanced braces: joint '" + joint.name + "' (line " +
                                          std::to_string(joint.line) + ") is not closed");
      }
      const Token t = take("a keyword");
      if (t.text == "}") break;
      if (t.text == "OFFSET") {
        read_offset(index);
        has_offset = true;
      } else if (t.text == "CHANNELS") {
        read_channels(index, t);
      } else if (t.text == "JOINT") {
        parse_joint(t, index);
      } else if (t.text == "End") {
        parse_end_site(t, index);
      } else {
        fail(t.line, "unknown keyword " + quoted(t.text) + " in joint '" + joint.name + "'");
      }
    }
    if (!has_offset) fail(joint.line, "joint '" + joint.name + "' has no OFFSET");
  }

  void read_offset(int index) {
    Eigen::Vector3d offset;
    for (int k = 0; k < 3; ++k) offset[k] = take_number("an OFFSET value");
    bvh_.joints[static_cast<std::size_t>(index)].offset = offset;
  }

  void read_channels(int index, const Token& keyword) {
    BvhJoint& joint = bvh_.joints[static_cast<std::size_t>(index)];
    if (!joint.channels.empty())
      fail(keyword.line, "second CHANNELS in joint '" + joint.name + "'");
    const Token count = take("a channel count");
    int n = -1;
    const auto [end, error] =
        std::from_chars(count.text.data(), count.text.data() + count.text.size(), n);
    if (error != std::errc() || end != count.text.data() + count.text.size() || n < 0 || n > 6) {
      fail(count.line, "expected a channel count 0..6, got " + quoted(count.text));
    }
    for (int k = 0; k < n; ++k) {
      const Token t = take("a channel name");
      BvhChannel c{};
      if (!parse_channel(t.text, c)) {
        fail(t.line, "CHANNELS " + std::to_string(n) + ": expected a channel name (Xposition .. " +
                         "Zrotation), got " + quoted(t.text));
      }
      if (std::find(joint.channels.begin(), joint.channels.end(), c) != joint.channels.end()) {
        fail(t.line, "channel " + quoted(t.text) + " listed twice");
      }
      joint.channels.push_back(c);
    }
    joint.first_channel = bvh_.channel_count;
    bvh_.channel_count += n;
  }

  void parse_end_site(const Token& keyword, int parent) {
    const Token site = take("Site");
    if (site.text != "Site")
      fail(site.line, "expected 'End Site', got 'End " + std::string(site.text) + "'");
    BvhJoint end;
    end.name = bvh_.joints[static_cast<std::size_t>(parent)].name + "/End Site";
    end.parent = parent;
    end.end_site = true;
    end.line = keyword.line;
    end.first_channel = bvh_.channel_count;
    expect_open("End Site");
    const int index = static_cast<int>(bvh_.joints.size());
    bvh_.joints.push_back(end);
    const Token offset = take("OFFSET");
    if (offset.text != "OFFSET") {
      fail(offset.line, "expected OFFSET in End Site, got " + quoted(offset.text));
    }
    read_offset(index);
    const Token close = take("'}'");
    if (close.text != "}") {
      fail(close.line, "expected '}' closing the End Site, got " + quoted(close.text));
    }
  }

  // The words after `label` ("Frames:", "Frame Time:") at the start of the line.
  std::vector<std::string_view> labelled(std::size_t line, std::string_view label,
                                         const char* what) const {
    if (line >= lines_.size()) {
      fail(last_line(), std::string("expected ") + what + ", got end of file");
    }
    std::string_view text = lines_[line];
    text.remove_prefix(std::min(text.find_first_not_of(" \t"), text.size()));
    if (text.substr(0, label.size()) != label) {
      fail(static_cast<int>(line) + 1, std::string("expected ") + what);
    }
    return split_words(text.substr(label.size()));
  }

  std::size_t next_content_line(std::size_t line) const {
    while (line < lines_.size() && split_words(lines_[line]).empty()) ++line;
    return line;
  }

  void parse_motion() {
    const std::size_t frames_line = next_content_line(motion_line_ + 1);
    const auto frames = labelled(frames_line, "Frames:", "'Frames: <count>'");
    const int frames_at = static_cast<int>(frames_line) + 1;
    double count = 0;
    if (frames.size() != 1 || !parse_number(frames[0], count) || count < 1 ||
        count != std::floor(count)) {
      fail(frames_at, "expected 'Frames: <count>' with a count of at least 1");
    }
    bvh_.frame_count = static_cast<int>(count);
    const std::size_t time_line = next_content_line(frames_line + 1);
    const auto time = labelled(time_line, "Frame Time:", "'Frame Time: <seconds>'");
    if (time.size() != 1 || !parse_number(time[0], bvh_.frame_time_s) || bvh_.frame_time_s <= 0) {
      fail(static_cast<int>(time_line) + 1, "expected 'Frame Time: <seconds>' above 0");
    }
    read_frames(time_line + 1, frames_at);
  }

  void read_frames(std::size_t first_line, int frames_at) {
    const auto expected = static_cast<std::size_t>(bvh_.channel_count);
    bvh_.values.reserve(expected * static_cast<std::size_t>(bvh_.frame_count));
    int frames = 0;
    for (std::size_t line = first_line; line < lines_.size(); ++line) {
      const auto words = split_words(lines_[line]);
      const int at = static_cast<int>(line) + 1;
      if (words.empty()) continue;
      if (frames == bvh_.frame_count) {
        fail(at, "frame count mismatch: more frame lines than 'Frames: " +
                     std::to_string(bvh_.frame_count) + "' (line " + std::to_string(frames_at) +
                     ")");
      }
      if (words.size() != expected) {
        fail(at, "expected " + std::to_string(expected) + " channel values, got " +
                     std::to_string(words.size()));
      }
      for (std::size_t k = 0; k < words.size(); ++k) {
        double v = 0;
        if (!parse_number(words[k], v)) {
          fail(at,
               "channel value " + std::to_string(k + 1) + " is not a number: " + quoted(words[k]));
        }
        bvh_.values.push_back(v);
      }
      ++frames;
    }
    if (frames != bvh_.frame_count) {
      fail(last_line(), "frame count mismatch: " + std::to_string(frames) +
                            " frame lines, 'Frames: " + std::to_string(bvh_.frame_count) +
                            "' (line " + std::to_string(frames_at) + ")");
    }
  }

  std::vector<std::string_view> lines_;
  std::string source_;
  std::vector<Token> tokens_;
  std::size_t next_ = 0;
  std::size_t motion_line_ = 0;
  Bvh bvh_;
};

}  // namespace

BvhError::BvhError(const std::string& file, int line, const std::string& problem)
    : std::runtime_error(file + ":" + std::to_string(line) + ": " + problem),
      file_(file),
      line_(line),
      problem_(problem) {}

std::span<const double> Bvh::frame(int k) const {
  const auto n = static_cast<std::size_t>(channel_count);
  return std::span<const double>(values).subspan(static_cast<std::size_t>(k) * n, n);
}

int Bvh::find(std::string_view name) const {
  for (std::size_t i = 0; i < joints.size(); ++i) {
    if (joints[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

Bvh parse_bvh(std::string_view text, const std::string& source) {
  return Parser(text, source).parse();
}

Bvh load_bvh(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw BvhError(path.string(), 0, "cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_bvh(text.str(), path.string());
}

}  // namespace syncap::body
