#include "arrays.hpp"

#include <cmath>
#include <cstdint>
#include <string>

#include "errors.hpp"

namespace py = pybind11;

namespace geotex::python {

namespace {

// Storage the view functions rely on: an Eigen::Vector3d is three packed doubles, a face
// three packed ints, so the vectors are #V by 3 and #F by 3 C-order arrays.
static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double));
static_assert(sizeof(std::array<int, 3>) == 3 * sizeof(int));

std::string shape_text(const py::array& a) {
    std::string s = "(";
    for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
    return s + (a.ndim() == 1 ? ",)" : ")");
}

std::string dtype_text(const py::array& a) { return py::str(a.dtype()).cast<std::string>(); }

py::array as_array(const py::object& o, const char* name, const char* what) {
    py::array a = py::array::ensure(o);  // numpy.asarray; null (error cleared) when it fails
    if (!a) raise_error(Phase::Input, std::string(name) + " is not an array of " + what);
    return a;
}

void check_shape(const py::array& a, const char* name, const char* rows) {
    if (a.ndim() != 2 || a.shape(1) != 3)
        raise_error(Phase::Input, std::string(name) + " must be a " + rows +
                                      " by 3 array (got shape " + shape_text(a) + ")");
}

template <class T>
void read_positions(const py::array& a, PolygonSoup& soup) {
    const auto v = py::reinterpret_borrow<py::array_t<T>>(a).template unchecked<2>();
    soup.positions.resize(static_cast<std::size_t>(v.shape(0)));
    for (py::ssize_t i = 0; i < v.shape(0); ++i)
        for (py::ssize_t c = 0; c < 3; ++c) {
            const double x = static_cast<double>(v(i, c));
            if (!std::isfinite(x))
                raise_error(Phase::Input, "V[" + std::to_string(i) + ", " + std::to_string(c) +
                                              "] is not finite (" + std::to_string(x) + ")");
            soup.positions[static_cast<std::size_t>(i)][c] = x;
        }
}

template <class T>
void read_faces(const py::array& a, PolygonSoup& soup) {
    const auto f = py::reinterpret_borrow<py::array_t<T>>(a).template unchecked<2>();
    const auto num_vertices = static_cast<std::int64_t>(soup.positions.size());
    const auto rows = static_cast<std::size_t>(f.shape(0));
    soup.face_indices.resize(3 * rows);
    soup.face_offsets.resize(rows + 1);
    for (py::ssize_t i = 0; i < f.shape(0); ++i) {
        for (py::ssize_t c = 0; c < 3; ++c) {
            const T index = f(i, c);
            // Compared in 64 bits whatever T is, so that no unsigned or wide index wraps.
            const bool in_range = index >= 0 && static_cast<std::uint64_t>(index) <
                                                    static_cast<std::uint64_t>(num_vertices);
            if (!in_range)
                raise_error(Phase::Input, "F[" + std::to_string(i) + ", " + std::to_string(c) +
                                              "] = " + std::to_string(index) +
                                              " is not a row of V (0 to " +
                                              std::to_string(num_vertices - 1) + ")");
            soup.face_indices[3 * static_cast<std::size_t>(i) + c] = static_cast<int>(index);
        }
        soup.face_offsets[static_cast<std::size_t>(i) + 1] = 3 * static_cast<int>(i + 1);
    }
}

}  // namespace

PolygonSoup soup_from_arrays(const py::object& V, const py::object& F) {
    const py::array v = as_array(V, "V", "coordinates");
    const py::array f = as_array(F, "F", "vertex indices");
    check_shape(v, "V", "#V");
    check_shape(f, "F", "#F");
    if (v.shape(0) > INT32_MAX || 3 * f.shape(0) > INT32_MAX)
        raise_error(Phase::Input,
                    "the mesh is too large (at most 2^31 - 1 vertices and face corners)");
    PolygonSoup soup;
    const char kind = v.dtype().kind();
    if (py::isinstance<py::array_t<double>>(v)) {
        read_positions<double>(v, soup);
    } else if (py::isinstance<py::array_t<float>>(v)) {
        read_positions<float>(v, soup);
    } else if (kind == 'f' || kind == 'i' || kind == 'u' || kind == 'b') {
        read_positions<double>(py::array_t<double, py::array::forcecast>::ensure(v), soup);
    } else {
        raise_error(Phase::Input, "V must hold real numbers (got dtype " + dtype_text(v) + ")");
    }
    if (f.dtype().kind() != 'i' && f.dtype().kind() != 'u')
        raise_error(Phase::Input,
                    "F must hold integer vertex indices (got dtype " + dtype_text(f) + ")");
    if (py::isinstance<py::array_t<std::int32_t>>(f))
        read_faces<std::int32_t>(f, soup);
    else if (py::isinstance<py::array_t<std::int64_t>>(f))
        read_faces<std::int64_t>(f, soup);
    else if (py::isinstance<py::array_t<std::uint64_t>>(f))
        read_faces<std::uint64_t>(f, soup);
    else  // the narrower integer types: exact in int64
        read_faces<std::int64_t>(py::array_t<std::int64_t, py::array::forcecast>::ensure(f), soup);
    return soup;
}

py::array_t<double> vertices_view(const Mesh& mesh, py::handle owner) {
    const double* data = mesh.positions.empty() ? nullptr : mesh.positions.front().data();
    return view(data, {mesh.num_vertices(), 3}, owner);
}

py::array_t<int> faces_view(const Mesh& mesh, py::handle owner) {
    const int* data = mesh.faces.empty() ? nullptr : mesh.faces.front().data();
    return view(data, {mesh.num_faces(), 3}, owner);
}

}  // namespace geotex::python
