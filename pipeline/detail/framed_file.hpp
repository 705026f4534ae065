#pragma once
// The layout the mesh files of a tiled run share (prepared_mesh.cpp, tile_mesh.cpp): a magic
// line, the length of a CBOR header as 8 little-endian bytes, the header (with the file's
// schema and the run's key), then raw little-endian arrays. The arrays are not in the CBOR so
// that they are read straight into their vectors a block at a time: a CBOR byte string would
// be held whole beside them while read.

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <istream>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "pipeline/detail/little_endian.hpp"

namespace geotex::detail {

using Cbor = nlohmann::json;  // the header, through the library's CBOR writer and reader

// A header is a few hundred bytes; a larger length is a damaged file, not a reason to
// allocate gigabytes.
inline constexpr std::uint64_t kMaxFramedHeader = 1 << 20;

/// Writes the magic line `magic` and `header`.
inline void write_framed_header(std::ostream& out, const std::string& magic, const Cbor& header) {
    const std::vector<std::uint8_t> bytes = Cbor::to_cbor(header);
    out.write(magic.data(), static_cast<std::streamsize>(magic.size()));
    std::uint8_t length[8];
    put_le(length, bytes.size(), 8);
    out.write(reinterpret_cast<const char*>(length), 8);
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
}

/// The header after the magic line `magic`, checked to be of schema `schema` and of the run
/// `key`. `kind` names the file in messages ("prepared mesh"). Throws InvalidInput.
inline Cbor read_framed_header(std::istream& in, const std::string& magic, const std::string& kind,
                               int schema, const std::string& key) {
    std::string head(magic.size(), '\0');
    if (!in.read(head.data(), static_cast<std::streamsize>(head.size())) || head != magic)
        throw InvalidInput("not a geotex " + kind);
    std::uint8_t length[8];
    if (!in.read(reinterpret_cast<char*>(length), 8))
        throw InvalidInput("damaged: the file ends in its header");
    const std::uint64_t size = get_le(length, 8);
    if (size > kMaxFramedHeader) throw InvalidInput("damaged: the header's length is wrong");
    std::vector<std::uint8_t> bytes(size);
    if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size)))
        throw InvalidInput("damaged: the file ends in its header");
    Cbor header;
    try {
        header = Cbor::from_cbor(bytes);
        if (header.at("schema").get<int>() != schema)
            throw InvalidInput("a " + kind + " of schema " + header.at("schema").dump() + ", not " +
                               std::to_string(schema) + " (made by another geotex)");
        if (header.at("key").get<std::string>() != key)
            throw InvalidInput("the " + kind +
                               " of another run: another mesh, other options, another number "
                               "of tiles or another geotex");
    } catch (const InvalidInput&) {
        throw;
    } catch (const std::exception& e) {
        throw InvalidInput(std::string("damaged header (") + e.what() + ")");
    }
    return header;
}

/// Checks that `in` holds exactly `expected` more bytes, so that a damaged count is an error
/// before its arrays are made, not an allocation of its size.
inline void expect_bytes_left(std::istream& in, std::uint64_t expected) {
    const std::istream::pos_type here = in.tellg();
    in.seekg(0, std::ios::end);
    const std::istream::pos_type end = in.tellg();
    in.seekg(here);
    if (here == std::istream::pos_type(-1) || end == std::istream::pos_type(-1))
        throw InvalidInput("cannot measure the file");
    const auto left = static_cast<std::uint64_t>(end - here);
    if (left < expected) throw InvalidInput("damaged: the file ends inside its arrays");
    if (left > expected) throw InvalidInput("damaged: bytes past the end of its arrays");
}

/// A point as the bits of its three coordinates in the header, so that it reads back exactly.
inline Cbor bits_of(const Eigen::Vector3d& p) {
    return {bits_of(p.x()), bits_of(p.y()), bits_of(p.z())};
}

/// The point of bits_of. Throws what nlohmann_json throws on a value that is not one.
inline Eigen::Vector3d point_of(const Cbor& bits) {
    return {double_of(bits.at(0).get<std::uint64_t>()), double_of(bits.at(1).get<std::uint64_t>()),
            double_of(bits.at(2).get<std::uint64_t>())};
}

// Values are packed a block at a time, so that neither side holds a second copy of an array.
inline constexpr std::size_t kBlockValues = 1 << 16;

/// Writes `count` values, value(i) giving the i-th as its bits, each `size` bytes.
template <class Fn>
void write_values(std::ostream& out, std::size_t count, std::size_t size, Fn&& value) {
    std::vector<std::uint8_t> block(kBlockValues * size);
    for (std::size_t begin = 0; begin < count; begin += kBlockValues) {
        const std::size_t n = std::min(kBlockValues, count - begin);
        for (std::size_t i = 0; i < n; ++i) put_le(&block[i * size], value(begin + i), size);
        out.write(reinterpret_cast<const char*>(block.data()),
                  static_cast<std::streamsize>(n * size));
    }
}

/// Reads `count` values of `size` bytes, handing each to take(i, bits).
template <class Fn>
void read_values(std::istream& in, std::size_t count, std::size_t size, Fn&& take) {
    std::vector<std::uint8_t> block(std::min(count, kBlockValues) * size);
    for (std::size_t begin = 0; begin < count; begin += kBlockValues) {
        const std::size_t n = std::min(kBlockValues, count - begin);
        if (!in.read(reinterpret_cast<char*>(block.data()), static_cast<std::streamsize>(n * size)))
            throw InvalidInput("damaged: the file ends inside its arrays");
        for (std::size_t i = 0; i < n; ++i) take(begin + i, get_le(&block[i * size], size));
    }
}

}  // namespace geotex::detail
