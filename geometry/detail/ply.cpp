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

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

#include "geometry/detail/text.hpp"
#include "geometry/errors.hpp"

namespace geotex::detail {
namespace {

constexpr std::uint64_t kMaxInt = static_cast<std::uint64_t>(std::numeric_limits<int>::max());

enum class Type : std::uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::size_t type_size(Type t) {
    switch (t) {
        case Type::Int8:
        case Type::UInt8:
            return 1;
        case Type::Int16:
        case Type::UInt16:
            return 2;
        case Type::Int32:
        case Type::UInt32:
        case Type::Float32:
            return 4;
        case Type::Float64:
            return 8;
    }
    return 0;
}

bool is_integer(Type t) { return t != Type::Float32 && t != Type::Float64; }

const char* type_name(Type t) {
    switch (t) {
        case Type::Int8:
            return "char";
        case Type::UInt8:
            return "uchar";
        case Type::Int16:
            return "short";
        case Type::UInt16:
            return "ushort";
        case Type::Int32:
            return "int";
        case Type::UInt32:
            return "uint";
        case Type::Float32:
            return "float";
        case Type::Float64:
            return "double";
    }
    return "?";
}

bool parse_type(std::string_view s, Type& t) {
    struct Entry {
        const char* name;
        Type type;
    };
    static const Entry entries[] = {
        {"char", Type::Int8},      {"int8", Type::Int8},       {"uchar", Type::UInt8},
        {"uint8", Type::UInt8},    {"short", Type::Int16},     {"int16", Type::Int16},
        {"ushort", Type::UInt16},  {"uint16", Type::UInt16},   {"int", Type::Int32},
        {"int32", Type::Int32},    {"uint", Type::UInt32},     {"uint32", Type::UInt32},
        {"float", Type::Float32},  {"float32", Type::Float32}, {"double", Type::Float64},
        {"float64", Type::Float64}};
    for (const Entry& e : entries) {
        if (s == e.name) {
            t = e.type;
            return true;
        }
    }
    return false;
}

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };

// What the reader does with a property's values.
enum class Role : std::uint8_t { Skip, X, Y, Z, Indices, FaceScalar };

struct Property {
    std::string name;
    bool is_list = false;
    Type type = Type::Float32;      // scalar type, or the type of a list's items
    Type count_type = Type::UInt8;  // lists only
    Role role = Role::Skip;
    int face_scalar = -1;  // index into MeshFile::face_properties for Role::FaceScalar
    long line = 0;
    long column = 0;
};

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> properties;
    long line = 0;
    long count_column = 0;
};

// a * b, saturating at the largest uint64.
std::uint64_t mul_sat(std::uint64_t a, std::uint64_t b) {
    if (a != 0 && b > std::numeric_limits<std::uint64_t>::max() / a) {
        return std::numeric_limits<std::uint64_t>::max();
    }
    return a * b;
}

std::uint64_t add_sat(std::uint64_t a, std::uint64_t b) {
    return b > std::numeric_limits<std::uint64_t>::max() - a
               ? std::numeric_limits<std::uint64_t>::max()
               : a + b;
}

class PlyParser {
  public:
    PlyParser(std::string_view data, const std::string& name) : data_(data), name_(name) {}

    MeshFile parse() {
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
        out_.soup.face_offsets = std::move(face_offsets_);
        out_.soup.face_indices = std::move(face_indices_);
        return std::move(out_);
    }

  private:
    static bool host_is_little_endian() {
        const std::uint16_t probe = 1;
        unsigned char first = 0;
        std::memcpy(&first, &probe, 1);
        return first == 1;
    }

    [[noreturn]] void fail(const std::string& message, long line = 0, long column = 0) const {
        throw ParseError(message, name_, line, column);
    }

    // ---- header ------------------------------------------------------------------------

    // Next header line without its end of line ("\n" or "\r\n"); false at end of data.
    bool next_line(std::string_view& line) {
        if (!detail::next_line(data_, pos_, line)) return false;
        ++line_;
        return true;
    }

    std::uint64_t parse_count(const TextToken& t) const {
        std::uint64_t value = 0;
        const char* first = t.text.data();
        const char* last = first + t.text.size();
        const bool digits_only =
            !t.text.empty() && t.text.find_first_not_of("0123456789") == std::string_view::npos;
        const auto res = std::from_chars(first, last, value);
        if (!digits_only || res.ptr != last) {
            fail("element count must be a non-negative integer, got '" + printable(t.text) + "'",
                 line_, t.column);
        }
        if (res.ec == std::errc::result_out_of_range) {
            fail("element count '" + printable(t.text) + "' is too large", line_, t.column);
        }
        return value;
    }

    Type parse_type_token(const TextToken& t) const {
        Type type{};
        if (!parse_type(t.text, type)) {
            fail("unknown property type '" + printable(t.text) +
                     "' (expected char, uchar, short, ushort, int, uint, float, double or "
                     "int8, uint8, int16, uint16, int32, uint32, float32, float64)",
                 line_, t.column);
        }
        return type;
    }

    void parse_header() {
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
                    fail("unsupported PLY version '" + printable(tokens[2].text) +
                             "' (expected 1.0)",
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
                        fail("malformed property line (expected 'property <type> <name>')", line_,
                             1);
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

    void assign_roles() {
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
                fail(std::string("the vertex element has no '") + axes[k] + "' property",
                     vertex->line, 1);
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
            } else if (!p.is_list) {
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

    // Every declared count against the bytes that follow the header, before allocating.
    // Binary: each element needs at least its minimal size (lists empty, except a face's
    // vertex list, which needs 3 items). ASCII: at least 2 bytes per element (a digit and a
    // separator), a bound loose enough that a short file reaches the token that is missing
    // and the error names its line.
    void check_sizes() const {
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
                fail(
                    (ascii ? std::string() : locate_truncation() + "; ") + "the header declares " +
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

    // Where a binary body that is too short for its header ends: "face 3 of 4: truncated
    // at byte 315". Walks the elements reading only list counts; bounded by the file size.
    std::string locate_truncation() const {
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
                    const std::int64_t n = swap ? load_int<true>(prop.count_type, p)
                                                : load_int<false>(prop.count_type, p);
                    p += size;
                    const std::size_t item = type_size(prop.type);
                    if (n < 0 || static_cast<std::uint64_t>(n) >
                                     static_cast<std::uint64_t>(end - p) / item) {
                        return element_place(e, i) + at;
                    }
                    p += static_cast<std::size_t>(n) * item;
                }
            }
        }
        return "truncated at byte " + std::to_string(data_.size());
    }

    void allocate() {
        num_vertices_ = static_cast<std::int64_t>(vertex_element_->count);
        std::uint64_t num_faces = face_element_->count;
        if (format_ == Format::Ascii) {
            // The 2-byte bound lets a lying ASCII header through with counts up to half the
            // file size; reserve no more than the text can hold ("0 0 0\n" per vertex,
            // "3 0 0 0\n" per face) and let the vectors grow if it really holds more.
            const std::uint64_t remaining = data_.size() - body_offset_;
            out_.soup.positions.reserve(
                std::min<std::uint64_t>(vertex_element_->count, remaining / 6 + 1));
            num_faces = std::min<std::uint64_t>(num_faces, remaining / 8 + 1);
        } else {
            out_.soup.positions.assign(vertex_element_->count, Eigen::Vector3d::Zero());
        }
        face_offsets_.clear();
        face_offsets_.reserve(num_faces + 1);
        face_offsets_.push_back(0);
        face_indices_.reserve(3 * num_faces);
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

    // "4 vertex, 4 face": every element with data, as the header declares it.
    std::string declared_counts() const {
        std::string out;
        for (const Element& e : elements_) {
            if (e.properties.empty()) continue;
            if (!out.empty()) out += ", ";
            out += std::to_string(e.count) + " " + printable(e.name);
        }
        return out;
    }

    std::string element_place(const Element& e, std::uint64_t i) const {
        return printable(e.name) + " " + std::to_string(i) + " of " + std::to_string(e.count);
    }

    // ---- binary body -------------------------------------------------------------------

    template <typename T, bool Swap>
    static T load(const unsigned char* p) {
        T v;
        if constexpr (Swap) {
            unsigned char b[sizeof(T)];
            for (std::size_t i = 0; i < sizeof(T); ++i) b[i] = p[sizeof(T) - 1 - i];
            std::memcpy(&v, b, sizeof(T));
        } else {
            std::memcpy(&v, p, sizeof(T));
        }
        return v;
    }

    // Calls fn with a value of the C++ type of t (its type picks the load below).
    template <class Fn>
    static auto with_type(Type t, Fn&& fn) {
        switch (t) {
            case Type::Int8:
                return fn(std::int8_t{});
            case Type::UInt8:
                return fn(std::uint8_t{});
            case Type::Int16:
                return fn(std::int16_t{});
            case Type::UInt16:
                return fn(std::uint16_t{});
            case Type::Int32:
                return fn(std::int32_t{});
            case Type::UInt32:
                return fn(std::uint32_t{});
            case Type::Float32:
                return fn(float{});
            case Type::Float64:
                break;
        }
        return fn(double{});
    }

    template <bool Swap>
    static double load_double(Type t, const unsigned char* p) {
        return with_type(t, [p](auto tag) { return static_cast<double>(load<decltype(tag), Swap>(p)); });
    }

    // Only called with integer types (checked in the header).
    template <bool Swap>
    static std::int64_t load_int(Type t, const unsigned char* p) {
        return with_type(t, [p](auto tag) {
            if constexpr (std::is_integral_v<decltype(tag)>)
                return static_cast<std::int64_t>(load<decltype(tag), Swap>(p));
            else
                return std::int64_t{0};
        });
    }

    [[noreturn]] void fail_truncated(const Element& e, std::uint64_t i) const {
        fail(element_place(e, i) + ": truncated at byte " + std::to_string(data_.size()));
    }

    // Where a value is: the element and its index, and in a binary body the byte offset
    // (`at`); in an ASCII body line and column go into the exception instead.
    struct Place {
        const Element& element;
        std::uint64_t index;
        const unsigned char* at;  // nullptr in ASCII
        long line;
        long column;
    };

    [[noreturn]] void fail_at(const Place& place, const std::string& what) const {
        std::string where = element_place(place.element, place.index);
        if (place.at != nullptr) where += " (byte " + std::to_string(place.at - base_) + ")";
        fail(where + ": " + what, place.line, place.column);
    }

    void store_coordinate(Role role, double v, const Place& place) {
        const int axis = role == Role::X ? 0 : role == Role::Y ? 1 : 2;
        if (!std::isfinite(v)) {
            static const char* names[3] = {"x", "y", "z"};
            fail_at(place, std::string("non-finite coordinate ") + names[axis] + " = " +
                               (std::isnan(v) ? "nan"
                                : v > 0       ? "inf"
                                              : "-inf"));
        }
        out_.soup.positions[place.index][axis] = v;
    }

    void check_list_count(std::int64_t n, const Property& p, const Place& place) const {
        if (n < 0) {
            fail_at(place, "negative count " + std::to_string(n) + " for list '" + p.name + "'");
        }
        if (p.role == Role::Indices) {
            if (n < 3) {
                fail_at(place,
                        "polygon with " + std::to_string(n) + " vertices (at least 3 needed)");
            }
            if (face_indices_.size() + static_cast<std::uint64_t>(n) > kMaxInt) {
                fail_at(place, "more than " + std::to_string(kMaxInt) + " face vertex indices");
            }
        }
    }

    void push_index(std::int64_t index, const Place& place) {
        if (index < 0 || index >= num_vertices_) {
            if (index < 0) fail_at(place, "negative vertex index " + std::to_string(index));
            fail_at(place, "vertex index " + std::to_string(index) +
                               " out of range (the file has " + std::to_string(num_vertices_) +
                               " vertices)");
        }
        face_indices_.push_back(static_cast<int>(index));
    }

    template <bool Swap>
    void parse_binary() {
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
    void parse_fixed_element(const Element& e, const unsigned char* p) {
        for (std::uint64_t i = 0; i < e.count; ++i) {
            for (const Property& prop : e.properties) {
                switch (prop.role) {
                    case Role::X:
                    case Role::Y:
                    case Role::Z:
                        store_coordinate(prop.role, load_double<Swap>(prop.type, p),
                                         Place{e, i, p, 0, 0});
                        break;
                    case Role::FaceScalar:
                        out_.face_properties[prop.face_scalar].values.push_back(
                            load_double<Swap>(prop.type, p));
                        break;
                    case Role::Skip:
                    case Role::Indices:
                        break;
                }
                p += type_size(prop.type);
            }
        }
    }

    template <bool Swap>
    const unsigned char* parse_variable_element(const Element& e, const unsigned char* p,
                                                const unsigned char* end) {
        for (std::uint64_t i = 0; i < e.count; ++i) {
            for (const Property& prop : e.properties) {
                if (!prop.is_list) {
                    const std::size_t size = type_size(prop.type);
                    if (static_cast<std::size_t>(end - p) < size) fail_truncated(e, i);
                    switch (prop.role) {
                        case Role::X:
                        case Role::Y:
                        case Role::Z:
                            store_coordinate(prop.role, load_double<Swap>(prop.type, p),
                                             Place{e, i, p, 0, 0});
                            break;
                        case Role::FaceScalar:
                            out_.face_properties[prop.face_scalar].values.push_back(
                                load_double<Swap>(prop.type, p));
                            break;
                        case Role::Skip:
                        case Role::Indices:
                            break;
                    }
                    p += size;
                    continue;
                }
                const std::size_t count_size = type_size(prop.count_type);
                if (static_cast<std::size_t>(end - p) < count_size) fail_truncated(e, i);
                const std::int64_t n = load_int<Swap>(prop.count_type, p);
                check_list_count(n, prop, Place{e, i, p, 0, 0});
                p += count_size;
                const std::size_t item_size = type_size(prop.type);
                if (static_cast<std::uint64_t>(n) >
                    static_cast<std::uint64_t>(end - p) / item_size) {
                    fail_truncated(e, i);
                }
                if (prop.role == Role::Indices) {
                    for (std::int64_t j = 0; j < n; ++j) {
                        push_index(load_int<Swap>(prop.type, p), Place{e, i, p, 0, 0});
                        p += item_size;
                    }
                    face_offsets_.push_back(static_cast<int>(face_indices_.size()));
                } else {
                    p += static_cast<std::size_t>(n) * item_size;
                }
            }
        }
        return p;
    }

    // ---- ASCII body --------------------------------------------------------------------

    struct AsciiToken {
        std::string_view text;  // empty at end of data
        long line = 0;
        long column = 0;
    };

    AsciiToken next_token() {
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

    AsciiToken expect_token(const Element& e, std::uint64_t i, const Property& p,
                            const char* what) {
        AsciiToken t = next_token();
        if (t.text.empty()) {
            fail(element_place(e, i) + ": end of file where " + what + " of '" + p.name +
                     "' was expected",
                 t.line, t.column);
        }
        return t;
    }

    std::int64_t ascii_int(const AsciiToken& t, const Element& e, std::uint64_t i,
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

    double ascii_number(const AsciiToken& t, Type type, const Element& e, std::uint64_t i,
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

    void parse_ascii() {
        pos_ = body_offset_;
        line_ = body_line_;
        line_start_ = body_offset_;
        for (const Element& e : elements_) {
            if (e.properties.empty()) continue;
            const bool vertices = &e == vertex_element_;
            for (std::uint64_t i = 0; i < e.count; ++i) {
                if (vertices) out_.soup.positions.emplace_back(0.0, 0.0, 0.0);
                for (const Property& prop : e.properties) {
                    if (!prop.is_list) {
                        const AsciiToken t = expect_token(e, i, prop, "the value");
                        const double v = ascii_number(t, prop.type, e, i, prop);
                        switch (prop.role) {
                            case Role::X:
                            case Role::Y:
                            case Role::Z:
                                store_coordinate(prop.role, v,
                                                 Place{e, i, nullptr, t.line, t.column});
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
                        face_offsets_.push_back(static_cast<int>(face_indices_.size()));
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

    std::string_view data_;
    const std::string& name_;
    std::size_t pos_ = 0;
    long line_ = 0;
    std::size_t line_start_ = 0;
    Format format_ = Format::Ascii;
    std::vector<Element> elements_;
    Element* vertex_element_ = nullptr;
    Element* face_element_ = nullptr;
    std::size_t body_offset_ = 0;
    long body_line_ = 0;
    const unsigned char* base_ = nullptr;
    std::int64_t num_vertices_ = 0;
    MeshFile out_;
    std::vector<int> face_offsets_;
    std::vector<int> face_indices_;
};

}  // namespace

MeshFile read_ply(std::string_view data, const std::string& name) {
    return PlyParser(data, name).parse();
}

}  // namespace geotex::detail
