// geotex.read_mesh: a mesh file as the command reads it, as numpy arrays.

#include <memory>
#include <string>

#include "arrays.hpp"
#include "bindings.hpp"
#include "errors.hpp"
#include "geometry/mesh_io.hpp"
#include "geometry/mesh_repair.hpp"
#include "geometry/unit_frame.hpp"

namespace py = pybind11;

namespace geotex::python {

namespace {

/// The mesh of `path` as `geotex segment` reads it: the file read, its size checked, the
/// soup repaired into triangles. Returned arrays are views of the repaired mesh (no copy).
py::tuple read_mesh(const std::string& path) {
    auto mesh = std::make_unique<Mesh>();
    in_phase(Phase::Input, path, [&] {
        py::gil_scoped_release release;
        MeshFile file = read_mesh_file(path);
        make_unit_frame(file.soup.positions);  // before the repair, as the command does
        *mesh = repair_soup(std::move(file.soup)).mesh;
    });
    const Mesh* data = mesh.get();
    py::capsule owner(mesh.release(), [](void* p) { delete static_cast<Mesh*>(p); });
    return py::make_tuple(vertices_view(*data, owner), faces_view(*data, owner));
}

}  // namespace

void bind_mesh(py::module_& m) {
    m.def("read_mesh", &read_mesh, py::arg("path"),
          R"(Reads a mesh file as `geotex segment` reads it: .ply (ASCII or binary), .off, .obj
or .stl, polygons triangulated, duplicate vertices merged, degenerate and duplicate faces
removed, faces oriented consistently (README, "Input meshes").

Returns (V, F): V float64 #V by 3 vertex positions, F int32 #F by 3 vertex indices
(read-only views of the mesh the library built; copy them to modify).
Raises geotex.IoError (cannot read), geotex.ParseError (malformed, with line and column) or
geotex.InputError (unknown extension, no face left, a size no double holds), with the
command's message naming the file.)");
}

}  // namespace geotex::python
