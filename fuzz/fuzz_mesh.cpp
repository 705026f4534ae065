#include "fuzz/fuzz_mesh.hpp"

#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>

#include "common/errors.hpp"
#include "geometry/mesh_io.hpp"
#include "geometry/mesh_repair.hpp"
#include "geometry/topology.hpp"

namespace geotex::fuzz {
namespace {

[[noreturn]] void fail(const char* what) {
    std::fprintf(stderr, "fuzz_mesh: invariant broken: %s\n", what);
    std::abort();
}

void require(bool ok, const char* what) {
    if (!ok) fail(what);
}

void check_soup(const MeshFile& file) {
    const PolygonSoup& soup = file.soup;
    require(!soup.face_offsets.empty() && soup.face_offsets.front() == 0,
            "face_offsets starts with 0");
    require(static_cast<std::size_t>(soup.face_offsets.back()) == soup.face_indices.size(),
            "face_offsets ends at the index count");
    for (std::size_t p = 1; p < soup.face_offsets.size(); ++p)
        require(soup.face_offsets[p - 1] <= soup.face_offsets[p], "face_offsets increasing");
    for (const FaceProperty& property : file.face_properties)
        require(property.values.size() == static_cast<std::size_t>(soup.num_polygons()),
                "one face property value per polygon");
    require(!file.format.empty(), "the format is named");
}

void check_repair(const PolygonSoup& soup, const MeshRepairResult& repaired) {
    const Mesh& mesh = repaired.mesh;
    require(mesh.num_faces() > 0, "repair_soup returns faces");
    require(repaired.source_polygon.size() == mesh.faces.size(), "source_polygon is #F");
    require(mesh.positions.size() <= soup.positions.size(), "no vertex is added");
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        const auto& t = mesh.faces[f];
        for (int v : t) require(v >= 0 && v < mesh.num_vertices(), "face index in range");
        require(t[0] != t[1] && t[1] != t[2] && t[0] != t[2], "no repeated corner");
        const int p = repaired.source_polygon[f];
        require(p >= 0 && p < soup.num_polygons(), "source polygon in range");
        if (f > 0) require(repaired.source_polygon[f - 1] <= p, "faces keep the polygon order");
    }
    for (const auto& v : mesh.positions) require(v.allFinite(), "finite positions");
}

void check_topology(const Mesh& mesh, const MeshTopology& t) {
    const std::size_t nv = mesh.positions.size(), nf = mesh.faces.size();
    require(t.vertex_neighbour_offsets.size() == nv + 1, "vertex_neighbour_offsets is #V + 1");
    require(t.vertex_face_offsets.size() == nv + 1, "vertex_face_offsets is #V + 1");
    require(t.face_neighbour_offsets.size() == nf + 1, "face_neighbour_offsets is #F + 1");
    require(t.vertex_faces.size() == 3 * nf, "three corners per face");
    require(t.vertex_on_boundary.size() == nv, "vertex_on_boundary is #V");
    for (int f = 0; f < mesh.num_faces(); ++f)
        for (int g : t.face_neighbours_of(f))
            require(g >= 0 && g < mesh.num_faces() && g != f, "face neighbour in range");
    for (int v = 0; v < mesh.num_vertices(); ++v)
        for (int u : t.neighbours(v))
            require(u >= 0 && u < mesh.num_vertices() && u != v, "vertex neighbour in range");
}

// The repaired mesh written as PLY reads back as the same triangles at the same positions.
void check_ply_round_trip(const Mesh& mesh, bool binary) {
    std::ostringstream out;
    PlyWriteOptions options;
    options.binary = binary;
    write_ply(out, mesh, {}, options);
    const MeshFile back = read_mesh_memory(out.str(), "round-trip.ply");
    require(back.soup.positions.size() == mesh.positions.size(), "round trip: vertex count");
    require(back.soup.num_polygons() == mesh.num_faces(), "round trip: face count");
    for (std::size_t v = 0; v < mesh.positions.size(); ++v)
        for (int k = 0; k < 3; ++k)
            require(
                std::memcmp(&back.soup.positions[v][k], &mesh.positions[v][k], sizeof(double)) == 0,
                "round trip: positions bit for bit");
    for (int f = 0; f < mesh.num_faces(); ++f) {
        require(back.soup.face_offsets[f + 1] - back.soup.face_offsets[f] == 3,
                "round trip: triangles");
        for (int k = 0; k < 3; ++k)
            require(back.soup.face_indices[back.soup.face_offsets[f] + k] == mesh.faces[f][k],
                    "round trip: face indices");
    }
}

}  // namespace

int run_mesh_input(const std::uint8_t* data, std::size_t size, const char* name) {
    // One thread: deterministic runs and no worker threads between inputs.
    static const auto one_thread =
        std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, 1);
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    MeshFile file;
    try {
        file = read_mesh_memory(bytes, name);
    } catch (const Error&) {
        return 0;
    }
    check_soup(file);

    MeshRepairResult repaired;
    try {
        repaired = repair_soup(file.soup);
    } catch (const InvalidInput&) {
        return 0;
    }
    check_repair(file.soup, repaired);

    // The repaired mesh is clean: every later stage must accept it.
    const MeshTopology topology = make_topology(repaired.mesh);
    check_topology(repaired.mesh, topology);
    try {
        make_mesh_metrics(repaired.mesh, topology);
    } catch (const InvalidInput&) {
        // A mesh whose vertices all coincide, or whose extent overflows, has no bounding box.
    }
    check_ply_round_trip(repaired.mesh, size % 2 == 0);
    return 0;
}

}  // namespace geotex::fuzz
