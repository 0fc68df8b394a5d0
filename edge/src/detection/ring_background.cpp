#include "detection/ring_background.hpp"

#include <algorithm>
#include <cstring>

#include <opencv2/core/hal/intrin.hpp>

#include "detection/bright_mask.hpp"

namespace syncap::edge {
namespace {

// Copies the ring's pixels into `ring` (grown to hold them and 32 bytes more: the row copies
// and the padding store whole vectors) and returns how many. Row segments by whole vectors when
// those lie inside the image.
size_t gather_ring(const cv::Mat& image, cv::Rect cw, cv::Rect window, std::vector<uint8_t>& ring) {
  const int xa = std::max(cw.x - 1, window.x);
  const int xb = std::min(cw.x + cw.width, window.x + window.width - 1);
  const int row_length = xb - xa + 1;
  const bool top = cw.y - 1 >= window.y, bottom = cw.y + cw.height < window.y + window.height;
  const bool left = cw.x - 1 >= window.x, right = cw.x + cw.width < window.x + window.width;
  const size_t most = static_cast<size_t>((top + bottom) * row_length + (left + right) * cw.height);
  if (ring.size() < most + 32) ring.resize(most + 32);
  // Through a local pointer: a byte store may alias anything, the vector's own pointer too.
  uint8_t* out = ring.data();
  const int row_vectors = (row_length + 15) / 16;
  const auto copy_row = [&](int y) {
    const uint8_t* row = image.ptr<uint8_t>(y) + xa;
    if (row + 16 * row_vectors <= image.dataend) {
      for (int j = 0; j < row_vectors; ++j) cv::v_store(out + 16 * j, cv::v_load(row + 16 * j));
    } else {
      std::memcpy(out, row, static_cast<size_t>(row_length));
    }
    out += row_length;
  };
  if (top) copy_row(cw.y - 1);
  if (bottom) copy_row(cw.y + cw.height);
  const size_t step = image.step[0];
  const uint8_t* p = image.ptr<uint8_t>(cw.y) + (cw.x - 1);
  if (left && right) {
    const int right_offset = cw.width + 1;
#pragma GCC unroll 2
    for (int i = 0; i < cw.height; ++i, p += step) {
      out[i] = p[0];
      out[cw.height + i] = p[right_offset];
    }
  } else if (left || right) {
    if (right) p += cw.width + 1;
    for (int i = 0; i < cw.height; ++i, p += step) out[i] = *p;
  }
  return most;
}

// The interquartile mean from counts of each value v in [low, high], each counted over the whole
// ring by one vector compare a 16 values (a lane counts at most `vectors` <= 255 matches). A small
// ring's values lie in a narrow range: ~16 counts of a few vectors each, where a histogram's
// increments of the same few bins wait on each other's stores.
double mean_by_vector_counts(const uint8_t* ring, size_t vectors, int64_t n, int low, int high) {
  const int64_t lo = n / 4, hi = std::max<int64_t>(n - n / 4, lo + 1);
  int64_t seen = 0, taken = lo, sum = 0;  // taken: ranks lo .. seen, hi at most
  for (int v = low; taken < hi && v <= high; ++v) {
    const cv::v_uint8x16 value = cv::v_setall_u8(static_cast<uint8_t>(v));
    cv::v_uint8x16 matches = cv::v_setzero_u8();
    for (size_t j = 0; j < vectors; ++j) {
      matches = cv::v_sub_wrap(matches, cv::v_load(ring + 16 * j) == value);  // 0xFF is -1
    }
    seen += cv::v_reduce_sad(matches, cv::v_setzero_u8());
    if (seen <= taken) continue;
    const int64_t now = std::min(seen, hi);
    sum += v * (now - taken);
    taken = now;
  }
  return static_cast<double>(sum) / static_cast<double>(hi - lo);
}

// Vector counts win while the range has at most this many values and the ring this many vectors.
constexpr int kMaxCountedRange = 24;
constexpr size_t kMaxCountedVectors = 32;

}  // namespace

double RingBackground::operator()(const cv::Mat& image, cv::Rect cw, cv::Rect window,
                                  int threshold) {
  if (threshold <= 0) return 0;  // every pixel is a blob's
  const size_t total = gather_ring(image, cw, window, ring_);
  uint8_t* const ring = ring_.data();
  // The lanes after the last value are 255, as if a blob's (>= threshold <= 255); with
  // threshold > 255 every pixel counts, the padding too, but it is not counted below.
  cv::v_store(ring + total, cv::v_setall_u8(255));
  const size_t vectors = (total + 15) / 16;
  const cv::v_uint8x16 t = cv::v_setall_u8(static_cast<uint8_t>(std::min(threshold, 255)));
  const cv::v_uint8x16 blobs_count = threshold > 255 ? cv::v_setzero_u8() : cv::v_setall_u8(255);
  cv::v_uint8x16 low = cv::v_setall_u8(255), high = cv::v_setzero_u8();
  cv::v_uint8x16 marked = cv::v_setzero_u8();  // per lane, how many were marked (mod 256)
  for (size_t j = 0; j < vectors; ++j) {
    const cv::v_uint8x16 x = cv::v_load(ring + 16 * j);
    const cv::v_uint8x16 bright = detail::bright_lanes(x, t) & blobs_count;  // x >= t
    cv::v_store(ring + 16 * j, x | bright);  // a blob's pixel: 255, never summed below
    low = cv::v_min(low, x);
    high = cv::v_max(high, x & ~bright);
    marked = cv::v_sub_wrap(marked, bright);  // 0xFF is -1
  }
  const int low_value = cv::v_reduce_min(low), high_value = cv::v_reduce_max(high);
  // Below the threshold (<= 255) every value that counts is < 255, the marked ones and the
  // padding 255: counting the values of [low, high] counts exactly the ring's.
  if (threshold <= 255 && vectors <= kMaxCountedVectors &&
      high_value - low_value < kMaxCountedRange) {
    const auto n =
        static_cast<int64_t>(16 * vectors - cv::v_reduce_sad(marked, cv::v_setzero_u8()));
    return n == 0 ? 0 : mean_by_vector_counts(ring, vectors, n, low_value, high_value);
  }
  // A histogram, then the sum a sort would give in one pass over [low, high] that leaves the
  // counts zero (bin 255 too, where the blobs' pixels went: how many do not count).
  int* const count = count_.data();  // a local pointer: the stores may not alias it
#pragma GCC unroll 8
  for (const uint8_t* p = ring; p != ring + total; ++p) ++count[*p];
  const size_t n = threshold > 255 ? total : total - static_cast<size_t>(count[255]);
  if (n == 0) {
    count[255] = 0;
    return 0;
  }
  const int64_t lo = static_cast<int64_t>(n / 4), hi = std::max<int64_t>(n - n / 4, lo + 1);
  int v = low_value;
  int64_t seen = 0;
  for (; seen + count[v] <= lo; ++v) {  // ranks below lo
    seen += count[v];
    count[v] = 0;
  }
  int64_t sum = 0;
  for (int64_t taken = lo; taken < hi; ++v) {  // taken: ranks lo .. seen, hi at most
    seen += count[v];
    count[v] = 0;
    const int64_t now = std::min(seen, hi);
    sum += v * (now - taken);
    taken = now;
  }
  for (; v <= high_value; ++v) count[v] = 0;
  count[255] = 0;
  return static_cast<double>(sum) / static_cast<double>(hi - lo);
}

}  // namespace syncap::edge
