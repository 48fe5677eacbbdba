// python/src/module.cpp — polyvol._polyvol: the compiled half of the Python
// package. It wraps the public C++ API (include/polyvol/) one call each;
// polyvol/__init__.py gives the documented Python API on top (argument
// checks, dtype conversion, result classes' to_dict). Every call that
// computes releases the GIL.
#include <algorithm>
#include <exception>
#include <string>

#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "polyvol/device.hpp"
#include "polyvol/implicit.hpp"
#include "polyvol/io.hpp"

namespace polyvol::python {

MeshView mesh_view(const Doubles& positions, const Indices& indices, const std::optional<Indices>& offsets) {
    if (positions.ndim() != 2 || positions.shape(1) != 3)
        throw std::invalid_argument("vertices must have shape (n, 3)");
    MeshView m{span_of(positions), {}, span_of(indices)};
    if (offsets) {
        m.face_offsets = span_of(*offsets);
        const auto& o = m.face_offsets;
        if (o.empty() || o.front() != 0 || o.back() != m.indices.size())
            throw std::invalid_argument("face_offsets must run from 0 to the number of face indices");
        for (std::size_t f = 1; f < o.size(); ++f)
            if (o[f] < o[f - 1]) throw std::invalid_argument("face_offsets must not decrease");
    } else if (m.indices.size() % 3 != 0) {
        throw std::invalid_argument("triangle faces must have shape (m, 3)");
    }
    const std::size_t n = m.vertex_count();
    uint32_t largest = 0;
    {
        py::gil_scoped_release release;
        for (const uint32_t v : m.indices) largest = std::max(largest, v);
    }
    if (!m.indices.empty() && largest >= n)
        throw std::invalid_argument("face index " + std::to_string(largest) + " is out of range for " +
                                    std::to_string(n) + " vertices");
    return m;
}

py::array_t<double> symmetric3(const std::array<double, 6>& m) {
    py::array_t<double> a({3, 3});
    auto r = a.mutable_unchecked<2>();
    r(0, 0) = m[0];
    r(1, 1) = m[1];
    r(2, 2) = m[2];
    r(0, 1) = r(1, 0) = m[3];
    r(1, 2) = r(2, 1) = m[4];
    r(2, 0) = r(0, 2) = m[5];
    return a;
}

namespace {

// Text from the file system (a path, or a message holding one): decoded as
// Python decodes file names (surrogateescape), so non-UTF-8 names survive.
py::str fs_text(const std::string& s) {
    PyObject* o = PyUnicode_DecodeFSDefaultAndSize(s.data(), static_cast<Py_ssize_t>(s.size()));
    if (o == nullptr) throw py::error_already_set();
    return py::reinterpret_steal<py::str>(o);
}

// C++ exceptions with a position become the package's exception classes
// (polyvol/_errors.py), their fields as attributes.
void translate_exceptions() {
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const ReadError& e) {
            const py::object cls = py::module_::import("polyvol._errors").attr("ReadError");
            const py::object line = e.line ? py::object(py::int_(e.line)) : py::object(py::none());
            const py::object offset = e.has_byte_offset ? py::object(py::int_(e.byte_offset)) : py::object(py::none());
            const py::object exc = cls(fs_text(e.what()), fs_text(e.file), line, offset, fs_text(e.message));
            PyErr_SetObject(cls.ptr(), exc.ptr());
        } catch (const ImplicitError& e) {
            const py::object cls = py::module_::import("polyvol._errors").attr("ImplicitError");
            const char* code = e.code() == ImplicitError::Code::not_a_number ? "not_a_number"
                               : e.code() == ImplicitError::Code::touches_box ? "touches_box"
                                                                              : "too_large";
            const py::object exc = cls(e.what(), code, py::cast(e.point()));
            PyErr_SetObject(cls.ptr(), exc.ptr());
        } catch (const ExpressionError& e) {
            const py::object cls = py::module_::import("polyvol._errors").attr("ExpressionError");
            const py::object exc = cls(e.what(), e.position());
            PyErr_SetObject(cls.ptr(), exc.ptr());
        } catch (const DeviceError& e) {
            const py::object cls = py::module_::import("polyvol._errors").attr("DeviceError");
            PyErr_SetObject(cls.ptr(), cls(e.what()).ptr());
        }
    });
}

}  // namespace
}  // namespace polyvol::python

PYBIND11_MODULE(_polyvol, m) {
    using namespace polyvol::python;
    m.doc() = "polyvol's compiled core; use the `polyvol` package.";
    m.attr("__version__") = POLYVOL_VERSION;
    translate_exceptions();
    bind_io(m);
    bind_measure(m);
    bind_grid(m);
    bind_chain(m);
    bind_cells(m);
}
