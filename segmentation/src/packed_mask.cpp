#include "syncap/segmentation/packed_mask.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>

#include <opencv2/core/hal/intrin.hpp>

namespace syncap::segmentation::detail {
namespace {

constexpr std::uint64_t kOnes = ~std::uint64_t{0};

// Bits x .. x + 63 of a padded row shifted by `dx` (|dx| <= 63): bit i of the result is pixel
// x + i + dx. `word` points at the row's word holding pixel x.
inline std::uint64_t shifted_word(const std::uint64_t* word, int dx) {
  if (dx > 0) return (word[0] >> dx) | (word[1] << (64 - dx));
  if (dx < 0) return (word[0] << -dx) | (word[-1] >> (64 + dx));
  return word[0];
}

// For each byte value, the eight bytes 0 / 0xFF of its bits, bit 0 first.
constexpr std::array<std::uint64_t, 256> make_unpack_table() {
  std::array<std::uint64_t, 256> table{};
  for (int value = 0; value < 256; ++value) {
    std::uint64_t bytes = 0;
    for (int bit = 0; bit < 8; ++bit) {
      if ((value >> bit) & 1) bytes |= std::uint64_t{0xFF} << (8 * bit);
    }
    table[static_cast<std::size_t>(value)] = bytes;
  }
  return table;
}
constexpr std::array<std::uint64_t, 256> kUnpack = make_unpack_table();

// The run of ones of one element row as offsets from the anchor column; empty when lo > hi.
struct ElementRow {
  int dy, lo, hi;
};

std::vector<ElementRow> element_rows(const cv::Mat& element) {
  std::vector<ElementRow> result;
  const int anchor_x = element.cols / 2, anchor_y = element.rows / 2;
  for (int j = 0; j < element.rows; ++j) {
    const uchar* e = element.ptr<uchar>(j);
    int lo = 0;
    while (lo < element.cols && e[lo] == 0) ++lo;
    if (lo == element.cols) continue;
    int hi = element.cols - 1;
    while (e[hi] == 0) --hi;
    result.push_back({j - anchor_y, lo - anchor_x, hi - anchor_x});
  }
  return result;
}

}  // namespace

void PackedMask::pack(const cv::Mat& bytes) {
  rows_ = bytes.rows;
  cols_ = bytes.cols;
  words_per_row_ = (cols_ + 63) / 64;
  stride_ = static_cast<std::size_t>(words_per_row_) + 2;
  words_.assign(static_cast<std::size_t>(rows_) * stride_, 0);
  for (int y = 0; y < rows_; ++y) {
    const uchar* in = bytes.ptr<uchar>(y);
    std::uint64_t* out = row(y);
    int x = 0;
#if CV_SIMD128
    // 16 pixels at a time: the sign bits of (pixel != 0).
    const cv::v_uint8x16 zero = cv::v_setzero_u8();
    for (; x + 16 <= cols_; x += 16) {
      const auto bits = static_cast<std::uint64_t>(
          static_cast<unsigned>(cv::v_signmask(cv::v_load(in + x) != zero)) & 0xFFFFu);
      out[x / 64] |= bits << (x % 64);
    }
#endif
    for (; x + 8 <= cols_; x += 8) {
      std::uint64_t eight;
      std::memcpy(&eight, in + x, 8);
      if (eight == 0) continue;
      std::uint64_t bits = 0;
      for (int i = 0; i < 8; ++i) bits |= std::uint64_t{in[x + i] != 0} << i;
      out[x / 64] |= bits << (x % 64);
    }
    for (; x < cols_; ++x) {
      if (in[x] != 0) out[x / 64] |= std::uint64_t{1} << (x % 64);
    }
  }
}

void PackedMask::unpack(cv::Mat& bytes) const {
  for (int y = 0; y < rows_; ++y) {
    const std::uint64_t* in = row(y);
    uchar* out = bytes.ptr<uchar>(y);
    int x = 0;
    // A mask is mostly wide stretches of one value: a word of 64 equal pixels is one fill.
    for (; x + 64 <= cols_; x += 64) {
      const std::uint64_t word = in[x / 64];
      if (word == 0) {
        std::memset(out + x, 0, 64);
        continue;
      }
      if (word == kOnes) {
        std::memset(out + x, 255, 64);
        continue;
      }
      for (int i = 0; i < 64; i += 8) {
        const std::uint64_t eight = kUnpack[(word >> i) & 0xFF];
        std::memcpy(out + x + i, &eight, 8);
      }
    }
    for (; x + 8 <= cols_; x += 8) {
      const std::uint64_t eight = kUnpack[(in[x / 64] >> (x % 64)) & 0xFF];
      std::memcpy(out + x, &eight, 8);
    }
    for (; x < cols_; ++x) out[x] = ((in[x / 64] >> (x % 64)) & 1) != 0 ? 255 : 0;
  }
}

bool PackedMask::closable_by(const cv::Mat& element) {
  if (element.type() != CV_8UC1 || element.cols > 127 || element.rows > 127) return false;
  for (int j = 0; j < element.rows; ++j) {
    const uchar* e = element.ptr<uchar>(j);
    int x = 0;
    while (x < element.cols && e[x] == 0) ++x;
    while (x < element.cols && e[x] != 0) ++x;
    while (x < element.cols && e[x] == 0) ++x;
    if (x != element.cols) return false;  // a second run
  }
  return true;
}

void PackedMask::set_padding(std::uint64_t fill) {
  const int tail = cols_ % 64;
  for (int y = 0; y < rows_; ++y) {
    std::uint64_t* r = row(y);
    r[-1] = fill;
    r[words_per_row_] = fill;
    if (tail != 0) {
      const std::uint64_t inside = (std::uint64_t{1} << tail) - 1;
      r[words_per_row_ - 1] = (r[words_per_row_ - 1] & inside) | (fill & ~inside);
    }
  }
}

template <bool kDilate>
void PackedMask::morph_from(const PackedMask& source, const cv::Mat& element) {
  rows_ = source.rows_;
  cols_ = source.cols_;
  words_per_row_ = source.words_per_row_;
  stride_ = source.stride_;
  const std::uint64_t neutral = kDilate ? 0 : kOnes;
  const auto combine = [](std::uint64_t a, std::uint64_t b) { return kDilate ? a | b : a & b; };
  words_.assign(static_cast<std::size_t>(rows_) * stride_, neutral);
  const std::size_t width = static_cast<std::size_t>(words_per_row_);

  // Each distinct run [lo, hi] of the element's rows, combined along every source row: from
  // levels L_i (run [0, 2^i - 1], L_{i+1} = L_i op L_i shifted by 2^i), two shifted copies of
  // the largest level not longer than the run cover it.
  const std::vector<ElementRow> rows = element_rows(element);
  std::vector<std::pair<int, int>> runs;
  std::vector<std::size_t> run_of_row;
  int longest = 1;
  for (const ElementRow& e : rows) {
    const std::pair<int, int> run{e.lo, e.hi};
    auto found = std::find(runs.begin(), runs.end(), run);
    if (found == runs.end()) found = runs.insert(runs.end(), run);
    run_of_row.push_back(static_cast<std::size_t>(found - runs.begin()));
    longest = std::max(longest, e.hi - e.lo + 1);
  }
  const int levels = std::bit_width(static_cast<unsigned>(longest));  // 2^(levels-1) <= longest
  levels_.assign(static_cast<std::size_t>(levels) * stride_, neutral);
  combined_.resize(runs.size() * static_cast<std::size_t>(rows_) * width);
  for (int y = 0; y < rows_; ++y) {
    const std::uint64_t* in = source.row(y);
    std::copy(in, in + width, levels_.begin() + 1);
    for (int level = 1; level < levels; ++level) {
      const std::uint64_t* previous =
          levels_.data() + static_cast<std::size_t>(level - 1) * stride_ + 1;
      std::uint64_t* next = levels_.data() + static_cast<std::size_t>(level) * stride_ + 1;
      const int step = 1 << (level - 1);
      // The left padding word too: its runs reach into the row.
      next[-1] = combine(previous[-1], shifted_word(previous - 1, step));
      for (std::size_t k = 0; k < width; ++k) {
        next[k] = combine(previous[k], shifted_word(previous + k, step));
      }
    }
    for (std::size_t r = 0; r < runs.size(); ++r) {
      const auto [lo, hi] = runs[r];
      const int level = std::bit_width(static_cast<unsigned>(hi - lo + 1)) - 1;
      const std::uint64_t* base = levels_.data() + static_cast<std::size_t>(level) * stride_ + 1;
      const int second = hi - (1 << level) + 1;
      std::uint64_t* out =
          combined_.data() +
          (r * static_cast<std::size_t>(rows_) + static_cast<std::size_t>(y)) * width;
      for (std::size_t k = 0; k < width; ++k) {
        out[k] = combine(shifted_word(base + k, lo), shifted_word(base + k, second));
      }
    }
  }
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const int dy = rows[j].dy;
    const std::uint64_t* run_rows =
        combined_.data() + run_of_row[j] * static_cast<std::size_t>(rows_) * width;
    // Rows outside the image are neutral: they neither dilate nor erode.
    const int y_begin = std::max(0, -dy), y_end = std::min(rows_, rows_ - dy);
    for (int y = y_begin; y < y_end; ++y) {
      const std::uint64_t* in = run_rows + static_cast<std::size_t>(y + dy) * width;
      std::uint64_t* out = row(y);
      for (std::size_t k = 0; k < width; ++k) out[k] = combine(out[k], in[k]);
    }
  }
}

void PackedMask::close(const cv::Mat& element) {
  set_padding(0);
  PackedMask dilated;
  dilated.morph_from<true>(*this, element);
  dilated.set_padding(kOnes);
  morph_from<false>(dilated, element);
  set_padding(0);
}

int PackedMask::root_of(int run) {
  while (parent_[static_cast<std::size_t>(run)] != run) {
    const int up = parent_[static_cast<std::size_t>(run)];
    parent_[static_cast<std::size_t>(run)] = parent_[static_cast<std::size_t>(up)];
    run = up;
  }
  return run;
}

void PackedMask::label_runs(bool eight_connected) {
  set_padding(0);
  runs_.clear();
  parent_.clear();
  // Columns beyond its ends where a run touches a run of the last row.
  const int reach = eight_connected ? 1 : 0;
  std::size_t previous_begin = 0, previous_end = 0;
  for (int y = 0; y < rows_; ++y) {
    const std::size_t begin = runs_.size();
    const std::uint64_t* r = row(y);
    std::size_t scan = previous_begin;
    // Runs of ones: from each run start (a set bit after a clear one) to its end.
    int x = 0;
    while (x < cols_) {
      std::uint64_t word = r[x / 64] >> (x % 64);
      if (word == 0) {
        x = (x / 64 + 1) * 64;
        continue;
      }
      x += std::countr_zero(word);
      const int start = x;
      while (x < cols_) {  // the bits past the last column are clear, so the run ends there
        const int offset = x % 64;
        const int length = std::countr_one(r[x / 64] >> offset);
        x += length;
        if (length < 64 - offset) break;
      }
      runs_.push_back({y, start, x - 1});
      const int id = static_cast<int>(parent_.size());
      parent_.push_back(id);
      // Joined to the runs of the previous row that overlap [start - reach, x - 1 + reach].
      while (scan < previous_end && runs_[scan].x1 < start - reach) ++scan;
      for (std::size_t p = scan; p < previous_end && runs_[p].x0 <= x - 1 + reach; ++p) {
        const int a = root_of(static_cast<int>(p)), b = root_of(id);
        if (a != b) parent_[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
      }
    }
    previous_begin = begin;
    previous_end = runs_.size();
  }
  area_.assign(runs_.size(), 0);
  for (std::size_t i = 0; i < runs_.size(); ++i) {
    area_[static_cast<std::size_t>(root_of(static_cast<int>(i)))] += runs_[i].x1 - runs_[i].x0 + 1;
  }
}

void PackedMask::set_run(const Run& run, bool value) {
  std::uint64_t* r = row(run.y);
  for (int x = run.x0; x <= run.x1; ++x) {
    const std::uint64_t bit = std::uint64_t{1} << (x % 64);
    r[x / 64] = value ? r[x / 64] | bit : r[x / 64] & ~bit;
  }
}

void PackedMask::remove_small_components(int min_area) {
  if (min_area <= 1) return;
  label_runs(true);
  for (std::size_t i = 0; i < runs_.size(); ++i) {
    if (area_[static_cast<std::size_t>(root_of(static_cast<int>(i)))] < min_area) {
      set_run(runs_[i], false);
    }
  }
}

void PackedMask::invert() {
  for (int y = 0; y < rows_; ++y) {
    std::uint64_t* r = row(y);
    for (int k = 0; k < words_per_row_; ++k) r[k] = ~r[k];
  }
  set_padding(0);
}

void PackedMask::fill_holes(int max_area) {
  if (max_area <= 0) return;
  invert();  // the background becomes the ones that label_runs joins
  label_runs(false);
  // A component with a run on the mask's rim reaches what lies beyond it: not a hole.
  rim_.assign(runs_.size(), 0);
  for (std::size_t i = 0; i < runs_.size(); ++i) {
    const Run& run = runs_[i];
    if (run.y == 0 || run.y == rows_ - 1 || run.x0 == 0 || run.x1 == cols_ - 1) {
      rim_[static_cast<std::size_t>(root_of(static_cast<int>(i)))] = 1;
    }
  }
  invert();
  for (std::size_t i = 0; i < runs_.size(); ++i) {
    const auto root = static_cast<std::size_t>(root_of(static_cast<int>(i)));
    if (rim_[root] == 0 && area_[root] <= max_area) set_run(runs_[i], true);
  }
}

}  // namespace syncap::segmentation::detail
