#pragma once
/// Adjacency of a triangle mesh in compressed rows: vertex neighbours, vertex faces,
/// edge-adjacent faces, boundary flags.

#include <vector>

#include "geometry/face_blocks.hpp"
#include "geometry/mesh.hpp"

namespace geotex {

/// A read-only view of a contiguous run of indices (one row of a compressed table).
struct IndexRange {
    const int* first = nullptr;
    const int* last = nullptr;
    const int* begin() const { return first; }
    const int* end() const { return last; }
    int size() const { return static_cast<int>(last - first); }
    int operator[](int i) const { return first[i]; }
};

/// Compressed-row adjacency of a mesh. Rows are sorted ascending, so every walk over them
/// is deterministic.
struct MeshTopology {
    std::vector<int> vertex_neighbour_offsets;  ///< #V + 1
    std::vector<int> vertex_neighbours;         ///< vertices sharing an edge with each vertex
    std::vector<int> vertex_face_offsets;       ///< #V + 1
    std::vector<int> vertex_faces;              ///< faces incident to each vertex
    std::vector<int> face_neighbour_offsets;    ///< #F + 1
    std::vector<int> face_neighbours;      ///< faces sharing an edge with each face (more than 3
                                           ///< around non-manifold edges)
    std::vector<char> vertex_on_boundary;  ///< #V: 1 if on an edge with one face, or on a
                                           ///< non-manifold edge
    int num_boundary_edges = 0;
    int num_non_manifold_edges = 0;

    IndexRange neighbours(int v) const {
        return {vertex_neighbours.data() + vertex_neighbour_offsets[v],
                vertex_neighbours.data() + vertex_neighbour_offsets[v + 1]};
    }
    IndexRange faces_of(int v) const {
        return {vertex_faces.data() + vertex_face_offsets[v],
                vertex_faces.data() + vertex_face_offsets[v + 1]};
    }
    IndexRange face_neighbours_of(int f) const {
        return {face_neighbours.data() + face_neighbour_offsets[f],
                face_neighbours.data() + face_neighbour_offsets[f + 1]};
    }
};

/// Which rows make_topology builds:
/// - All;
/// - WithoutFaceNeighbours: face_neighbour_offsets and face_neighbours left empty (16 bytes a
///   face, of about 46 that the tables hold), which only the texel regions and the rims walk;
///   a tile's features job measures the curvature without them;
/// - VertexNeighbours: the vertices' neighbours, the boundary flags and the edge counts alone
///   (the vertices' faces, 14 bytes a face, are made to find them and let go), which is all the
///   smoothing's disc walks read: a tile's depth job smooths with these.
/// The functions that read rows a topology lacks refuse it (expect_vertex_faces).
enum class TopologyRows { All, WithoutFaceNeighbours, VertexNeighbours };

/// Builds the adjacency tables. Linear in the mesh size; parallel over vertices and faces.
/// Throws InvalidInput if a face index is out of range.
MeshTopology make_topology(const Mesh& mesh, TopologyRows rows = TopologyRows::All);

/// Throws InvalidInput, its message starting with `who`, unless `topology` holds the rows of
/// each vertex's faces over `mesh` (it was made with other rows than VertexNeighbours).
void expect_vertex_faces(const Mesh& mesh, const MeshTopology& topology, const char* who);

/// Connected components of the vertices, joined by the faces' edges.
struct VertexComponents {
    std::vector<int> component;  ///< #V, in [0, num_components), numbered by their first vertex
    int num_components = 0;      ///< an isolated vertex is a component of its own
};

/// The connected components of the mesh's vertices. Linear in the mesh size. Face indices
/// must be in range (make_topology checks them).
VertexComponents vertex_components(const Mesh& mesh);
/// The same for a mesh of `num_vertices` vertices whose `num_faces` faces are read a block at a
/// time; throws what `faces` throws.
VertexComponents vertex_components(int num_vertices, const FaceBlockReader& faces,
                                   std::size_t num_faces);

/// Per-element measures used by several stages.
struct MeshMetrics {
    std::vector<double> face_area;               ///< #F
    std::vector<Eigen::Vector3d> vertex_normal;  ///< #V, unit, area-weighted face normals
    std::vector<double> vertex_area;             ///< #V, one third of the incident face areas
    Eigen::Vector3d bbox_min = Eigen::Vector3d::Zero();
    Eigen::Vector3d bbox_max = Eigen::Vector3d::Zero();
    double largest_side = 0;      ///< largest bounding-box side, mesh units
    double mean_edge_length = 0;  ///< mesh units
    int num_vertices = 0;         ///< #V of the mesh measured, also where the arrays are not made
    int num_faces = 0;            ///< #F of the mesh measured, likewise
};

/// Normals, areas and the bounding box. Throws InvalidInput on an empty mesh or when the
/// bounding box has zero size.
MeshMetrics make_mesh_metrics(const Mesh& mesh, const MeshTopology& topology);
/// The same without the topology (for a mesh whose topology is never built whole, tiles.hpp):
/// the same bits, one face at a time rather than in parallel over vertices.
MeshMetrics make_mesh_metrics(const Mesh& mesh);
/// Only the bounding box, the largest side and the mean edge length of make_mesh_metrics, the
/// same bits, without its arrays (#V and #F) or their memory: what a tiled run's jobs need.
/// Throws as make_mesh_metrics.
MeshMetrics make_mesh_extent(const Mesh& mesh);

/// make_mesh_extent over faces given a block at a time, in face order, the same bits: for the
/// join of a tiled run, which holds the positions and reads the faces from disk.
///
///     MeshExtentSum sum(positions);
///     for (each block of faces, in order) sum.add(block);
///     MeshMetrics m = sum.finish();
class MeshExtentSum {
  public:
    /// `positions` must outlive the sum.
    explicit MeshExtentSum(PositionSpan positions) : positions_(positions) {}
    /// Adds the next faces; their indices must be below #V.
    void add(const std::vector<std::array<int, 3>>& faces);
    /// The extent of the faces added (num_faces set too). Throws as make_mesh_extent.
    MeshMetrics finish() const;

  private:
    PositionSpan positions_;
    double perimeters_ = 0;  // in face order, as make_mesh_metrics adds them
    long long faces_ = 0;
};

}  // namespace geotex
