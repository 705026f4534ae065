#pragma once
// What the OFF, OBJ and STL readers (text_mesh_readers.hpp; off_reader.cpp, obj_reader.cpp,
// stl_reader.cpp) share: a cursor over the bytes with line and column, the slow path of a
// number that is not a plain one (its message, or a subnormal value), and the checks every
// reader ends with. These formats used to go through CGAL's stream readers after a scan of
// ours for line-numbered errors: two passes, an istringstream per line and istream >> double,
// about 11 MB/s. Here a cursor walks the bytes once; the common case (a number followed by a
// blank) costs one std::from_chars, and the messages are built only when something is wrong.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "geometry/detail/mesh_scan.hpp"
#include "geometry/detail/polygon_collector.hpp"
#include "geometry/detail/read_window.hpp"
#include "geometry/mesh_io.hpp"
#include "geometry/work_progress.hpp"

namespace geotex::detail::text_mesh {

// "vertex 12": the element a message is about, built only when there is a message.
inline std::string place(const char* kind, std::int64_t index) {
    return std::string(kind) + " " + std::to_string(index);
}

// A position in a text with its line and column. Blanks are ASCII white space except '\n',
// which ends a statement; with `hash_comments` a '#' ends it too (the rest of the line is a
// comment); with `continuations` a backslash before the end of a line joins the next line
// (OBJ).
class TextCursor {
  public:
    TextCursor(std::string_view data, long first_line, bool hash_comments, bool continuations)
        : p_(data.data()),
          end_(data.data() + data.size()),
          line_start_(data.data()),
          line_(first_line),
          hash_(hash_comments),
          continuations_(continuations),
          meter_(static_cast<long long>(data.size())),
          reported_(data.data()) {}

    bool at_end() const { return p_ == end_; }
    long line() const { return line_; }
    long column() const { return static_cast<long>(p_ - line_start_) + 1; }

    // Past blanks and continuations, to a token, the end of the statement or of the data.
    void skip_blanks() {
        for (;;) {
            while (p_ != end_ && is_blank(*p_)) ++p_;
            if (!continuations_ || p_ == end_ || *p_ != '\\' || !continues_at(p_)) return;
            p_ = std::find(p_, end_, '\n') + 1;  // continues_at found the '\n'
            ++line_;
            line_start_ = p_;
        }
    }

    // At the end of the statement: end of data, '\n', or a comment. Call after skip_blanks.
    bool at_statement_end() const { return p_ == end_ || *p_ == '\n' || (hash_ && *p_ == '#'); }

    // To the start of the next line (past a comment); statements continued with a backslash
    // are skipped whole when `statement` is set.
    void next_line(bool statement = false) {
        for (;;) {
            const void* nl = std::memchr(p_, '\n', static_cast<std::size_t>(end_ - p_));
            if (nl == nullptr) {
                p_ = end_;
                return;
            }
            const char* at = static_cast<const char*>(nl);
            const bool joined = statement && continuations_ && ends_with_backslash(at);
            p_ = at + 1;
            ++line_;
            line_start_ = p_;
            // The bytes read, for a progress line on a large file (work_progress.hpp).
            if ((line_ & 65535) == 0) {
                meter_.add(p_ - reported_);
                reported_ = p_;
                release_read(line_start_);  // a line is never read again before its start
            }
            if (!joined) return;
        }
    }

    // The token at the cursor (up to a blank, the end of the line or a comment), unread.
    std::string_view token() const {
        const char* q = p_;
        while (!is_delimiter(q)) ++q;
        return {p_, static_cast<std::size_t>(q - p_)};
    }

    TextToken text_token() const { return {token(), column()}; }

    void skip(std::size_t n) { p_ += n; }

    // Past the rest of the token.
    void skip_token() {
        while (!is_delimiter(p_)) ++p_;
    }

    // A finite decimal number that is the whole token: read, true. Else false and unmoved
    // (the caller asks number_slow for the value or the message).
    bool number(double& value) {
        const char* first = p_;
        if (first != end_ && *first == '+') ++first;
        const auto res = std::from_chars(first, end_, value);
        if (res.ec != std::errc() || !is_delimiter(res.ptr) || !std::isfinite(value)) return false;
        p_ = res.ptr;
        return true;
    }

    // An integer at the cursor, with a '+' when `plus`; true if it ends at a delimiter or at
    // `stop` (which then stays unread).
    bool integer(std::int64_t& value, bool plus, char stop = '\n') {
        const char* first = p_;
        if (plus && first != end_ && *first == '+') ++first;
        const auto res = std::from_chars(first, end_, value);
        if (res.ec != std::errc() || !(is_delimiter(res.ptr) || *res.ptr == stop)) return false;
        p_ = res.ptr;
        return true;
    }

  private:
    static bool is_blank(char c) {
        return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
    }

    bool is_delimiter(const char* q) const {
        if (q == end_) return true;
        const char c = *q;
        return is_blank(c) || c == '\n' || (hash_ && c == '#') ||
               (continuations_ && c == '\\' && continues_at(q));
    }

    // A backslash at q followed by the end of its line (blanks allowed before it).
    bool continues_at(const char* q) const {
        ++q;
        while (q != end_ && is_blank(*q)) ++q;
        return q != end_ && *q == '\n';
    }

    // The line that ends at the '\n' at `nl` ends with a backslash (blanks allowed after it).
    bool ends_with_backslash(const char* nl) const {
        const char* q = nl;
        while (q != line_start_ && q != p_ && is_blank(q[-1])) --q;
        return q != line_start_ && q[-1] == '\\' && !(hash_ && line_has_comment(q - 1));
    }

    // A '#' before `q` on the current line: the backslash is inside a comment.
    bool line_has_comment(const char* q) const {
        return std::memchr(line_start_, '#', static_cast<std::size_t>(q - line_start_)) != nullptr;
    }

    const char* p_;
    const char* end_;
    const char* line_start_;
    long line_;
    bool hash_;
    bool continuations_;
    LoopMeter meter_;
    const char* reported_;  // the bytes before it were added to meter_
};

// The number at the cursor when TextCursor::number said no: the message of what is wrong
// (non-finite, not a number, overflow); or, for a number so small that from_chars calls it
// out of range, its value (0 or a subnormal, as istream >> double reads it).
inline double number_slow(const Scan& scan, TextCursor& c, const char* kind, std::int64_t index) {
    const TextToken t = c.text_token();
    scan.check_number(t, c.line(), place(kind, index));
    const std::string copy(t.text);
    const double value = std::strtod(copy.c_str(), nullptr);
    c.skip(t.text.size());
    return value;
}

// The checks every reader ends with.
inline void finish_soup(const Scan& scan, std::uint64_t num_vertices,
                        const PolygonCollector& polygons, long line) {
    if (num_vertices > kMaxInt) scan.fail("too many vertices: " + std::to_string(num_vertices));
    if (polygons.num_polygons() == 0) scan.fail("the file has no faces", line);
}

}  // namespace geotex::detail::text_mesh
