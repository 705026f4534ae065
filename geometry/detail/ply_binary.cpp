// Binary PLY bodies (either byte order), read from a per-property plan.

#include "geometry/detail/ply_parser.hpp"
#include "geometry/detail/read_window.hpp"

namespace geotex::detail::ply {

template <bool Swap>
void PlyParser::parse_binary() {
    base_ = reinterpret_cast<const unsigned char*>(data_.data());
    const unsigned char* p = base_ + body_offset_;
    const unsigned char* const end = base_ + data_.size();
    for (const Element& e : elements_) {
        if (e.properties.empty()) continue;
        bool fixed = true;
        bool needed = false;
        std::size_t stride = 0;
        for (const Property& prop : e.properties) {
            fixed = fixed && !prop.is_list;
            needed = needed || prop.role != Role::Skip;
            if (!prop.is_list) stride += type_size(prop.type);
        }
        if (fixed) {
            // Fixed-size records: one bounds check for the whole element.
            const std::uint64_t left = static_cast<std::uint64_t>(end - p);
            if (mul_sat(e.count, stride) > left) fail_truncated(e, left / stride);
            if (needed) parse_fixed_element<Swap>(e, p);
            p += e.count * stride;
        } else {
            p = parse_variable_element<Swap>(e, p, end);
        }
    }
    // Bytes past the declared elements mean the header's counts are wrong and part of
    // the mesh would be dropped silently; a final line break is tolerated.
    const unsigned char* rest = p;
    while (rest != end && (*rest == '\n' || *rest == '\r' || *rest == ' ')) ++rest;
    if (rest != end) {
        fail(std::to_string(end - p) + " bytes after the last declared element (from byte " +
             std::to_string(p - base_) + "): the file holds more than its header's counts (" +
             declared_counts() + ") describe");
    }
}

template <bool Swap>
void PlyParser::store_scalar(const Property& prop, const Element& e, std::uint64_t i,
                             const unsigned char* p) {
    switch (prop.role) {
        case Role::X:
        case Role::Y:
        case Role::Z:
            store_coordinate(prop.role, load_double<Swap>(prop.type, p), Place{e, i, p, 0, 0});
            break;
        case Role::FaceScalar:
            out_.face_properties[prop.face_scalar].values.push_back(
                load_double<Swap>(prop.type, p));
            break;
        case Role::Skip:
        case Role::Indices:
            break;
    }
}

template <bool Swap>
void PlyParser::parse_fixed_element(const Element& e, const unsigned char* p) {
    const bool vertices = &e == vertex_element_;
    for (std::uint64_t i = 0; i < e.count; ++i) {
        if ((i & 65535) == 65535) release_read(p);
        if (vertices) polygons_.new_vertex();
        for (const Property& prop : e.properties) {
            store_scalar<Swap>(prop, e, i, p);
            p += type_size(prop.type);
        }
    }
}

template <bool Swap>
const unsigned char* PlyParser::parse_variable_element(const Element& e, const unsigned char* p,
                                                       const unsigned char* end) {
    const bool vertices = &e == vertex_element_;
    for (std::uint64_t i = 0; i < e.count; ++i) {
        if ((i & 65535) == 65535) release_read(p);
        if (vertices) polygons_.new_vertex();
        for (const Property& prop : e.properties) {
            if (!prop.is_list) {
                const std::size_t size = type_size(prop.type);
                if (static_cast<std::size_t>(end - p) < size) fail_truncated(e, i);
                store_scalar<Swap>(prop, e, i, p);
                p += size;
                continue;
            }
            const std::size_t count_size = type_size(prop.count_type);
            if (static_cast<std::size_t>(end - p) < count_size) fail_truncated(e, i);
            const std::int64_t n = load_int<Swap>(prop.count_type, p);
            check_list_count(n, prop, Place{e, i, p, 0, 0});
            p += count_size;
            const std::size_t item_size = type_size(prop.type);
            if (static_cast<std::uint64_t>(n) > static_cast<std::uint64_t>(end - p) / item_size) {
                fail_truncated(e, i);
            }
            if (prop.role == Role::Indices) {
                for (std::int64_t j = 0; j < n; ++j) {
                    push_index(load_int<Swap>(prop.type, p), Place{e, i, p, 0, 0});
                    p += item_size;
                }
                polygons_.end_polygon();
            } else {
                p += static_cast<std::size_t>(n) * item_size;
            }
        }
    }
    return p;
}

// parse() picks the byte swap at run time.
template void PlyParser::parse_binary<false>();
template void PlyParser::parse_binary<true>();

}  // namespace geotex::detail::ply
