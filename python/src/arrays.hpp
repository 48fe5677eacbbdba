// python/src/arrays.hpp — numpy arrays in and out of the C++ API, without copies.
//
// In: the Python layer (polyvol/_arrays.py) has already converted every
// input to C-contiguous float64 coordinates and uint32 indices, so the
// array_t casts below never copy; these helpers only check shapes and index
// ranges (the C++ measures trust their input) and make the views.
// Out: arrays that view memory owned by a C++ object keep that object alive
// through numpy's base pointer and are read-only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "polyvol/mesh.hpp"

namespace polyvol::python {

namespace py = pybind11;

using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Indices = py::array_t<uint32_t, py::array::c_style | py::array::forcecast>;

inline std::span<const double> span_of(const Doubles& a) {
    return {a.data(), static_cast<std::size_t>(a.size())};
}
inline std::span<const uint32_t> span_of(const Indices& a) {
    return {a.data(), static_cast<std::size_t>(a.size())};
}

// A MeshView over (n, 3) positions, the flat indices and, for polygon
// faces, the offsets (m + 1 entries, from 0 to indices.size()). Throws
// ValueError (std::invalid_argument) for inconsistent arrays: every index must
// be below n, as the measures assume.
MeshView mesh_view(const Doubles& positions, const Indices& indices, const std::optional<Indices>& offsets);

// A read-only (rows, cols) or (rows,) array over memory that `owner` keeps alive.
template <class T>
py::array_t<T> view_array(const T* data, std::vector<py::ssize_t> shape, py::handle owner) {
    std::vector<py::ssize_t> strides(shape.size(), static_cast<py::ssize_t>(sizeof(T)));
    for (std::size_t d = shape.size(); d-- > 1;) strides[d - 1] = strides[d] * shape[d];
    py::array_t<T> a(shape, strides, data, owner);
    a.attr("flags").attr("writeable") = false;
    return a;
}

// A new array holding a copy of `values`, with the given shape.
template <class T>
py::array_t<T> copy_array(std::span<const T> values, std::vector<py::ssize_t> shape) {
    py::array_t<T> a(shape);
    std::copy(values.begin(), values.end(), a.mutable_data());
    return a;
}

// A new array that takes over a vector (no copy): the vector moves into a
// capsule that numpy frees with the array.
template <class T>
py::array_t<T> adopt_array(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
    auto* owned = new std::vector<T>(std::move(values));
    py::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
    std::vector<py::ssize_t> strides(shape.size(), static_cast<py::ssize_t>(sizeof(T)));
    for (std::size_t d = shape.size(); d-- > 1;) strides[d - 1] = strides[d] * shape[d];
    return py::array_t<T>(shape, strides, owned->data(), free_when_done);
}

// {xx, yy, zz, xy, yz, zx} as a symmetric (3, 3) array.
py::array_t<double> symmetric3(const std::array<double, 6>& m);

}  // namespace polyvol::python
