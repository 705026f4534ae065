// OFF, OBJ and STL through CGAL's stream readers. Those readers return only true or false,
// wrap a negative index into a huge size_t, stop at "nan" with no reason, and size their
// containers from a header count; so each format is scanned first (mesh_scan.hpp), line by
// line, for the problems we can name with a line and column, and CGAL's result is checked
// again afterwards.

#include "geometry/detail/cgal_readers.hpp"

#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/OFF.h>
#include <CGAL/IO/STL.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <istream>
#include <limits>
#include <streambuf>
#include <vector>

#include "common/errors.hpp"
#include "geometry/detail/mesh_scan.hpp"

namespace geotex::detail {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Polygons = std::vector<std::vector<std::size_t>>;

constexpr std::uint64_t kMaxInt = static_cast<std::uint64_t>(std::numeric_limits<int>::max());

// An istream over bytes in memory, without a copy. Seeking is supported because CGAL's STL
// reader rewinds.
class MemoryBuffer : public std::streambuf {
  public:
    explicit MemoryBuffer(std::string_view data) {
        // The get area is only read: sputbackc of the same character moves the pointer back
        // and never writes.
        char* begin = const_cast<char*>(data.data());
        setg(begin, begin, begin + data.size());
    }

  protected:
    pos_type seekoff(off_type off, std::ios_base::seekdir dir,
                     std::ios_base::openmode which) override {
        if ((which & std::ios_base::in) == 0) return pos_type(off_type(-1));
        char* base = dir == std::ios_base::beg   ? eback()
                     : dir == std::ios_base::cur ? gptr()
                                                 : egptr();
        const off_type target = (base - eback()) + off;
        if (target < 0 || target > egptr() - eback()) return pos_type(off_type(-1));
        setg(eback(), eback() + target, egptr());
        return pos_type(target);
    }

    pos_type seekpos(pos_type pos, std::ios_base::openmode which) override {
        return seekoff(off_type(pos), std::ios_base::beg, which);
    }
};

// ---- CGAL soup to our soup -----------------------------------------------------------------

// Converts and checks what CGAL read (it does not check index range or non-finite binary
// coordinates). `polygon_lines` gives the line of each polygon when known.
MeshFile to_mesh_file(const Scan& scan, const std::vector<Point>& points, const Polygons& polygons,
                      const std::string& format, const std::vector<long>& polygon_lines = {}) {
    if (points.size() > kMaxInt) scan.fail("too many vertices: " + std::to_string(points.size()));
    if (polygons.empty()) scan.fail("the file has no faces");
    MeshFile out;
    out.format = format;
    out.soup.positions.reserve(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Point& p = points[i];
        if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) {
            scan.fail("vertex " + std::to_string(i) + ": non-finite coordinate");
        }
        out.soup.positions.emplace_back(p.x(), p.y(), p.z());
    }
    std::size_t total = 0;
    for (const auto& polygon : polygons) total += polygon.size();
    if (total > kMaxInt) scan.fail("too many face vertex indices: " + std::to_string(total));
    out.soup.face_offsets.reserve(polygons.size() + 1);
    out.soup.face_indices.reserve(total);
    for (std::size_t f = 0; f < polygons.size(); ++f) {
        const long line = f < polygon_lines.size() ? polygon_lines[f] : 0;
        const std::string where = "face " + std::to_string(f);
        if (polygons[f].size() < 3) {
            scan.fail(where + ": polygon with " + std::to_string(polygons[f].size()) +
                          " vertices (at least 3 needed)",
                      line);
        }
        for (std::size_t index : polygons[f]) {
            if (index >= points.size()) {
                // A negative index arrives here wrapped around to a huge size_t.
                const auto as_signed = static_cast<std::int64_t>(index);
                scan.fail(where + ": vertex index " + std::to_string(as_signed) +
                              " out of range (the file has " + std::to_string(points.size()) +
                              " vertices)",
                          line);
            }
            out.soup.face_indices.push_back(static_cast<int>(index));
        }
        out.soup.face_offsets.push_back(static_cast<int>(out.soup.face_indices.size()));
    }
    return out;
}

}  // namespace

MeshFile read_off(std::string_view data, const std::string& name) {
    const Scan scan{name};
    const OffHeader header = scan_off_header(scan, data);
    check_off_sizes(scan, header, data.size());
    std::vector<long> face_lines;
    if (header.binary) {
        scan_off_binary_body(scan, header, data);
    } else {
        face_lines = scan_off_body(scan, header, data);
    }
    // For the texture coordinates, colours and normals that the ST, C and N prefixes announce,
    // CGAL's ASCII scanner reads past the numbers a line holds (the previous line's values) and
    // casts colours to unsigned char out of range, which is undefined behaviour. geotex uses
    // none of them: CGAL gets a copy whose keyword has no such prefix, and then reads the
    // coordinates and indices of each line and skips the numbers after them.
    std::string copy;
    if (!header.binary && header.keyword_prefix > 0) {
        copy.assign(data);
        copy.replace(header.keyword_offset, header.keyword_prefix, header.keyword_prefix, ' ');
    }
    std::vector<Point> points;
    Polygons polygons;
    MemoryBuffer buffer(copy.empty() ? data : std::string_view(copy));
    std::istream in(&buffer);
    if (!CGAL::IO::read_OFF(in, points, polygons, CGAL::parameters::verbose(false))) {
        scan.fail("not a valid OFF file (malformed header, counts, or coordinates)");
    }
    return to_mesh_file(scan, points, polygons, "off", face_lines);
}

MeshFile read_obj(std::string_view data, const std::string& name) {
    const Scan scan{name};
    const ObjScan obj = scan_obj(scan, data);
    std::string copy;
    if (obj.needs_copy) copy = clean_obj(data);
    std::vector<Point> points;
    Polygons polygons;
    MemoryBuffer buffer(obj.needs_copy ? std::string_view(copy) : data);
    std::istream in(&buffer);
    if (!CGAL::IO::read_OBJ(in, points, polygons, CGAL::parameters::verbose(false))) {
        scan.fail("not a valid OBJ file (malformed vertex or face statement)");
    }
    if (polygons.size() != obj.face_lines.size()) {
        scan.fail("not a valid OBJ file: read " + std::to_string(polygons.size()) + " faces, " +
                  "but the file has " + std::to_string(obj.face_lines.size()) + " 'f' lines");
    }
    return to_mesh_file(scan, points, polygons, "obj", obj.face_lines);
}

MeshFile read_stl(std::string_view data, const std::string& name) {
    const Scan scan{name};
    const std::uint64_t n = data.size() >= 84 ? le32(data, 80) : 0;
    const std::uint64_t binary_size = 84 + 50 * n;
    const bool solid = starts_with_solid(data);
    bool binary = data.size() >= 84 && binary_size == data.size();
    if (!binary && !solid) {
        if (data.size() < 84) {
            scan.fail("not a valid STL file: it does not start with 'solid' and is too short (" +
                      std::to_string(data.size()) + " bytes) for a binary STL (84-byte header)");
        }
        if (binary_size > data.size()) {
            scan.fail("binary STL truncated: it declares " + std::to_string(n) +
                      " triangles, which need " + std::to_string(binary_size) +
                      " bytes, but the file has " + std::to_string(data.size()) + " bytes");
        }
        binary = true;  // extra bytes after the triangles are ignored
    }
    std::string copy;
    std::string_view input = data;
    if (binary) {
        scan_binary_stl(scan, data, n);
        if (n == 0) scan.fail("the file has no faces");
        if (solid) {
            // A binary header that begins with "solid" sends CGAL to its ASCII parser first;
            // the header carries no data, so CGAL gets a copy with a blank header.
            copy.assign(data);
            std::fill(copy.begin(), copy.begin() + 80, '\0');
            input = copy;
        }
    } else {
        scan_ascii_stl(scan, data);
    }
    std::vector<Point> points;
    Polygons polygons;
    MemoryBuffer buffer(input);
    std::istream in(&buffer);
    if (!CGAL::IO::read_STL(in, points, polygons, CGAL::parameters::verbose(false))) {
        scan.fail(std::string("not a valid ") + (binary ? "binary" : "ASCII") + " STL file");
    }
    return to_mesh_file(scan, points, polygons, "stl");
}

}  // namespace geotex::detail
