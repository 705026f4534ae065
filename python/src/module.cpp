// The compiled part of the Python package geotex (python/geotex/__init__.py re-exports it).

#include "bindings.hpp"

PYBIND11_MODULE(_geotex, m) {
    m.doc() = "geotex: geometric textures of 3D meshes (compiled part; use the package geotex)";
    geotex::python::bind_errors(m);  // first: the other parts raise its exception classes
    geotex::python::bind_mesh(m);
    geotex::python::bind_segment(m);
    geotex::python::bind_annotate(m);  // after segment: it calls geotex.segment
}
