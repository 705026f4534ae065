#pragma once
/// A bounding-volume hierarchy over the triangles of a mesh whose vertices move while its
/// faces stay: built once from one set of positions, its boxes refitted to each new set, and
/// asked for the least distance from a point. The depth maps of a segmentation (one to three
/// per scale, and the scales of a series) all measure distances to surfaces that are the
/// mesh with some vertices moved a little towards their disc means.
///
/// Written here rather than taken from CGAL because CGAL's AABB_tree cannot refit: it is
/// rebuilt, on one thread, for every new set of positions, and holds about 68 bytes a
/// triangle. This tree is built once and in parallel, refits in one pass over its nodes, and
/// holds about 7 bytes a triangle, plus 7 of boxes for each set of positions. The distance
/// from a point to a triangle is still CGAL's, so that the depths stay those of an AABB_tree
/// query, bit for bit.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <vector>

namespace geotex {

class TriangleBvh {
  public:
    /// The boxes of every node for one set of positions (refit()), 6 floats a node (least
    /// x, y, z, then greatest), rounded outwards so that each holds its triangles exactly;
    /// and the faces left out of the queries at those positions.
    struct Boxes {
        std::vector<float> bounds;
        std::vector<char> degenerate;  ///< #F: the face's corners are collinear
    };

    /// One tree per group of faces: group g is faces group_faces[group_offsets[g] ..
    /// group_offsets[g + 1]) (#groups + 1 offsets from 0 to group_faces.size()); a query asks
    /// one group. The splits follow the faces' centroids at `positions` (#V), which the tree
    /// does not keep; `faces` (#F, corner indices) must outlive it. Parallel, and the same
    /// tree for any thread count. Throws InvalidInput when an offset or a face or corner index
    /// is out of range.
    TriangleBvh(const std::vector<Eigen::Vector3d>& positions,
                const std::vector<std::array<int, 3>>& faces, std::vector<int> group_faces,
                const std::vector<int>& group_offsets);

    /// The boxes of the faces with corners at `positions` (#V, as many as the construction's).
    /// A degenerate face (CGAL's Triangle_3::is_degenerate: collinear corners) adds no surface
    /// that its neighbours do not, and CGAL's projection expects a proper triangle: it is left
    /// out of the boxes and of every query with them. Parallel. Throws InvalidInput when
    /// `positions` has another size.
    Boxes refit(const std::vector<Eigen::Vector3d>& positions) const;

    /// The least squared distance from `q` to a face of `group`, with corners at `positions`,
    /// the ones `boxes` was refitted to; `bound` when none is closer (start with the squared
    /// distance to a point known to lie on the surface). Each face's distance is CGAL's: the
    /// squared distance to CGAL's projection of q on the triangle. Throws InvalidInput for a
    /// group out of range or boxes of another tree.
    double squared_distance(int group, const Eigen::Vector3d& q, double bound, const Boxes& boxes,
                            const std::vector<Eigen::Vector3d>& positions) const;

    /// Whether `group` has a face that is not degenerate at the positions of `boxes`.
    bool has_faces(int group, const Boxes& boxes) const;

    int num_groups() const { return static_cast<int>(roots_.size()); }

  private:
    // A node covers order_[first, first + count); a leaf holds at most kLeafSize faces. The
    // nodes of a tree are in pre-order: an inner node's left child follows it, `right` is
    // the index of its right child.
    struct Node {
        int first = 0;
        int count = 0;
        int right = 0;
    };

    // A face and its centroid, while the tree is built.
    struct SplitItem {
        std::array<float, 3> centroid;
        int face;
    };
    static void split(std::vector<SplitItem>& items, int first, int count);
    int root_of(int group) const;  // its tree's root (-1: no face); throws when out of range
    int lay_out(int first, int count);

    const std::vector<std::array<int, 3>>* faces_;
    std::size_t num_positions_ = 0;
    std::vector<int> order_;  // the faces, each tree's leaves in order
    std::vector<Node> nodes_;
    std::vector<int> roots_;  // per group; -1 for an empty group
};

}  // namespace geotex
