#pragma once
// The steps of repair_soup (geometry/mesh_repair.cpp) that its tiled form
// (geometry/mesh_repair_tiles.cpp) runs on each tile: the edges matched, and the orientation
// spread over the faces they join.

#include <array>
#include <optional>
#include <vector>

#include "geometry/mesh.hpp"

namespace geotex::detail {

constexpr int kBoundaryEdge = -1;
constexpr int kNonManifoldEdge = -2;
/// Not an edge value of match_edges: one that a caller masks, which the spread does not cross.
constexpr int kUnknownEdge = -3;

struct EdgeMatch {
    /// Per half-edge h of a manifold edge: 2 * (the other half-edge) + 1 if both run the same
    /// way (one of the two faces must flip); else kBoundaryEdge or kNonManifoldEdge. Half-edge
    /// 3f+k runs from faces[f][k] to faces[f][(k+1)%3].
    std::vector<int> opposite;
    int num_boundary_edges = 0;
    int num_non_manifold_edges = 0;
    std::vector<int> non_manifold_faces;       ///< faces of each non-manifold edge, runs ...
    std::vector<int> non_manifold_offsets{0};  ///< ... delimited here
    std::vector<char> duplicate;               ///< per face: same vertex set as an earlier face
    int num_duplicates = 0;
};

/// The edges of `faces` (over `nv` vertices), and the faces with the vertex set of an earlier
/// face.
EdgeMatch match_edges(const std::vector<std::array<int, 3>>& faces, int nv);

/// The faces' orientation relative to their patch, spread breadth-first over the manifold
/// edges of `opposite` (match_edges'; a negative value is not crossed).
struct OrientationSpread {
    /// Per face: 2 * patch + 1 if the face must flip to agree with its patch's first face.
    /// Patches are numbered in the order of their first face.
    std::vector<int> state;
    std::vector<int> seed;         ///< per patch: its first face
    std::vector<char> patch_open;  ///< per patch: a face has an edge valued below 0
    int num_conflicts = 0;         ///< manifold edges whose two faces cannot agree
};
OrientationSpread spread_orientation(const std::vector<std::array<int, 3>>& faces,
                                     const std::vector<int>& opposite);

/// What steps (4) and (5) of repair_soup make of its triangles: the duplicate faces removed
/// and the rest oriented.
struct OrientedFaces {
    std::vector<char> flip;  ///< per face left, to be flipped; all 0 without orienting
    int num_duplicates = 0;
    int num_boundary_edges = 0;
    int num_non_manifold_edges = 0;
    int num_components = 0;
    int num_closed_components = 0;
    int num_conflicts = 0;  ///< 0 without orienting
};

/// Steps (4) and (5) over the whole mesh: the duplicate faces of `mesh` are dropped from its
/// faces and from `source` (one entry a face, or empty), and the rest oriented when `orient`.
OrientedFaces orient_whole(Mesh& mesh, std::vector<int>& source, bool orient);

/// The same a tile at a time (tiles.hpp's boxes, `tiles` of them), holding the edges of one
/// tile instead of the whole mesh's: the same result, or nothing (and `mesh` and `source`
/// untouched) where the tiles cannot tell it: when orienting, on a surface that cannot be
/// oriented or a closed one whose volume is too near 0 for its sign to be the same whatever
/// the order of the sum.
std::optional<OrientedFaces> orient_in_tiles(Mesh& mesh, std::vector<int>& source, bool orient,
                                             int tiles);

/// Drops the faces marked in `removed` from `faces` and their entries in `source` (unless it is
/// empty), keeping the order.
void remove_faces(std::vector<std::array<int, 3>>& faces, std::vector<int>& source,
                  const std::vector<char>& removed);

}  // namespace geotex::detail
