#pragma once
/// The scale-dependent oriented depth map of paper §3.1: the oriented rule (eq. 2) and the
/// distance from each vertex to the smoothed surface of smoothed_surface.hpp (eq. 1).

#include <vector>

#include "geometry/enum_names.hpp"
#include "geometry/mesh.hpp"
#include "geometry/smoothed_surface.hpp"
#include "geometry/topology.hpp"
#include "geometry/triangle_bvh.hpp"

namespace geotex {

/// Which details a depth map measures: regions above the smoothed surface (paper's M_s^+)
/// or below it (M_s^-, engravings and incisions).
enum class DetailOrientation { Positive, Negative };

/// The names of the orientations in options and reports.
inline constexpr std::array<std::pair<const char*, DetailOrientation>, 2> kDetailOrientationNames =
    {{{"positive", DetailOrientation::Positive}, {"negative", DetailOrientation::Negative}}};
inline const char* name_of(DetailOrientation o) { return name_in(kDetailOrientationNames, o); }

/// Whether a vertex at `position` with unit normal `normal` stands out of its smoothed position
/// on the side of `orientation` (paper eq. 2): only those vertices move to the smoothed
/// surface and get a depth.
inline bool stands_out(const Eigen::Vector3d& position, const Eigen::Vector3d& smoothed,
                       const Eigen::Vector3d& normal, DetailOrientation orientation) {
    const double sign = orientation == DetailOrientation::Positive ? 1.0 : -1.0;
    return sign * (position - smoothed).dot(normal) > 0;
}

/// Oriented depth per vertex and face.
struct DepthMap {
    DetailOrientation orientation = DetailOrientation::Positive;
    std::vector<double> vertex_depth;  ///< #V, >= 0, mesh units
    std::vector<double> face_depth;    ///< #F, mean of the face's vertex depths
    double max_depth = 0;              ///< largest vertex depth
    int num_moved_vertices = 0;        ///< vertices the oriented rule moved to v_s
};

/// Paper eq. 2 and §3.1: v_s^+ = v_s where (v - v_s) . n(v) > 0, else v (mirrored for
/// negative details); the depth of v is its distance to the closest point of the mesh with
/// vertices v_s^± within v's connected component. Vertices left in place have depth 0.
/// `vertex_normal` is #V, unit, consistently oriented. Parallel over vertices. For several
/// depth maps of one mesh, a DepthMapper shares what does not depend on the surface.
DepthMap make_depth_map(const Mesh& mesh, const std::vector<Eigen::Vector3d>& vertex_normal,
                        const SmoothedSurface& smoothed, DetailOrientation orientation);

/// Sets d.face_depth (#F, each face's mean vertex depth) and d.max_depth from d.vertex_depth
/// (#V of `mesh`), as make_depth_map does: for depth maps assembled from parts.
void set_face_depths(const Mesh& mesh, DepthMap& d);

/// make_depth_map for many smoothed surfaces of one mesh (both orientations, the second
/// smoothing of the rim removal, the scales of a series): the connected components, a
/// triangle tree over the mesh (triangle_bvh.hpp) and the vertices' query order are made
/// once, and each depth map only refits the tree's boxes to its surface. Holds a pointer to
/// `mesh`, which must outlive it; map() may be called from several threads at once.
class DepthMapper {
  public:
    explicit DepthMapper(const Mesh& mesh);
    /// With the connected components given (#V ids in [0, num_components)) rather than those
    /// of `mesh`: a tile (tiles.hpp) measures each vertex to the part of the smoothed surface
    /// that is its component in the whole mesh, even where the tile cuts it in two. Throws
    /// InvalidInput when a size or an id does not fit.
    DepthMapper(const Mesh& mesh, VertexComponents components);
    DepthMapper(const DepthMapper&) = delete;
    DepthMapper& operator=(const DepthMapper&) = delete;

    /// make_depth_map(mesh, vertex_normal, smoothed, orientation), bit for bit.
    DepthMap map(const std::vector<Eigen::Vector3d>& vertex_normal, const SmoothedSurface& smoothed,
                 DetailOrientation orientation) const;

  private:
    const Mesh* mesh_;
    VertexComponents components_;
    TriangleBvh tree_;              // one tree per component, over all its faces
    std::vector<int> query_order_;  // #V, along a Morton curve
};

}  // namespace geotex
