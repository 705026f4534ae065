// geotex_simplify: the mesh-density experiment of paper §4.1.3 (Fig. 9). Simplifies a
// synthetic sphere from `geotex synth` to about N triangles with CGAL's edge collapse and
// moves its ground truth to the simplified mesh by the closest original vertex.
//
//   geotex_simplify IN.ply IN.truth.json N OUT.ply OUT.truth.json
//
// Ground-truth transfer (the paper: "the greyscale value of each vertex in simplified meshes
// has been obtained by considering the value associated to the closest vertex in the
// original mesh"): the synthetic sphere is rebuilt from the parameters stored in
// IN.truth.json (checked against IN.ply and its face labels), which gives each original
// vertex its grey value g in [0, 1] and the shape that owns it. Each simplified vertex takes
// g and the owner of its closest original vertex (Euclidean, k-d tree). A simplified face is
// foreground when the mean g of its three vertices exceeds 0.5 and then belongs to the owner
// of its greyest vertex: the same rule as `geotex synth` on the original mesh.
//
// Exit codes: 0 ok, 1 usage, 2 bad input, 3 processing failed, 4 cannot write.

#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/mesh_io.hpp"
#include "geometry/synth.hpp"

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using PointMap = CGAL::Pointer_property_map<Point>::type;
using Traits = CGAL::Search_traits_adapter<std::size_t, PointMap, CGAL::Search_traits_3<Kernel>>;
using Search = CGAL::Orthogonal_k_neighbor_search<Traits>;
namespace SMS = CGAL::Surface_mesh_simplification;

struct Failure : std::runtime_error {
    int code;
    Failure(int c, const std::string& what) : std::runtime_error(what), code(c) {}
};

geotex::Mesh read_triangles(const std::string& path) {
    const geotex::MeshFile file = geotex::read_mesh_file(path);
    geotex::Mesh mesh;
    mesh.positions = file.soup.positions;
    for (int p = 0; p < file.soup.num_polygons(); ++p) {
        const int b = file.soup.face_offsets[p];
        if (file.soup.face_offsets[p + 1] - b != 3)
            throw Failure(2, path + ": not a triangle mesh");
        mesh.faces.push_back({file.soup.face_indices[b], file.soup.face_indices[b + 1],
                              file.soup.face_indices[b + 2]});
    }
    return mesh;
}

geotex::SynthParams synth_params(const nlohmann::json& p) {
    geotex::SynthParams s;
    s.level = p.at("level").get<int>();
    s.num_big_discs = p.at("big_discs").get<int>();
    s.num_small_discs = p.at("small_discs").get<int>();
    s.num_squares = p.at("squares").get<int>();
    s.num_rectangles = p.at("rectangles").get<int>();
    s.displacement_rel = p.at("displacement_rel").get<double>();
    s.edge_width_rel = p.at("edge_width_rel").get<double>();
    s.gap_rel = p.at("gap_rel").get<double>();
    s.noise_percent = p.at("noise_percent").get<double>();
    s.engraved_fraction = p.at("engraved_fraction").get<double>();
    s.layout_seed = p.at("layout_seed").get<std::uint64_t>();
    s.noise_seed = p.at("noise_seed").get<std::uint64_t>();
    return s;
}

int run(int argc, char** argv) {
    if (argc != 6)
        throw Failure(1, "usage: geotex_simplify IN.ply IN.truth.json N OUT.ply OUT.truth.json");
    const std::string in_mesh = argv[1], in_truth = argv[2], out_mesh = argv[4],
                      out_truth = argv[5];
    long target = 0;
    try {
        target = std::stol(argv[3]);
    } catch (const std::exception&) {
        target = 0;
    }
    if (target < 4) throw Failure(1, "N must be an integer >= 4 (target number of triangles)");

    const geotex::Mesh original = read_triangles(in_mesh);
    nlohmann::json truth;
    {
        std::ifstream in(in_truth);
        if (!in) throw Failure(2, in_truth + ": cannot open");
        try {
            truth = nlohmann::json::parse(in);
        } catch (const nlohmann::json::exception& e) {
            throw Failure(2, in_truth + ": " + e.what());
        }
    }
    geotex::SyntheticMesh synth;
    try {
        synth = geotex::make_synthetic_sphere(synth_params(truth.at("parameters")));
    } catch (const std::exception& e) {
        throw Failure(
            2, in_truth + ": cannot rebuild the synthetic sphere from its parameters: " + e.what());
    }
    if (synth.mesh.num_vertices() != original.num_vertices() ||
        synth.mesh.faces != original.faces ||
        synth.face_shape != truth.at("face_shape").get<std::vector<int>>())
        throw Failure(
            2, in_truth + ": its parameters do not rebuild " + in_mesh + " and its face labels");
    double worst = 0;
    for (int v = 0; v < original.num_vertices(); ++v)
        worst = std::max(worst, (synth.mesh.positions[v] - original.positions[v]).norm());
    if (worst > 1e-5)
        throw Failure(2, in_truth + ": its parameters do not rebuild the vertices of " + in_mesh);

    // Edge collapse with CGAL's defaults (Lindstrom-Turk cost and placement). A closed
    // triangle mesh has 3F/2 edges, so stopping at 3N/2 edges leaves about N faces.
    SurfaceMesh sm;
    {
        std::vector<SurfaceMesh::Vertex_index> vid;
        vid.reserve(original.positions.size());
        for (const auto& p : original.positions)
            vid.push_back(sm.add_vertex(Point(p.x(), p.y(), p.z())));
        for (const auto& f : original.faces)
            if (sm.add_face(vid[f[0]], vid[f[1]], vid[f[2]]) == SurfaceMesh::null_face())
                throw Failure(2, in_mesh + ": not an oriented 2-manifold; cannot simplify");
    }
    SMS::Count_stop_predicate<SurfaceMesh> stop(static_cast<std::size_t>(target) * 3 / 2);
    SMS::edge_collapse(sm, stop);
    sm.collect_garbage();

    geotex::Mesh simple;
    for (auto v : sm.vertices()) {
        const Point& p = sm.point(v);
        simple.positions.emplace_back(p.x(), p.y(), p.z());
    }
    for (auto f : sm.faces()) {
        std::array<int, 3> tri{};
        int k = 0;
        for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
            if (k == 3) throw Failure(3, "edge collapse produced a non-triangle face");
            tri[k++] = static_cast<int>(v);
        }
        simple.faces.push_back(tri);
    }

    // Ground truth by the closest original vertex.
    std::vector<Point> points;
    points.reserve(original.positions.size());
    for (const auto& p : original.positions) points.emplace_back(p.x(), p.y(), p.z());
    std::vector<std::size_t> indices(points.size());
    for (std::size_t i = 0; i < indices.size(); ++i) indices[i] = i;
    const PointMap point_map(points.data());
    Search::Tree tree(indices.begin(), indices.end(), Search::Tree::Splitter(), Traits(point_map));
    const Search::Distance distance(point_map);
    std::vector<double> grey(simple.positions.size());
    std::vector<int> owner(simple.positions.size());
    for (std::size_t v = 0; v < simple.positions.size(); ++v) {
        const auto& p = simple.positions[v];
        Search search(tree, Point(p.x(), p.y(), p.z()), 1, 0, true, distance);
        const std::size_t nearest = search.begin()->first;
        grey[v] = synth.vertex_grey[nearest];
        owner[v] = synth.vertex_shape[nearest];
    }
    std::vector<int> face_shape(simple.faces.size(), -1);
    int foreground = 0;
    for (std::size_t f = 0; f < simple.faces.size(); ++f) {
        const auto& fv = simple.faces[f];
        if ((grey[fv[0]] + grey[fv[1]] + grey[fv[2]]) / 3.0 <= 0.5) continue;
        int best = fv[0];
        for (int v : fv)
            if (grey[v] > grey[best]) best = v;
        face_shape[f] = owner[best];
        ++foreground;
    }

    {
        std::ofstream out(out_mesh, std::ios::binary);
        if (!out) throw Failure(4, out_mesh + ": cannot write");
        geotex::PlyWriteOptions w;
        w.comments = {"geotex_simplify: " + in_mesh + " simplified to " +
                      std::to_string(simple.num_faces()) +
                      " faces (CGAL edge collapse, Lindstrom-Turk)"};
        geotex::write_ply(out, simple, {}, w);
        if (!out) throw Failure(4, out_mesh + ": write failed");
    }
    nlohmann::json t = truth;
    const auto slash = out_mesh.find_last_of('/');
    t["mesh"] = {{"file", slash == std::string::npos ? out_mesh : out_mesh.substr(slash + 1)},
                 {"vertices", simple.num_vertices()},
                 {"faces", simple.num_faces()}};
    t["simplification"] = {
        {"source", in_mesh},
        {"source_faces", original.num_faces()},
        {"target_faces", target},
        {"method", "CGAL::Surface_mesh_simplification::edge_collapse, Lindstrom-Turk"},
        {"transfer",
         "grey and owner of the closest original vertex; face foreground when "
         "the mean grey of its vertices > 0.5, owner of its greyest vertex"}};
    t["face_shape"] = face_shape;
    {
        std::ofstream out(out_truth);
        if (!out) throw Failure(4, out_truth + ": cannot write");
        out << t.dump(2) << '\n';
        if (!out) throw Failure(4, out_truth + ": write failed");
    }
    std::printf("simplified %d -> %d faces (%d vertices), %d foreground faces; wrote %s and %s\n",
                original.num_faces(), simple.num_faces(), simple.num_vertices(), foreground,
                out_mesh.c_str(), out_truth.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const Failure& e) {
        std::fprintf(stderr, "geotex_simplify: error: %s\n", e.what());
        return e.code;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "geotex_simplify: error: %s\n", e.what());
        return 3;
    }
}
