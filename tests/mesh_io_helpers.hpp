#pragma once
// Helpers shared by the mesh reader tests.

#include <catch2/catch.hpp>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "geometry/mesh_io.hpp"

namespace geotex::test {

// A tetrahedron whose coordinates are not all floats (0.1 is not), faces outward.
inline Mesh tetrahedron(double a = 0.1) {
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, a}};
    m.faces = {{{0, 2, 1}}, {{0, 1, 3}}, {{0, 3, 2}}, {{1, 2, 3}}};
    return m;
}

inline std::string to_ply(const Mesh& m, bool binary, const std::vector<FaceAttribute>& attrs = {},
                          const std::vector<std::string>& comments = {}) {
    std::ostringstream out;
    PlyWriteOptions options;
    options.binary = binary;
    options.comments = comments;
    write_ply(out, m, attrs, options);
    return out.str();
}

// The soup's polygons as vectors, for comparisons.
inline std::vector<std::vector<int>> polygons(const PolygonSoup& s) {
    std::vector<std::vector<int>> out;
    for (int p = 0; p < s.num_polygons(); ++p) {
        out.emplace_back(s.face_indices.begin() + s.face_offsets[p],
                         s.face_indices.begin() + s.face_offsets[p + 1]);
    }
    return out;
}

inline std::vector<std::vector<int>> polygons(const Mesh& m) {
    std::vector<std::vector<int>> out;
    for (const auto& f : m.faces) out.push_back({f[0], f[1], f[2]});
    return out;
}

// The ParseError that reading `data` as `name` throws.
inline ParseError parse_error(const std::string& data, const std::string& name) {
    try {
        read_mesh_memory(data, name);
    } catch (const ParseError& e) {
        return e;
    }
    FAIL("no ParseError for " << name);
    return ParseError("unreachable");
}

inline bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// Big-endian and little-endian bytes of a value, whatever the host.
template <typename T>
inline void put(std::string& s, T value, bool big_endian) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &value, sizeof(T));
    const std::uint16_t probe = 1;
    unsigned char host_first = 0;
    std::memcpy(&host_first, &probe, 1);
    const bool host_little = host_first == 1;
    for (std::size_t i = 0; i < sizeof(T); ++i) {
        const std::size_t j = (host_little == !big_endian) ? i : sizeof(T) - 1 - i;
        s += static_cast<char>(b[j]);
    }
}

inline const char* const kTriangleHeader =
    "ply\n"
    "format ascii 1.0\n"
    "element vertex 3\n"
    "property float x\n"
    "property float y\n"
    "property float z\n"
    "element face 1\n"
    "property list uchar int vertex_indices\n"
    "end_header\n";

}  // namespace geotex::test
