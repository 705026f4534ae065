// The PLY header: elements, properties and their roles, and every declared count checked
// against the bytes that follow before anything is allocated.

#include "geometry/detail/ply_parser.hpp"

namespace geotex::detail::ply {

bool PlyParser::next_line(std::string_view& line) {
    if (!detail::next_line(data_, pos_, line)) return false;
    ++line_;
    return true;
}

std::uint64_t PlyParser::parse_count(const TextToken& t) const {
    std::uint64_t value = 0;
    const char* first = t.text.data();
    const char* last = first + t.text.size();
    const bool digits_only =
        !t.text.empty() && t.text.find_first_not_of("0123456789") == std::string_view::npos;
    const auto res = std::from_chars(first, last, value);
    if (!digits_only || res.ptr != last) {
        fail("element count must be a non-negative integer, got '" + printable(t.text) + "'", line_,
             t.column);
    }
    if (res.ec == std::errc::result_out_of_range) {
        fail("element count '" + printable(t.text) + "' is too large", line_, t.column);
    }
    return value;
}

Type PlyParser::parse_type_token(const TextToken& t) const {
    Type type{};
    if (!parse_type(t.text, type)) {
        fail("unknown property type '" + printable(t.text) +
                 "' (expected char, uchar, short, ushort, int, uint, float, double or "
                 "int8, uint8, int16, uint16, int32, uint32, float32, float64)",
             line_, t.column);
    }
    return type;
}

void PlyParser::parse_header() {
    std::string_view line;
    if (!next_line(line) || line != "ply") {
        fail("not a PLY file: the first line is not 'ply'", 1, 1);
    }
    bool have_format = false;
    for (;;) {
        if (!next_line(line)) {
            fail("end of file in the header: 'end_header' is missing", line_, 0);
        }
        const std::vector<TextToken> tokens = split_tokens(line, false);
        if (tokens.empty()) continue;
        const std::string_view keyword = tokens[0].text;
        if (keyword == "comment" || keyword == "obj_info") continue;
        if (keyword == "format") {
            if (have_format) fail("a second 'format' line", line_, 1);
            if (tokens.size() != 3) {
                fail(
                    "malformed format line (expected 'format <ascii|binary_little_endian|"
                    "binary_big_endian> 1.0')",
                    line_, 1);
            }
            if (tokens[1].text == "ascii") {
                format_ = Format::Ascii;
            } else if (tokens[1].text == "binary_little_endian") {
                format_ = Format::BinaryLittleEndian;
            } else if (tokens[1].text == "binary_big_endian") {
                format_ = Format::BinaryBigEndian;
            } else {
                fail("unknown PLY format '" + printable(tokens[1].text) +
                         "' (expected ascii, binary_little_endian or binary_big_endian)",
                     line_, tokens[1].column);
            }
            if (tokens[2].text != "1.0") {
                fail("unsupported PLY version '" + printable(tokens[2].text) + "' (expected 1.0)",
                     line_, tokens[2].column);
            }
            have_format = true;
        } else if (keyword == "element") {
            if (!have_format) fail("'element' before the 'format' line", line_, 1);
            if (tokens.size() != 3) {
                fail("malformed element line (expected 'element <name> <count>')", line_, 1);
            }
            Element e;
            e.name = std::string(tokens[1].text);
            e.count = parse_count(tokens[2]);
            e.line = line_;
            e.count_column = tokens[2].column;
            for (const Element& other : elements_) {
                if (other.name == e.name) {
                    fail("a second element named '" + printable(e.name) + "'", line_,
                         tokens[1].column);
                }
            }
            elements_.push_back(std::move(e));
        } else if (keyword == "property") {
            if (elements_.empty()) fail("'property' before any 'element'", line_, 1);
            Property p;
            p.line = line_;
            if (tokens.size() >= 2 && tokens[1].text == "list") {
                if (tokens.size() != 5) {
                    fail(
                        "malformed list property (expected 'property list <count type> "
                        "<item type> <name>')",
                        line_, 1);
                }
                p.is_list = true;
                p.count_type = parse_type_token(tokens[2]);
                p.type = parse_type_token(tokens[3]);
                p.name = std::string(tokens[4].text);
                p.column = tokens[4].column;
                if (!is_integer(p.count_type)) {
                    fail("list property '" + printable(p.name) + "' has count type " +
                             type_name(p.count_type) + ", which is not an integer type",
                         line_, tokens[2].column);
                }
            } else {
                if (tokens.size() != 3) {
                    fail("malformed property line (expected 'property <type> <name>')", line_, 1);
                }
                p.type = parse_type_token(tokens[1]);
                p.name = std::string(tokens[2].text);
                p.column = tokens[2].column;
            }
            elements_.back().properties.push_back(std::move(p));
        } else if (keyword == "end_header") {
            if (tokens.size() != 1) {
                fail("unexpected text after 'end_header'", line_, tokens[1].column);
            }
            break;
        } else {
            std::string hint;
            const char c = keyword[0];
            if ((c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.') {
                hint = "; is 'end_header' missing?";
            }
            fail("unknown header keyword '" + printable(keyword) +
                     "' (expected comment, obj_info, format, element, property or "
                     "end_header" +
                     hint + ")",
                 line_, tokens[0].column);
        }
    }
    if (!have_format) fail("the header has no 'format' line", 2, 1);
    body_offset_ = pos_;
    body_line_ = line_ + 1;
}

void PlyParser::assign_roles() {
    Element* vertex = nullptr;
    Element* face = nullptr;
    for (Element& e : elements_) {
        if (e.name == "vertex") vertex = &e;
        if (e.name == "face") face = &e;
    }
    if (vertex == nullptr) fail("the header declares no 'vertex' element");
    const char* axes[3] = {"x", "y", "z"};
    const Role roles[3] = {Role::X, Role::Y, Role::Z};
    for (int k = 0; k < 3; ++k) {
        Property* found = nullptr;
        for (Property& p : vertex->properties) {
            if (p.name == axes[k]) {
                found = &p;
                break;
            }
        }
        if (found == nullptr) {
            fail(std::string("the vertex element has no '") + axes[k] + "' property", vertex->line,
                 1);
        }
        if (found->is_list) {
            fail(std::string("vertex property '") + axes[k] + "' is a list, not a number",
                 found->line, found->column);
        }
        found->role = roles[k];
    }
    if (face == nullptr || face->count == 0) {
        fail(
            "the file has no faces (a point cloud?): a mesh needs a 'face' element with a "
            "'vertex_indices' list",
            face == nullptr ? 0 : face->line, face == nullptr ? 0 : face->count_column);
    }
    Property* indices = nullptr;
    for (Property& p : face->properties) {
        if (indices == nullptr && (p.name == "vertex_indices" || p.name == "vertex_index")) {
            indices = &p;
        } else if (!p.is_list && keep_face_scalars_) {
            p.role = Role::FaceScalar;
            p.face_scalar = static_cast<int>(out_.face_properties.size());
            out_.face_properties.push_back({p.name, {}});
        }
    }
    if (indices == nullptr) {
        fail("the face element has no 'vertex_indices' (or 'vertex_index') list property",
             face->line, 1);
    }
    if (!indices->is_list) {
        fail("face property '" + indices->name + "' must be a list", indices->line,
             indices->column);
    }
    if (!is_integer(indices->type)) {
        fail("face property '" + indices->name + "' has item type " + type_name(indices->type) +
                 ", which is not an integer type",
             indices->line, indices->column);
    }
    indices->role = Role::Indices;
    vertex_element_ = vertex;
    face_element_ = face;
}

void PlyParser::check_sizes() const {
    const std::uint64_t available = data_.size() - body_offset_;
    const bool ascii = format_ == Format::Ascii;
    std::uint64_t used = 0;
    for (const Element& e : elements_) {
        std::uint64_t element_min = 0;
        for (const Property& p : e.properties) {
            const std::uint64_t items = p.role == Role::Indices ? 3 : 0;
            if (ascii) {
                element_min = 2;
            } else if (p.is_list) {
                element_min += type_size(p.count_type) + items * type_size(p.type);
            } else {
                element_min += type_size(p.type);
            }
        }
        const std::uint64_t need = mul_sat(e.count, element_min);
        // The last ASCII value needs no separator after it.
        const std::uint64_t slack = ascii ? 1 : 0;
        if (need > 0 && add_sat(used, need) > add_sat(available, slack)) {
            const std::uint64_t left = available > used ? available - used : 0;
            fail((ascii ? std::string() : locate_truncation() + "; ") + "the header declares " +
                     std::to_string(e.count) + " '" + printable(e.name) +
                     "' elements, which need at least " +
                     (need == std::numeric_limits<std::uint64_t>::max() ? std::string("2^64")
                                                                        : std::to_string(need)) +
                     " bytes of " + (ascii ? "ASCII" : "binary") + " data, but only " +
                     std::to_string(left) + " bytes remain in the file",
                 e.line, e.count_column);
        }
        used = add_sat(used, need);
    }
    if (vertex_element_->count > kMaxInt) {
        fail("too many vertices: " + std::to_string(vertex_element_->count) + " (at most " +
                 std::to_string(kMaxInt) + ")",
             vertex_element_->line, vertex_element_->count_column);
    }
    if (face_element_->count > kMaxInt) {
        fail("too many faces: " + std::to_string(face_element_->count) + " (at most " +
                 std::to_string(kMaxInt) + ")",
             face_element_->line, face_element_->count_column);
    }
}

std::string PlyParser::locate_truncation() const {
    const bool swap = (format_ == Format::BinaryBigEndian) == host_is_little_endian();
    const auto* p = reinterpret_cast<const unsigned char*>(data_.data()) + body_offset_;
    const auto* const end = reinterpret_cast<const unsigned char*>(data_.data()) + data_.size();
    const std::string at = ": truncated at byte " + std::to_string(data_.size());
    for (const Element& e : elements_) {
        if (e.properties.empty()) continue;
        for (std::uint64_t i = 0; i < e.count; ++i) {
            for (const Property& prop : e.properties) {
                const std::size_t size = type_size(prop.is_list ? prop.count_type : prop.type);
                if (static_cast<std::size_t>(end - p) < size) return element_place(e, i) + at;
                if (!prop.is_list) {
                    p += size;
                    continue;
                }
                const std::int64_t n =
                    swap ? load_int<true>(prop.count_type, p) : load_int<false>(prop.count_type, p);
                p += size;
                const std::size_t item = type_size(prop.type);
                if (n < 0 ||
                    static_cast<std::uint64_t>(n) > static_cast<std::uint64_t>(end - p) / item) {
                    return element_place(e, i) + at;
                }
                p += static_cast<std::size_t>(n) * item;
            }
        }
    }
    return "truncated at byte " + std::to_string(data_.size());
}

void PlyParser::allocate() {
    num_vertices_ = static_cast<std::int64_t>(vertex_element_->count);
    std::uint64_t num_faces = face_element_->count;
    if (format_ == Format::Ascii) {
        // The 2-byte bound lets a lying ASCII header through with counts up to half the
        // file size; reserve no more than the text can hold ("0 0 0\n" per vertex,
        // "3 0 0 0\n" per face) and let the vectors grow if it really holds more.
        const std::uint64_t remaining = data_.size() - body_offset_;
        polygons_.reserve_vertices(
            std::min<std::uint64_t>(vertex_element_->count, remaining / 6 + 1));
        num_faces = std::min<std::uint64_t>(num_faces, remaining / 8 + 1);
    } else {
        // Reserved, not filled: each vertex's page is touched as the parse reaches it, when the
        // file's bytes behind it are given back, rather than all at once beside the whole file
        // (sphere-1 level 10: 777 MB held at the start of the parse, 525 after).
        polygons_.reserve_vertices(vertex_element_->count);
    }
    polygons_.reserve(num_faces, 3 * num_faces);
    for (FaceProperty& fp : out_.face_properties) fp.values.reserve(num_faces);
    switch (format_) {
        case Format::Ascii:
            out_.format = "ply-ascii";
            break;
        case Format::BinaryLittleEndian:
            out_.format = "ply-binary-le";
            break;
        case Format::BinaryBigEndian:
            out_.format = "ply-binary-be";
            break;
    }
}

std::string PlyParser::declared_counts() const {
    std::string out;
    for (const Element& e : elements_) {
        if (e.properties.empty()) continue;
        if (!out.empty()) out += ", ";
        out += std::to_string(e.count) + " " + printable(e.name);
    }
    return out;
}

std::string PlyParser::element_place(const Element& e, std::uint64_t i) const {
    return printable(e.name) + " " + std::to_string(i) + " of " + std::to_string(e.count);
}

}  // namespace geotex::detail::ply
