// ASCII PLY bodies: tokens with their line and column.

#include "geometry/detail/ply_parser.hpp"
#include "geometry/detail/read_window.hpp"
#include "geometry/work_progress.hpp"

namespace geotex::detail::ply {

PlyParser::AsciiToken PlyParser::next_token() {
    while (pos_ < data_.size()) {
        const char c = data_[pos_];
        if (c == '\n') {
            ++line_;
            line_start_ = pos_ + 1;
        } else if (c != ' ' && c != '\t' && c != '\r' && c != '\f' && c != '\v') {
            break;
        }
        ++pos_;
    }
    AsciiToken t;
    t.line = line_;
    t.column = static_cast<long>(pos_ - line_start_) + 1;
    const std::size_t start = pos_;
    while (pos_ < data_.size()) {
        const char c = data_[pos_];
        if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v') break;
        ++pos_;
    }
    t.text = data_.substr(start, pos_ - start);
    return t;
}

PlyParser::AsciiToken PlyParser::expect_token(const Element& e, std::uint64_t i, const Property& p,
                                              const char* what) {
    AsciiToken t = next_token();
    if (t.text.empty()) {
        fail(element_place(e, i) + ": end of file where " + what + " of '" + p.name +
                 "' was expected",
             t.line, t.column);
    }
    return t;
}

std::int64_t PlyParser::ascii_int(const AsciiToken& t, const Element& e, std::uint64_t i,
                                  const Property& p) const {
    const char* first = t.text.data();
    const char* last = first + t.text.size();
    if (first != last && *first == '+') ++first;
    std::int64_t v = 0;
    const auto res = std::from_chars(first, last, v);
    if (res.ec != std::errc() || res.ptr != last) {
        fail(element_place(e, i) + ": expected an integer for '" + p.name + "', got '" +
                 printable(t.text) + "'",
             t.line, t.column);
    }
    return v;
}

double PlyParser::ascii_number(const AsciiToken& t, Type type, const Element& e, std::uint64_t i,
                               const Property& p) const {
    if (is_integer(type)) return static_cast<double>(ascii_int(t, e, i, p));
    const char* first = t.text.data();
    const char* last = first + t.text.size();
    if (first != last && *first == '+') ++first;
    double value = 0.0;
    std::from_chars_result res{};
    if (type == Type::Float32) {
        // Parsed as float so that a float written in shortest form reads back exactly.
        float f = 0.0F;
        res = std::from_chars(first, last, f);
        value = f;
        if (res.ec == std::errc::result_out_of_range) {
            // Underflow is a tiny value, not an error; overflow stays an error.
            double d = 0.0;
            const auto res_d = std::from_chars(first, last, d);
            if (res_d.ec == std::errc() && std::abs(d) < 1.0) {
                res = res_d;
                value = static_cast<float>(d);
            }
        }
    } else {
        res = std::from_chars(first, last, value);
    }
    if (res.ec == std::errc::result_out_of_range && res.ptr == last) {
        fail(element_place(e, i) + ": number '" + printable(t.text) + "' for '" + p.name +
                 "' is out of range for " + type_name(type),
             t.line, t.column);
    }
    if (res.ec != std::errc() || res.ptr != last) {
        fail(element_place(e, i) + ": expected a number for '" + p.name + "', got '" +
                 printable(t.text) + "'",
             t.line, t.column);
    }
    return value;
}

void PlyParser::parse_ascii() {
    pos_ = body_offset_;
    line_ = body_line_;
    line_start_ = body_offset_;
    // The bytes read, for a progress line on a large file (work_progress.hpp).
    LoopMeter meter(static_cast<long long>(data_.size() - body_offset_));
    std::size_t reported = body_offset_;
    for (const Element& e : elements_) {
        if (e.properties.empty()) continue;
        const bool vertices = &e == vertex_element_;
        for (std::uint64_t i = 0; i < e.count; ++i) {
            if ((i & 65535) == 65535) {
                meter.add(static_cast<long long>(pos_ - reported));
                reported = pos_;
                release_read(data_.data() + line_start_);
            }
            if (vertices) polygons_.new_vertex();
            for (const Property& prop : e.properties) {
                if (!prop.is_list) {
                    const AsciiToken t = expect_token(e, i, prop, "the value");
                    const double v = ascii_number(t, prop.type, e, i, prop);
                    switch (prop.role) {
                        case Role::X:
                        case Role::Y:
                        case Role::Z:
                            store_coordinate(prop.role, v, Place{e, i, nullptr, t.line, t.column});
                            break;
                        case Role::FaceScalar:
                            out_.face_properties[prop.face_scalar].values.push_back(v);
                            break;
                        case Role::Skip:
                        case Role::Indices:
                            break;
                    }
                    continue;
                }
                const AsciiToken ct = expect_token(e, i, prop, "the item count");
                const std::int64_t n = ascii_int(ct, e, i, prop);
                check_list_count(n, prop, Place{e, i, nullptr, ct.line, ct.column});
                for (std::int64_t j = 0; j < n; ++j) {
                    const AsciiToken t = expect_token(e, i, prop, "an item");
                    if (prop.role == Role::Indices) {
                        push_index(ascii_int(t, e, i, prop),
                                   Place{e, i, nullptr, t.line, t.column});
                    } else {
                        ascii_number(t, prop.type, e, i, prop);
                    }
                }
                if (prop.role == Role::Indices) {
                    polygons_.end_polygon();
                }
            }
        }
    }
    // Text past the declared elements: the header's counts are wrong (see parse_binary).
    const AsciiToken extra = next_token();
    if (!extra.text.empty()) {
        fail("'" + printable(extra.text) +
                 "' after the last declared element: the file holds more than its header's "
                 "counts (" +
                 declared_counts() + ") describe",
             extra.line, extra.column);
    }
}

}  // namespace geotex::detail::ply
