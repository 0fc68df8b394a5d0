// Splitting a message's items (blobs, markers) into datagram-sized parts and joining them: the
// arithmetic both blob_frame_t and marker_frame_t share. Items is a pointer to the message's item
// vector; the caller sets the per-part counts (num_*, total_*, part_index, part_count).
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

namespace syncap::proto::detail {

// Parts of at most `per_part` items (one part when there are none), each a copy of `whole` with
// its share of the items; `set_counts(part, index, count, items_in_part)` fills the counts.
template <class Message, class Item, class SetCounts>
std::vector<Message> split_items(const Message& whole, std::vector<Item> Message::*items,
                                 std::size_t per_part, SetCounts set_counts) {
  const std::vector<Item>& all = whole.*items;
  const std::size_t count = std::max<std::size_t>(1, (all.size() + per_part - 1) / per_part);
  std::vector<Message> parts;
  parts.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    Message part = whole;
    const std::size_t begin = i * per_part;
    const std::size_t end = std::min(all.size(), begin + per_part);
    (part.*items)
        .assign(all.begin() + static_cast<std::ptrdiff_t>(begin),
                all.begin() + static_cast<std::ptrdiff_t>(end));
    set_counts(part, i, count, end - begin);
    parts.push_back(std::move(part));
  }
  return parts;
}

// The first part with every part's items, in order.
template <class Message, class Item>
Message join_items(std::span<const Message> parts, std::vector<Item> Message::*items) {
  Message whole = parts.front();
  (whole.*items).clear();
  for (const Message& part : parts)
    (whole.*items).insert((whole.*items).end(), (part.*items).begin(), (part.*items).end());
  return whole;
}

}  // namespace syncap::proto::detail
