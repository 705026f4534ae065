// PLY reader, written by hand rather than taken from CGAL::IO::read_PLY, because:
//  - CGAL's reader returns a bare bool: there is no place for the line, column or byte of
//    the problem, and our errors must say where the file is wrong;
//  - it stores face indices as size_t, so a negative index wraps to a huge value that later
//    crashes whoever trusts it;
//  - it sizes its containers from the header counts, so a header that lies (10^12 faces in
//    a 1 kB file) makes it allocate what the header says; here every declared count is
//    checked against the bytes that follow the header before anything is allocated;
//  - binary PLY is the format of big scans: the whole file is read into memory once and
//    parsed from a per-property plan, with no iostream call per value.
#include "geometry/detail/ply.hpp"

#include "geometry/detail/ply_parser.hpp"

namespace geotex::detail {
namespace ply {

MeshFile PlyParser::parse() {
    parse_header();
    assign_roles();
    check_sizes();
    allocate();
    switch (format_) {
        case Format::Ascii:
            parse_ascii();
            break;
        case Format::BinaryLittleEndian:
            if (host_is_little_endian()) {
                parse_binary<false>();
            } else {
                parse_binary<true>();
            }
            break;
        case Format::BinaryBigEndian:
            if (host_is_little_endian()) {
                parse_binary<true>();
            } else {
                parse_binary<false>();
            }
            break;
    }
    polygons_.finish();
    return std::move(out_);
}

void PlyParser::fail_truncated(const Element& e, std::uint64_t i) const {
    fail(element_place(e, i) + ": truncated at byte " + std::to_string(data_.size()));
}

void PlyParser::fail_at(const Place& place, const std::string& what) const {
    std::string where = element_place(place.element, place.index);
    if (place.at != nullptr) where += " (byte " + std::to_string(place.at - base_) + ")";
    fail(where + ": " + what, place.line, place.column);
}

void PlyParser::store_coordinate(Role role, double v, const Place& place) {
    const int axis = role == Role::X ? 0 : role == Role::Y ? 1 : 2;
    if (!std::isfinite(v)) {
        static const char* names[3] = {"x", "y", "z"};
        fail_at(place, std::string("non-finite coordinate ") + names[axis] + " = " +
                           (std::isnan(v) ? "nan"
                            : v > 0       ? "inf"
                                          : "-inf"));
    }
    polygons_.vertex_being_read()[axis] = v;  // the vertex of row place.index
}

void PlyParser::check_list_count(std::int64_t n, const Property& p, const Place& place) const {
    if (n < 0) {
        fail_at(place, "negative count " + std::to_string(n) + " for list '" + p.name + "'");
    }
    if (p.role == Role::Indices) {
        if (n < 3) {
            fail_at(place, "polygon with " + std::to_string(n) + " vertices (at least 3 needed)");
        }
        if (polygons_.num_corners() + static_cast<std::uint64_t>(n) > kMaxInt) {
            fail_at(place, "more than " + std::to_string(kMaxInt) + " face vertex indices");
        }
    }
}

void PlyParser::push_index(std::int64_t index, const Place& place) {
    if (index < 0 || index >= num_vertices_) {
        if (index < 0) fail_at(place, "negative vertex index " + std::to_string(index));
        fail_at(place, "vertex index " + std::to_string(index) + " out of range (the file has " +
                           std::to_string(num_vertices_) + " vertices)");
    }
    polygons_.corner(static_cast<int>(index));
}

}  // namespace ply

MeshFile read_ply(std::string_view data, const std::string& name, const PolygonSink& sink) {
    return ply::PlyParser(data, name, sink).parse();
}

}  // namespace geotex::detail
