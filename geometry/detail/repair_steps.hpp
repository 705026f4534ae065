#pragma once
// The steps of repair_soup (geometry/mesh_repair.cpp), shared with its tiled form
// (geometry/mesh_repair_tiles.cpp), which runs the edge matching and the orientation's spread
// on each tile, and its form with the faces on disk (geometry/mesh_repair_disk.cpp), which runs
// every step a block or a tile at a time.

#include <algorithm>
#include <array>
#include <functional>
#include <optional>
#include <vector>

#include "geometry/detail/cgal_polygon.hpp"
#include "geometry/diagnostics.hpp"
#include "geometry/mesh.hpp"
#include "geometry/mesh_repair.hpp"

namespace geotex {
struct MeshTile;
}

namespace geotex::detail {

/// Step (0): throws InvalidInput unless `soup` is a polygon soup repair_soup can repair (offsets
/// that fit the indices, finite coordinates, indices in range, at least 3 corners a polygon).
/// It is the three checks below, in that order, each with repair_soup's words.
void validate_soup(const PolygonSoup& soup);

/// Throws unless the offsets start at 0, end at the indices' end and never decrease.
void validate_offsets(const PolygonSoup& soup);

/// Throws when there are no polygons or a position is not finite.
void validate_positions(PositionSpan positions, int num_polygons);

/// The polygons' checks, one polygon at a time (the repair on disk reads them a block at a
/// time): every corner in range, at least 3 corners.
class PolygonCheck {
  public:
    explicit PolygonCheck(int num_vertices) : num_vertices_(num_vertices) {}
    /// Polygon `p`, whose `n` corners are corners[0 .. n); false if it fails.
    bool add(int p, const int* corners, int n);
    /// Throws for the polygons added that fail, naming how many and the first.
    void throw_if_bad() const;

  private:
    int num_vertices_;
    int small_ = 0, first_small_ = -1, first_small_size_ = 0;
    int out_of_range_ = 0, first_out_ = -1, first_out_index_ = 0;
};

/// Step (1): old vertex index -> new index, `positions` compacted in place to the merged
/// vertices when `merge` (bit-identical positions become their first occurrence), else the
/// identity.
std::vector<int> vertex_remap(std::vector<Eigen::Vector3d>& positions, bool merge);

/// Step (1)'s matching (#V): for each vertex, the first vertex with bit-identical coordinates,
/// itself when none comes before it. Sort-based: a radix sort on a hash of the coordinate bits,
/// then the vertices of each run of equal hashes (almost always one vertex, or a group of true
/// duplicates) told apart by their positions, which are read in the vertices' order. The sort
/// holds 16 bytes a vertex of one `passes`-th of them at a time (by their hash), so that the
/// repair on disk can bound it; then, the keys gone, the runs' vertices 16 bytes each while
/// they are sorted, 8 each after, with 36 for each distinct position among them; the same
/// result for any `passes`.
std::vector<int> first_occurrences(PositionSpan positions, int passes);

/// Step (1)'s numbering, in place: `first` (first_occurrences) becomes old index -> new index,
/// the first occurrences numbered in their order, so that the merged vertices keep the order
/// in which they first occur; keep(v) is called for each of them, in that order.
template <class Keep>
void number_first_occurrences(std::vector<int>& first, Keep&& keep) {
    int kept = 0;
    for (std::size_t v = 0; v < first.size(); ++v) {
        if (first[v] == static_cast<int>(v)) {
            keep(static_cast<int>(v));
            first[v] = kept++;
        } else {
            first[v] = first[first[v]];  // numbered already: it comes earlier
        }
    }
}

/// Step (2) for one polygon: appends to `out` the triangles of the polygon whose `n` corners
/// are corner(0), ..., corner(n - 1) (vertex ids after step 1): itself, a quad cut along its
/// shorter diagonal, or CGAL's triangulation of the ring (a fan when it finds none), each
/// triangle ordered like the polygon. `ring` is scratch.
template <class Corner>
void triangulate(int n, Corner corner, PositionSpan positions, std::vector<Eigen::Vector3d>& ring,
                 std::vector<std::array<int, 3>>& out) {
    if (n == 3) {
        out.push_back({corner(0), corner(1), corner(2)});
        return;
    }
    if (n == 4) {
        const int a = corner(0), b = corner(1), c = corner(2), d = corner(3);
        if ((positions[a] - positions[c]).squaredNorm() <=
            (positions[b] - positions[d]).squaredNorm()) {
            out.push_back({a, b, c});
            out.push_back({a, c, d});
        } else {
            out.push_back({a, b, d});
            out.push_back({b, c, d});
        }
        return;
    }
    ring.clear();
    for (int i = 0; i < n; ++i) ring.push_back(positions[corner(i)]);
    std::vector<std::array<int, 3>> triangles = triangulate_polygon(ring);
    if (triangles.empty()) {
        // CGAL found no triangulation (e.g. a degenerate ring): a fan still covers it.
        for (int i = 1; i + 1 < n; ++i) triangles.push_back({0, i, i + 1});
    }
    for (const std::array<int, 3>& t : triangles)
        out.push_back({corner(t[0]), corner(t[1]), corner(t[2])});
}

/// Step (3): the face repeats a vertex or its corners lie exactly on a line.
bool degenerate(const std::array<int, 3>& t, PositionSpan positions);

/// Throws repair_soup's InvalidInput for a soup none of whose `num_triangles` triangles is
/// left.
[[noreturn]] void no_face_left(std::size_t num_triangles, int num_polygons);

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

/// Steps (4) and (5) over the whole mesh: the duplicate faces are dropped from `faces` (#F by 3,
/// over `positions`) and from `source` (one entry a face, or empty), and the rest oriented when
/// `orient`.
OrientedFaces orient_whole(PositionSpan positions, std::vector<std::array<int, 3>>& faces,
                           std::vector<int>& source, bool orient);

/// The same a tile at a time (tiles.hpp's boxes, `tiles` of them), holding the edges of one
/// tile instead of the whole mesh's: the same result, or nothing (and `mesh` and `source`
/// untouched) where the tiles cannot tell it: when orienting, on a surface that cannot be
/// oriented or a closed one whose volume is too near 0 for its sign to be the same whatever
/// the order of the sum.
std::optional<OrientedFaces> orient_in_tiles(Mesh& mesh, std::vector<int>& source, bool orient,
                                             int tiles);

/// orient_in_tiles' work on tiles however they are cut, the faces staying where they are:
/// `num_faces` faces (after step 3) in `num_tiles` tiles, tile_of(b) being make_mesh_tile's
/// tile b (tiles.hpp) with a halo as wide as the longest edge of a face. OrientedFaces::flip is
/// for the faces that are not duplicates, in order; `duplicate` gets a mark for each face when
/// there are duplicates, else is left empty.
std::optional<OrientedFaces> orient_tiles(std::size_t num_faces, int num_tiles,
                                          const std::function<MeshTile(int)>& tile_of, bool orient,
                                          std::vector<char>& duplicate);

/// The tiles in which repair_soup_on_disk orients `num_faces` faces when asked for `asked`
/// tiles of at most about `most` faces: `asked` when that is enough (or `asked` is 1: the whole
/// mesh), else the least k * k or k * (k + 1) tiles, which make_tile_boxes cuts nearly square,
/// that hold num_faces / most.
int orientation_tiles(std::size_t num_faces, int asked, std::size_t most);

/// The square of the length of the face's longest edge.
inline double longest_edge2(const std::array<int, 3>& t, PositionSpan positions) {
    double longest2 = 0;
    for (int k = 0; k < 3; ++k)
        longest2 =
            std::max(longest2, (positions[t[k]] - positions[t[k == 2 ? 0 : k + 1]]).squaredNorm());
    return longest2;
}

/// Copies what steps (4) and (5) found into the report (all but the flips).
void count_orientation(const OrientedFaces& oriented, MeshRepairReport& report);

/// Step (6): the notes of what the repair changed or found.
Diagnostics repair_notes(const MeshRepairReport& report, int num_conflicts);

/// Drops the faces marked in `removed` from `faces` and their entries in `source` (unless it is
/// empty), keeping the order.
void remove_faces(std::vector<std::array<int, 3>>& faces, std::vector<int>& source,
                  const std::vector<char>& removed);

}  // namespace geotex::detail
