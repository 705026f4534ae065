// Real-scan geometry: open borders, holes, several components, non-manifold edges,
// duplicated and isolated vertices, zero-area faces, flipped faces and units. Every mesh
// is built here from the synthetic sphere-1, whose ground truth says where the details are.
#include <algorithm>
#include <catch2/catch.hpp>
#include <map>
#include <set>

#include "geometry/evaluation.hpp"
#include "geometry/mesh_repair.hpp"
#include "geometry/segmentation.hpp"
#include "geometry/synth.hpp"
#include "tests/fixtures.hpp"

using namespace geotex;

namespace {

/// Sphere-1 at level 6 (81,920 faces): 88 shapes; cached, the tests only read it.
const SyntheticMesh& sphere1() {
    static const SyntheticMesh s = [] {
        SynthParams p;
        p.level = 6;
        return make_synthetic_sphere(p);
    }();
    return s;
}

/// A soup of the faces of `mesh` kept by `keep`, with all vertices (unused ones stay isolated).
struct Soup {
    PolygonSoup soup;
    std::vector<int> face_shape;  // ground truth per polygon
};

Soup soup_of(const SyntheticMesh& s, const std::function<bool(int)>& keep) {
    Soup out;
    out.soup.positions = s.mesh.positions;
    for (int f = 0; f < s.mesh.num_faces(); ++f) {
        if (!keep(f)) continue;
        for (int v : s.mesh.faces[f]) out.soup.face_indices.push_back(v);
        out.soup.face_offsets.push_back(static_cast<int>(out.soup.face_indices.size()));
        out.face_shape.push_back(s.face_shape[f]);
    }
    return out;
}

struct Outcome {
    MeshRepairResult repaired;
    Segmentation seg;
    std::vector<int> face_shape;  // ground truth on the repaired faces
    int spurious = 0;             // texels with most faces off every shape
    std::set<int> shapes_found;   // shapes that own most faces of some texel
    int shapes_present = 0;       // shapes with at least one face in the mesh
};

Outcome segment(const Soup& in, double radius = 0) {
    Outcome o;
    o.repaired = repair_soup(in.soup);
    for (int f = 0; f < o.repaired.mesh.num_faces(); ++f)
        o.face_shape.push_back(in.face_shape[o.repaired.source_polygon[f]]);
    SegmentationParams p;
    p.radius_rel = 0.04;
    p.radius = radius;
    o.seg = run_segmentation(o.repaired.mesh, p);
    for (const Texel& t : o.seg.texels) {
        std::map<int, int> votes;
        for (int f : t.faces) ++votes[o.face_shape[f]];
        const auto best = std::max_element(votes.begin(), votes.end(),
                                           [](auto& a, auto& b) { return a.second < b.second; });
        if (best->first < 0)
            ++o.spurious;
        else
            o.shapes_found.insert(best->first);
    }
    o.shapes_present =
        static_cast<int>(std::set<int>(o.face_shape.begin(), o.face_shape.end()).size() -
                         (std::count(o.face_shape.begin(), o.face_shape.end(), -1) > 0 ? 1 : 0));
    return o;
}

}  // namespace

TEST_CASE("real scans: a hemisphere's open border makes no texel", "[geometry][realscan]") {
    const auto& s = sphere1();
    const Soup half = soup_of(s, [&](int f) {
        const auto& t = s.mesh.faces[f];
        return (s.mesh.positions[t[0]] + s.mesh.positions[t[1]] + s.mesh.positions[t[2]]).z() > 0;
    });
    const Outcome o = segment(half, 0.04 * 2.0);  // the whole sphere's scale, in mesh units
    INFO("texels " << o.seg.texels.size() << " spurious " << o.spurious << " shapes "
                   << o.shapes_found.size() << " of " << o.shapes_present);
    CHECK(o.repaired.report.num_boundary_edges > 0);
    CHECK(o.spurious == 0);
    CHECK(static_cast<int>(o.shapes_found.size()) >= o.shapes_present - 4);
}

TEST_CASE("real scans: a hole in the surface makes no texel", "[geometry][realscan]") {
    const auto& s = sphere1();
    // A hole of radius 0.3 around a direction that no shape covers, and one that cuts
    // through shapes: the hole's rim is a border like any other.
    for (const Eigen::Vector3d& dir :
         {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0.6, -0.48, 0.64)}) {
        const Soup holed = soup_of(s, [&](int f) {
            const auto& t = s.mesh.faces[f];
            const Eigen::Vector3d c =
                (s.mesh.positions[t[0]] + s.mesh.positions[t[1]] + s.mesh.positions[t[2]]) / 3;
            return (c.normalized() - dir.normalized()).norm() > 0.3;
        });
        const Outcome o = segment(holed);
        INFO("hole at " << dir.transpose() << ": texels " << o.seg.texels.size() << " spurious "
                        << o.spurious << " shapes " << o.shapes_found.size() << " of "
                        << o.shapes_present);
        CHECK(o.repaired.report.num_boundary_edges > 0);
        CHECK(o.spurious == 0);
        CHECK(static_cast<int>(o.shapes_found.size()) >= o.shapes_present - 2);
    }
}

TEST_CASE("real scans: two components close together are analysed apart", "[geometry][realscan]") {
    const auto& s = sphere1();
    const Soup one = soup_of(s, [](int) { return true; });
    const Outcome alone = segment(one, 0.08);
    REQUIRE(alone.seg.texels.size() == 88);
    // The second copy 2.03 away in the direction of a shape's centre: that raised shape
    // (height 0.02) faces the other sphere across a gap of 0.01, far less than r = 0.08.
    Soup two = one;
    const int nv = static_cast<int>(one.soup.positions.size());
    const Eigen::Vector3d shift = 2.03 * s.shapes[0].center.normalized();
    for (int v = 0; v < nv; ++v) two.soup.positions.push_back(one.soup.positions[v] + shift);
    for (int i : one.soup.face_indices) two.soup.face_indices.push_back(i + nv);
    for (std::size_t p = 1; p < one.soup.face_offsets.size(); ++p)
        two.soup.face_offsets.push_back(one.soup.face_offsets[p] +
                                        static_cast<int>(one.soup.face_indices.size()));
    two.face_shape.insert(two.face_shape.end(), one.face_shape.begin(), one.face_shape.end());
    const Outcome both = segment(two, 0.08);
    CHECK(both.repaired.report.num_components == 2);
    REQUIRE(both.seg.texels.size() == 2 * alone.seg.texels.size());
    // Each copy gets exactly the texels it gets alone: nothing is measured or grown across
    // the gap.
    const int nf = s.mesh.num_faces();
    std::set<std::vector<int>> expected, first, second;
    for (const Texel& t : alone.seg.texels) expected.insert(t.faces);
    for (const Texel& t : both.seg.texels) {
        const bool in_first = t.faces.front() < nf;
        CHECK(in_first == (t.faces.back() < nf));  // no texel spans both
        std::vector<int> local = t.faces;
        if (!in_first)
            for (int& f : local) f -= nf;
        (in_first ? first : second).insert(local);
    }
    CHECK(first == expected);
    CHECK(second == expected);
}

TEST_CASE("real scans: a non-manifold fin is reported and changes nothing elsewhere",
          "[geometry][realscan]") {
    const auto& s = sphere1();
    Soup fin = soup_of(s, [](int) { return true; });
    // Two extra triangles on one mesh edge far from the shapes: that edge then has four faces.
    const Outcome clean = segment(fin, 0.08);
    int edge_face = -1;
    for (int f = 0; f < s.mesh.num_faces() && edge_face < 0; ++f)
        if (s.face_shape[f] < 0 && s.vertex_grey[s.mesh.faces[f][0]] == 0 &&
            s.mesh.positions[s.mesh.faces[f][0]].z() > 0.9)
            edge_face = f;
    REQUIRE(edge_face >= 0);
    const int a = s.mesh.faces[edge_face][0], b = s.mesh.faces[edge_face][1];
    const Eigen::Vector3d mid = (s.mesh.positions[a] + s.mesh.positions[b]) / 2;
    for (const double h : {0.05, -0.05}) {
        fin.soup.positions.push_back(mid + h * Eigen::Vector3d(0, 1, 0) + 0.05 * mid.normalized());
        fin.soup.face_indices.insert(fin.soup.face_indices.end(),
                                     {a, b, static_cast<int>(fin.soup.positions.size()) - 1});
        fin.soup.face_offsets.push_back(static_cast<int>(fin.soup.face_indices.size()));
        fin.face_shape.push_back(-1);
    }
    const Outcome o = segment(fin, 0.08);
    CHECK(o.repaired.report.num_non_manifold_edges == 1);
    CHECK(o.spurious == 0);
    CHECK(o.shapes_found == clean.shapes_found);
}

TEST_CASE("real scans: duplicated and isolated vertices, zero-area and flipped faces",
          "[geometry][realscan]") {
    const auto& s = sphere1();
    const Soup clean = soup_of(s, [](int) { return true; });
    const Outcome ref = segment(clean, 0.08);
    // Every face gets its own copy of its first vertex (a soup as STL files hold it), every
    // tenth face is flipped, a zero-area face and 100 unused vertices are added.
    Soup messy = clean;
    for (int p = 0; p < clean.soup.num_polygons(); ++p) {
        int* f = &messy.soup.face_indices[clean.soup.face_offsets[p]];
        messy.soup.positions.push_back(messy.soup.positions[f[0]]);
        f[0] = static_cast<int>(messy.soup.positions.size()) - 1;
        if (p % 10 == 3) std::swap(f[1], f[2]);
    }
    const int nv = static_cast<int>(messy.soup.positions.size());
    for (const double x : {10.0, 11.0, 12.0})
        messy.soup.positions.push_back(Eigen::Vector3d(x, 0, 0));
    messy.soup.face_indices.insert(messy.soup.face_indices.end(),
                                   {nv, nv + 1, nv + 2});  // zero area
    messy.soup.face_offsets.push_back(static_cast<int>(messy.soup.face_indices.size()));
    messy.face_shape.push_back(-1);
    for (int i = 0; i < 100; ++i) messy.soup.positions.push_back(Eigen::Vector3d(5 + i, 1, 0));
    const Outcome o = segment(messy, 0.08);
    CHECK(o.repaired.report.num_duplicate_vertices_merged == clean.soup.num_polygons());
    CHECK(o.repaired.report.num_faces_flipped > 0);
    CHECK(o.repaired.report.num_degenerate_faces_removed == 1);
    CHECK(o.repaired.report.num_isolated_vertices >= 103);
    REQUIRE(o.seg.texels.size() == ref.seg.texels.size());
    CHECK(o.shapes_found == ref.shapes_found);
    CHECK(o.spurious == 0);
}

TEST_CASE("real scans: millimetres or metres give the same texels", "[geometry][realscan]") {
    const auto& s = sphere1();
    const Soup m = soup_of(s, [](int) { return true; });
    const Outcome ref = segment(m);  // relative scale 4 %
    for (const double k : {1000.0, 0.001}) {
        Soup scaled = m;
        for (auto& p : scaled.soup.positions) p *= k;
        const Outcome o = segment(scaled);
        REQUIRE(o.seg.texels.size() == ref.seg.texels.size());
        for (std::size_t i = 0; i < o.seg.texels.size(); ++i)
            CHECK(o.seg.texels[i].faces == ref.seg.texels[i].faces);
        CHECK(o.seg.texel_texture == ref.seg.texel_texture);
    }
}
