#pragma once
// The parts of the Python module _geotex, one per area (errors, mesh, segmentation, annotation),
// each adding its names to the module; module.cpp calls them in order.

#include <pybind11/pybind11.h>

namespace geotex::python {

void bind_errors(pybind11::module_& m);
void bind_mesh(pybind11::module_& m);
void bind_segment(pybind11::module_& m);
void bind_annotate(pybind11::module_& m);

}  // namespace geotex::python
