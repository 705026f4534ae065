#include <catch2/catch.hpp>
#include <cmath>

#include "common/errors.hpp"
#include "geometry/curvature.hpp"
#include "geometry/icosphere.hpp"
#include "geometry/texels.hpp"
#include "geometry/topology.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;

TEST_CASE("make_icosphere: counts and outward faces", "[geometry][topology]") {
    for (int level : {0, 1, 3}) {
        const Mesh m = make_icosphere(level);
        const int faces = 20 * (1 << (2 * level));
        CHECK(m.num_faces() == faces);
        CHECK(m.num_vertices() == faces / 2 + 2);  // Euler: V - E + F = 2, E = 3F/2
        CHECK(test::signed_volume(m) > 0);
        for (const auto& p : m.positions) CHECK(p.norm() == Approx(1.0).epsilon(1e-12));
    }
    REQUIRE_THROWS_AS(make_icosphere(12), InvalidInput);
    REQUIRE_THROWS_AS(make_icosphere(-1), InvalidInput);
}

TEST_CASE("make_topology: closed sphere has valence 5 or 6 and no boundary",
          "[geometry][topology]") {
    const Mesh m = make_icosphere(3);
    const MeshTopology t = make_topology(m);
    CHECK(t.num_boundary_edges == 0);
    CHECK(t.num_non_manifold_edges == 0);
    int valence5 = 0;
    for (int v = 0; v < m.num_vertices(); ++v) {
        const int n = t.neighbours(v).size();
        CHECK((n == 5 || n == 6));
        valence5 += n == 5;
        CHECK(t.faces_of(v).size() == n);
        CHECK_FALSE(t.vertex_on_boundary[v]);
    }
    CHECK(valence5 == 12);  // the icosahedron's vertices
    for (int f = 0; f < m.num_faces(); ++f) CHECK(t.face_neighbours_of(f).size() == 3);
}

TEST_CASE("make_topology: grid boundary and non-manifold edge counted", "[geometry][topology]") {
    const int n = 6;
    Mesh m = test::make_grid(n, 1.0);
    MeshTopology t = make_topology(m);
    CHECK(t.num_boundary_edges == 4 * n);
    int on_boundary = 0;
    for (char b : t.vertex_on_boundary) on_boundary += b;
    CHECK(on_boundary == 4 * n);
    // A third face on an interior edge makes it non-manifold.
    const auto f0 = m.faces[0];
    m.positions.emplace_back(0, 0, 1);
    m.faces.push_back({f0[0], f0[2], m.num_vertices() - 1});
    t = make_topology(m);
    CHECK(t.num_non_manifold_edges == 1);
}

TEST_CASE("make_topology with fewer rows: the same rows it makes, refused where rows lack",
          "[geometry][topology]") {
    // A grid with a boundary, and a third face on an interior edge (non-manifold).
    Mesh m = test::make_grid(6, 1.0);
    const auto f0 = m.faces[0];
    m.positions.emplace_back(0, 0, 1);
    m.faces.push_back({f0[0], f0[2], m.num_vertices() - 1});
    const MeshTopology all = make_topology(m);
    CHECK(all.num_boundary_edges == 4 * 6 + 2);  // the grid's rim and the third face's free edges
    CHECK(all.num_non_manifold_edges == 1);
    // The vertices' neighbours and the boundary, which every choice of rows makes.
    const auto check_vertex_rows = [&](const MeshTopology& t) {
        CHECK(t.face_neighbour_offsets.empty());
        CHECK(t.face_neighbours.empty());
        CHECK(t.vertex_neighbour_offsets == all.vertex_neighbour_offsets);
        CHECK(t.vertex_neighbours == all.vertex_neighbours);
        CHECK(t.vertex_on_boundary == all.vertex_on_boundary);
        CHECK(t.num_boundary_edges == all.num_boundary_edges);
        CHECK(t.num_non_manifold_edges == all.num_non_manifold_edges);
    };
    const MeshTopology some = make_topology(m, TopologyRows::WithoutFaceNeighbours);
    check_vertex_rows(some);
    CHECK(some.vertex_face_offsets == all.vertex_face_offsets);
    CHECK(some.vertex_faces == all.vertex_faces);
    // The texel regions walk the faces' neighbours: such a topology is refused there.
    DepthMap depth;
    depth.vertex_depth.assign(m.positions.size(), 0.0);
    depth.face_depth.assign(m.faces.size(), 0.0);
    TexelParams params;
    params.radius = 0.1;
    CHECK_THROWS_WITH(make_texels(m, some, depth, params),
                      Catch::Contains("has no faces' neighbours"));
    CHECK_NOTHROW(make_texels(m, all, depth, params));

    // The vertices' neighbours alone: what the smoothing walks, the same rows and boundary.
    const MeshTopology walks = make_topology(m, TopologyRows::VertexNeighbours);
    check_vertex_rows(walks);
    CHECK(walks.vertex_face_offsets.empty());
    CHECK(walks.vertex_faces.empty());
    // What reads the vertices' faces refuses it, with its own name.
    CHECK_THROWS_WITH(make_mesh_metrics(m, walks), Catch::Contains("mesh metrics: the topology"));
    const std::vector<Eigen::Vector3d> normals = make_mesh_metrics(m, all).vertex_normal;
    CurvatureParams cp;
    cp.radius = 0.5;
    CHECK_THROWS_WITH(make_curvature(m, walks, normals, cp),
                      Catch::Contains("curvature: the topology"));
    CHECK_NOTHROW(make_curvature(m, some, normals, cp));
    CHECK_THROWS_WITH(make_texels(m, walks, depth, params),
                      Catch::Contains("has no faces' neighbours"));
}

TEST_CASE("make_mesh_metrics without the topology: the same bits as over it",
          "[geometry][topology]") {
    // An irregular surface, so that the normals' sums depend on the order of their terms.
    Mesh m = test::make_grid(9, 1.0);
    for (std::size_t v = 0; v < m.positions.size(); ++v)
        m.positions[v].z() =
            0.3 * std::sin(1.7 * m.positions[v].x() + 0.9 * v) * std::cos(2.3 * m.positions[v].y());
    const MeshMetrics over = make_mesh_metrics(m, make_topology(m));
    const MeshMetrics without = make_mesh_metrics(m);
    REQUIRE(over.vertex_normal.size() == without.vertex_normal.size());
    for (std::size_t v = 0; v < over.vertex_normal.size(); ++v) {
        CHECK(over.vertex_normal[v].x() == without.vertex_normal[v].x());
        CHECK(over.vertex_normal[v].y() == without.vertex_normal[v].y());
        CHECK(over.vertex_normal[v].z() == without.vertex_normal[v].z());
    }
    CHECK(over.vertex_area == without.vertex_area);
    CHECK(over.face_area == without.face_area);
    CHECK(over.mean_edge_length == without.mean_edge_length);
}

TEST_CASE("make_topology: index out of range throws", "[geometry][topology]") {
    Mesh m = test::make_grid(2, 1.0);
    m.faces.push_back({0, 1, 99});
    REQUIRE_THROWS_AS(make_topology(m), InvalidInput);
}

TEST_CASE("make_mesh_metrics: areas, normals and bounding box", "[geometry][topology]") {
    const Mesh m = test::make_grid(4, 2.0);
    const MeshMetrics mm = make_mesh_metrics(m, make_topology(m));
    double area = 0;
    for (double a : mm.face_area) area += a;
    CHECK(area == Approx(4.0));
    double vertex_area = 0;
    for (double a : mm.vertex_area) vertex_area += a;
    CHECK(vertex_area == Approx(4.0));
    for (const auto& n : mm.vertex_normal) CHECK(n.z() == Approx(1.0));
    CHECK(mm.largest_side == Approx(2.0));
    CHECK(mm.mean_edge_length > 0.5);
    Mesh point;
    point.positions = {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}};
    point.faces = {{0, 1, 2}};
    REQUIRE_THROWS_AS(make_mesh_metrics(point, make_topology(point)), InvalidInput);
}

TEST_CASE("make_mesh_extent: make_mesh_metrics' box, side and mean edge, bit for bit",
          "[geometry][topology]") {
    // An uneven mesh, so that the mean edge length depends on the order of the sum.
    Mesh m = make_icosphere(3);
    for (std::size_t v = 0; v < m.positions.size(); ++v)
        m.positions[v] *= 1.0 + 0.1 * std::sin(1.7 * static_cast<double>(v));
    const MeshMetrics full = make_mesh_metrics(m, make_topology(m));
    const MeshMetrics extent = make_mesh_extent(m);
    CHECK(extent.bbox_min == full.bbox_min);
    CHECK(extent.bbox_max == full.bbox_max);
    CHECK(extent.largest_side == full.largest_side);
    CHECK(extent.mean_edge_length == full.mean_edge_length);
    CHECK(extent.mean_edge_length > 0);
    CHECK(extent.vertex_normal.empty());
    CHECK(extent.face_area.empty());
    REQUIRE_THROWS_AS(make_mesh_extent(Mesh()), InvalidInput);
    Mesh point;
    point.positions = {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}};
    point.faces = {{0, 1, 2}};
    REQUIRE_THROWS_AS(make_mesh_extent(point), InvalidInput);
}

TEST_CASE("MeshExtentSum: faces in blocks of any size give make_mesh_extent's bits",
          "[geometry][topology]") {
    Mesh m = make_icosphere(3);
    for (std::size_t v = 0; v < m.positions.size(); ++v)
        m.positions[v] *= 1.0 + 0.1 * std::sin(1.7 * static_cast<double>(v));
    const MeshMetrics whole = make_mesh_extent(m);
    CHECK(whole.num_faces == m.num_faces());
    CHECK(whole.num_vertices == m.num_vertices());
    for (std::size_t block : {std::size_t{1}, std::size_t{7}, std::size_t{300}}) {
        MeshExtentSum sum(m.positions);
        for (std::size_t first = 0; first < m.faces.size(); first += block) {
            const auto begin = m.faces.begin() + static_cast<std::ptrdiff_t>(first);
            sum.add({begin,
                     begin + static_cast<std::ptrdiff_t>(std::min(block, m.faces.size() - first))});
        }
        const MeshMetrics blocks = sum.finish();
        CHECK(blocks.mean_edge_length == whole.mean_edge_length);
        CHECK(blocks.largest_side == whole.largest_side);
        CHECK(blocks.num_faces == whole.num_faces);
    }
    // No face added: refused as an empty mesh.
    CHECK_THROWS_AS(MeshExtentSum(m.positions).finish(), InvalidInput);
}

TEST_CASE(
    "vertex_components: pieces joined by faces, isolated vertices alone, numbered by first vertex",
    "[geometry][topology]") {
    // Vertex 0 is isolated; triangles {1, 4, 5} and {4, 5, 6} share an edge; triangle
    // {2, 3, 7} is apart.
    Mesh m;
    for (int v = 0; v < 8; ++v) m.positions.emplace_back(v, v % 3, 0.0);
    m.faces = {{1, 4, 5}, {2, 3, 7}, {4, 5, 6}};
    const VertexComponents c = vertex_components(m);
    CHECK(c.num_components == 3);
    CHECK(c.component == std::vector<int>{0, 1, 2, 2, 1, 1, 1, 2});
    CHECK(vertex_components(make_icosphere(2)).num_components == 1);
    CHECK(vertex_components(Mesh()).num_components == 0);
}
