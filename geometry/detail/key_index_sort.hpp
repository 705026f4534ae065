#pragma once
/// A sort of 32-bit keys that carry a 32-bit index each, for the steps that order many of them
/// (the merge of equal vertices by hash, a tile's vertices by id): neither the standard library
/// nor TBB has a radix sort, and std::sort of pairs was a seventh of the mesh job's cutting.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace geotex::detail {

/// A key in the high 32 bits and an index in the low: 8 bytes an item, so that the sort and
/// its buffer hold 16 bytes an item.
using KeyIndex = std::uint64_t;
constexpr int kIndexBits = 32;

inline KeyIndex key_index(std::uint32_t key, std::uint32_t index) {
    return (KeyIndex{key} << kIndexBits) | index;
}
inline std::uint32_t index_of(KeyIndex item) { return static_cast<std::uint32_t>(item); }
inline std::uint32_t key_of(KeyIndex item) {
    return static_cast<std::uint32_t>(item >> kIndexBits);
}

/// Stable LSD radix sort on the keys (the high 32 bits), 11 bits per pass; passes over a digit
/// that is the same in every key are skipped. Equal keys keep their order.
inline void sort_by_key(std::vector<KeyIndex>& items) {
    constexpr int kBits = 11;
    constexpr std::size_t kBuckets = std::size_t{1} << kBits;
    std::vector<KeyIndex> buffer(items.size());
    std::vector<std::size_t> count(kBuckets);
    for (int shift = kIndexBits; shift < 64; shift += kBits) {
        std::fill(count.begin(), count.end(), 0);
        for (const KeyIndex item : items) ++count[(item >> shift) & (kBuckets - 1)];
        if (std::find(count.begin(), count.end(), items.size()) != count.end()) continue;
        std::size_t sum = 0;
        for (std::size_t& c : count) {
            const std::size_t n = c;
            c = sum;
            sum += n;
        }
        for (const KeyIndex item : items) buffer[count[(item >> shift) & (kBuckets - 1)]++] = item;
        items.swap(buffer);
    }
}

}  // namespace geotex::detail
