#pragma once
// numpy arrays in and out of the library's plain data. Inputs are copied once, into the
// polygon soup that the repair reads (as the command's file readers fill it); outputs are
// views of vectors that the result object owns, never copies.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <vector>

#include "geometry/mesh.hpp"

namespace geotex::python {

/// The one copy of the inputs: V (#V by 3, a real dtype, any strides) and F (#F by 3, an
/// integer dtype) read into a polygon soup of triangles. Anything array-like is accepted
/// (numpy.asarray); float32 and float64 coordinates, int32 and int64 indices are read in
/// place, other dtypes are converted by numpy first. Raises geotex.InputError with a one-line
/// message on a wrong shape or dtype, a non-finite coordinate or an index out of range.
/// Needs the GIL.
PolygonSoup soup_from_arrays(const pybind11::object& V, const pybind11::object& F);

/// A read-only array of `shape` over `data` (C order), kept alive by `owner`: no copy.
template <class T>
pybind11::array_t<T> view(const T* data, std::vector<pybind11::ssize_t> shape,
                          pybind11::handle owner) {
    pybind11::array_t<T> a(std::move(shape), data, owner);
    pybind11::detail::array_proxy(a.ptr())->flags &=
        ~pybind11::detail::npy_api::NPY_ARRAY_WRITEABLE_;
    return a;
}

/// A read-only 1-D array over a vector, kept alive by `owner`.
template <class T>
pybind11::array_t<T> view(const std::vector<T>& values, pybind11::handle owner) {
    return view(values.data(), {static_cast<pybind11::ssize_t>(values.size())}, owner);
}

/// V (#V by 3 float64) and F (#F by 3 int32) of a mesh, kept alive by `owner`.
pybind11::array_t<double> vertices_view(const Mesh& mesh, pybind11::handle owner);
pybind11::array_t<int> faces_view(const Mesh& mesh, pybind11::handle owner);

}  // namespace geotex::python
