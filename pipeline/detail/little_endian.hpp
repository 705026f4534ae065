#pragma once
// Numbers as little-endian bytes whatever the machine's order, for the files the jobs of a
// tiled run share (tile_parts.cpp, prepared_mesh.cpp): a cluster's nodes need not share one
// order.

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace geotex::detail {

/// Writes the low `size` bytes of `bits` (size <= 8) to `out`, least significant first.
inline void put_le(std::uint8_t* out, std::uint64_t bits, std::size_t size) {
    for (std::size_t k = 0; k < size; ++k) out[k] = static_cast<std::uint8_t>(bits >> (8 * k));
}

/// The `size` bytes at `in` (size <= 8), least significant first.
inline std::uint64_t get_le(const std::uint8_t* in, std::size_t size) {
    std::uint64_t bits = 0;
    for (std::size_t k = 0; k < size; ++k) bits |= static_cast<std::uint64_t>(in[k]) << (8 * k);
    return bits;
}

/// A double's bits, and back: what put_le and get_le carry for a double.
inline std::uint64_t bits_of(double x) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &x, 8);
    return bits;
}

inline double double_of(std::uint64_t bits) {
    double x = 0;
    std::memcpy(&x, &bits, 8);
    return x;
}

}  // namespace geotex::detail
