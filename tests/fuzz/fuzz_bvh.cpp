// libFuzzer target: the BVH motion file reader (body::parse_bvh, which load_bvh and the
// simulator's person phases use), on the input as the file's text.
//
// Contract: the reader returns a motion or throws body::BvhError, nothing else; what it accepts
// is consistent: parents before children, channels numbered without gaps, frame_count rows of
// channel_count values, and every frame(k) of it readable.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "body/bvh.hpp"
#include "fuzz_check.hpp"

namespace {

using syncap::fuzz::check;

void check_motion(const syncap::body::Bvh& bvh) {
  check(!bvh.joints.empty() && bvh.joints.front().parent == -1, "the first joint is not a root");
  int channel = 0;
  for (std::size_t j = 0; j < bvh.joints.size(); ++j) {
    const auto& joint = bvh.joints[j];
    check(j == 0 || (joint.parent >= 0 && static_cast<std::size_t>(joint.parent) < j),
          "a joint's parent does not come before it");
    check(joint.first_channel == channel || joint.channels.empty(),
          "channels are not numbered in order");
    channel += static_cast<int>(joint.channels.size());
  }
  check(channel == bvh.channel_count, "channel_count differs from the joints' channels");
  check(
      bvh.frame_count >= 0 && bvh.values.size() == static_cast<std::size_t>(bvh.frame_count) *
                                                       static_cast<std::size_t>(bvh.channel_count),
      "values are not frame_count rows of channel_count");
  for (int k = 0; k < bvh.frame_count; ++k) {
    check(bvh.frame(k).size() == static_cast<std::size_t>(bvh.channel_count),
          "a frame's size is wrong");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  syncap::body::Bvh bvh;
  if (syncap::fuzz::decodes<syncap::body::BvhError>(
          "parse_bvh", [&] { bvh = syncap::body::parse_bvh(text, "motion.bvh"); })) {
    check_motion(bvh);
  }
  return 0;
}
