#pragma once
/// Triangle mesh and polygon soup: the plain data every stage works on.

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products, used by most stages
#include <array>
#include <cstddef>
#include <vector>

namespace geotex {

/// Polygons as read from a file, before repair. Polygon p has the vertex indices
/// face_indices[face_offsets[p] .. face_offsets[p+1]).
struct PolygonSoup {
    std::vector<Eigen::Vector3d> positions;  ///< #P
    std::vector<int> face_offsets{0};        ///< #polygons + 1, starts with 0
    std::vector<int> face_indices;           ///< concatenated polygon vertex indices

    int num_polygons() const { return static_cast<int>(face_offsets.size()) - 1; }
};

/// #V positions held elsewhere, read-only: a mesh's vector, or the positions of a scan too large
/// to hold, mapped from a scratch file (PositionFile, scratch_file.hpp). The steps that a tiled
/// run's mesh job shares with a whole run take it, so that they read either. C++17 has no
/// std::span, and Eigen's Map would change every `positions[v]` of those steps.
///
/// A mapped span may also carry a second copy of the positions in the order of space, with each
/// vertex's place in it (SpaceOrderedPositions, scratch_file.hpp). Then operator[], with which
/// the steps look up the corners of faces, reads the copy: faces near each other have their
/// corners on pages near each other, whatever the vertex numbers, so that a step over some
/// faces needs few pages in memory. Iteration (begin, end) and in_order() read the positions in
/// vertex order, as a pass over every vertex wants them. The values are the same either way.
class PositionSpan {
  public:
    PositionSpan() = default;
    PositionSpan(const std::vector<Eigen::Vector3d>& positions)  // NOLINT: a vector is a span
        : data_(positions.data()), size_(positions.size()) {}
    PositionSpan(const Eigen::Vector3d* data, std::size_t size) : data_(data), size_(size) {}
    /// `data` in vertex order, and the same positions at `near[place[v]]`.
    PositionSpan(const Eigen::Vector3d* data, std::size_t size, const Eigen::Vector3d* near,
                 const int* place)
        : data_(data), size_(size), near_(near), place_(place) {}

    const Eigen::Vector3d& operator[](std::size_t v) const {
        return place_ != nullptr ? near_[place_[v]] : data_[v];
    }
    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    const Eigen::Vector3d* begin() const { return data_; }
    const Eigen::Vector3d* end() const { return data_ + size_; }
    /// The positions in vertex order only, for a step that reads them all one after another.
    PositionSpan in_order() const { return {data_, size_}; }

  private:
    const Eigen::Vector3d* data_ = nullptr;
    std::size_t size_ = 0;
    const Eigen::Vector3d* near_ = nullptr;
    const int* place_ = nullptr;
};

/// The smallest axis-aligned box that holds `points`; empty (min above max) when there are none.
/// Written here once for the stages that each need the bounds of a mesh's positions.
inline Eigen::AlignedBox3d bounding_box(PositionSpan points) {
    Eigen::AlignedBox3d box;  // empty
    for (const Eigen::Vector3d& p : points) box.extend(p);
    return box;
}

/// A triangle mesh with contiguous indices (no deleted elements). Faces are oriented
/// consistently where the connectivity allows it (counter-clockwise seen from outside on
/// closed components).
struct Mesh {
    std::vector<Eigen::Vector3d> positions;  ///< #V
    std::vector<std::array<int, 3>> faces;   ///< #F

    int num_vertices() const { return static_cast<int>(positions.size()); }
    int num_faces() const { return static_cast<int>(faces.size()); }
};

}  // namespace geotex
