#include "geometry/detail/cgal_polygon.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/utility.h>

#include <algorithm>

namespace geotex::detail {
namespace {

// Exact predicates: collinearity and the hole filler's choices do not depend on rounding.
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;

Point to_point(const Eigen::Vector3d& p) { return Point(p.x(), p.y(), p.z()); }

// The hole filler looks for the best triangles among the faces of a 3D Delaunay triangulation
// of the corners, and when those hold none (corners on one line, repeated corners), among all
// triangles: both searches can take a time cubic in the number of corners (11 s for a ring of
// 400 repeated corners, an 834-byte OBJ file), and the second one's step count overflows an
// int from about 1,300 corners on. Larger rings get a constrained Delaunay triangulation in
// their plane instead, which needs a planar ring that does not cross itself, and otherwise no
// triangulation (repair_soup then fans them).
constexpr int kMaxSearchCorners = 100;

}  // namespace

std::vector<std::array<int, 3>> triangulate_polygon(const std::vector<Eigen::Vector3d>& ring) {
    const int n = static_cast<int>(ring.size());
    std::vector<std::array<int, 3>> result;
    if (n < 3) return result;
    std::vector<Point> points;
    points.reserve(ring.size());
    for (const Eigen::Vector3d& p : ring) points.push_back(to_point(p));
    std::vector<CGAL::Triple<int, int, int>> patch;
    patch.reserve(ring.size());
    const bool search = n <= kMaxSearchCorners;
    CGAL::Polygon_mesh_processing::triangulate_hole_polyline(
        points, std::back_inserter(patch),
        CGAL::parameters::use_2d_constrained_delaunay_triangulation(!search)
            .use_delaunay_triangulation(search)
            .do_not_use_cubic_algorithm(!search));
    if (static_cast<int>(patch.size()) != n - 2) return result;
    result.reserve(patch.size());
    for (const auto& t : patch) {
        std::array<int, 3> tri = {t.first, t.second, t.third};
        for (int index : tri) {
            if (index < 0 || index >= n) return {};
        }
        // The hole filler joins ring corners without crossings, so each triangle's corners
        // in increasing ring order run the same way round as the ring.
        std::sort(tri.begin(), tri.end());
        if (tri[0] == tri[1] || tri[1] == tri[2]) return {};
        result.push_back(tri);
    }
    return result;
}

bool collinear(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    return CGAL::collinear(to_point(a), to_point(b), to_point(c));
}

}  // namespace geotex::detail
