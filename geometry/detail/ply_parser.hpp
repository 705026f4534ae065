#pragma once
// The PLY reader's parser (private to geometry/detail/ply*.cpp): the property types, the
// header's elements and the parser class, whose work is split by file: ply.cpp drives it and
// stores the values read, ply_header.cpp reads and checks the header (every count against
// the file size before anything is allocated), ply_binary.cpp and ply_ascii.cpp read the
// two kinds of body. Why a reader of our own: ply.cpp.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "common/detail/text.hpp"
#include "common/errors.hpp"
#include "geometry/detail/polygon_collector.hpp"
#include "geometry/mesh_io.hpp"

namespace geotex::detail::ply {

constexpr std::uint64_t kMaxInt = static_cast<std::uint64_t>(std::numeric_limits<int>::max());

enum class Type : std::uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

inline std::size_t type_size(Type t) {
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

inline bool is_integer(Type t) { return t != Type::Float32 && t != Type::Float64; }

inline const char* type_name(Type t) {
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

inline bool parse_type(std::string_view s, Type& t) {
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
inline std::uint64_t mul_sat(std::uint64_t a, std::uint64_t b) {
    if (a != 0 && b > std::numeric_limits<std::uint64_t>::max() / a) {
        return std::numeric_limits<std::uint64_t>::max();
    }
    return a * b;
}

inline std::uint64_t add_sat(std::uint64_t a, std::uint64_t b) {
    return b > std::numeric_limits<std::uint64_t>::max() - a
               ? std::numeric_limits<std::uint64_t>::max()
               : a + b;
}
class PlyParser {
  public:
    PlyParser(std::string_view data, const std::string& name, const PolygonSink& sink)
        : data_(data), name_(name), keep_face_scalars_(!sink), polygons_(out_.soup, sink) {}

    MeshFile parse();

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
    bool next_line(std::string_view& line);

    std::uint64_t parse_count(const TextToken& t) const;

    Type parse_type_token(const TextToken& t) const;

    void parse_header();

    void assign_roles();

    // Every declared count against the bytes that follow the header, before allocating.
    // Binary: each element needs at least its minimal size (lists empty, except a face's
    // vertex list, which needs 3 items). ASCII: at least 2 bytes per element (a digit and a
    // separator), a bound loose enough that a short file reaches the token that is missing
    // and the error names its line.
    void check_sizes() const;

    // Where a binary body that is too short for its header ends: "face 3 of 4: truncated
    // at byte 315". Walks the elements reading only list counts; bounded by the file size.
    std::string locate_truncation() const;

    void allocate();

    // "4 vertex, 4 face": every element with data, as the header declares it.
    std::string declared_counts() const;

    std::string element_place(const Element& e, std::uint64_t i) const;

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
        return with_type(
            t, [p](auto tag) { return static_cast<double>(load<decltype(tag), Swap>(p)); });
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

    [[noreturn]] void fail_truncated(const Element& e, std::uint64_t i) const;

    // Where a value is: the element and its index, and in a binary body the byte offset
    // (`at`); in an ASCII body line and column go into the exception instead.
    struct Place {
        const Element& element;
        std::uint64_t index;
        const unsigned char* at;  // nullptr in ASCII
        long line;
        long column;
    };

    [[noreturn]] void fail_at(const Place& place, const std::string& what) const;

    void store_coordinate(Role role, double v, const Place& place);

    void check_list_count(std::int64_t n, const Property& p, const Place& place) const;

    void push_index(std::int64_t index, const Place& place);

    template <bool Swap>
    void parse_binary();

    // The scalar property `prop` of item i of e, at p: a coordinate or a face property kept.
    template <bool Swap>
    void store_scalar(const Property& prop, const Element& e, std::uint64_t i,
                      const unsigned char* p);

    template <bool Swap>
    void parse_fixed_element(const Element& e, const unsigned char* p);

    template <bool Swap>
    const unsigned char* parse_variable_element(const Element& e, const unsigned char* p,
                                                const unsigned char* end);

    // ---- ASCII body --------------------------------------------------------------------

    struct AsciiToken {
        std::string_view text;  // empty at end of data
        long line = 0;
        long column = 0;
    };

    AsciiToken next_token();

    AsciiToken expect_token(const Element& e, std::uint64_t i, const Property& p, const char* what);

    std::int64_t ascii_int(const AsciiToken& t, const Element& e, std::uint64_t i,
                           const Property& p) const;

    double ascii_number(const AsciiToken& t, Type type, const Element& e, std::uint64_t i,
                        const Property& p) const;

    void parse_ascii();

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
    // Without a sink, the face's scalar properties go into out_.face_properties. With one they
    // are skipped: a caller that does not hold the polygons would not want 8 bytes a face for
    // each of them (a segmentation PLY read back has five).
    bool keep_face_scalars_ = true;
    PolygonCollector polygons_;  // into out_.soup or to the caller's sink
};

}  // namespace geotex::detail::ply
