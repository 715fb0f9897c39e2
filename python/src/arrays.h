#pragma once
// NumPy <-> Eigen helpers of the Python module (docs/python.md, "Arrays"):
//   - an (N, 3) float64 or float32 C-contiguous array is used in place (no copy);
//   - any other numeric array of shape (N, 3) (another dtype, strides, Fortran order) is converted
//     once to float64 C-contiguous;
//   - a non-numeric dtype raises TypeError, a wrong shape or a non-finite value freeform.Error.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>

#include <charconv>
#include <cmath>
#include <cstddef>
#include <string>

#include <freeform/core/error.h>

namespace ffpy {

namespace py = pybind11;

using Points3 = Eigen::Matrix<double, 3, Eigen::Dynamic>;

/// A number as Python's repr() writes it (the shortest text that reads back to the same double),
/// so a message shows the problem: 1.000000001, not 1.000000 (as %f would).
inline std::string num(double x)
{
    if (std::isnan(x)) return "nan";
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, x);
    return std::string(buf, r.ptr);
}

inline std::string shapeText(const py::array& a)
{
    std::string s = "(";
    for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
    if (a.ndim() == 1) s += ",";
    return s + ")";
}

/// Any array-like as a NumPy array with a numeric dtype (TypeError otherwise).
inline py::array numericArray(py::handle h, const std::string& what)
{
    py::array a = py::array::ensure(h);
    if (!a) {
        PyErr_Clear();
        throw py::type_error(what + ": expected an array of numbers, got " +
                             std::string(py::str(py::type::handle_of(h).attr("__name__"))));
    }
    const char kind = a.dtype().kind();
    if (kind != 'f' && kind != 'i' && kind != 'u')
        throw py::type_error(what + ": dtype " + std::string(py::str(a.dtype())) +
                             " is not a real number type (float64, float32 or an integer type)");
    return a;
}

// Equivalent dtypes, not the same dtype object: an unpickled array has its own float64 descriptor.
inline bool isDouble(const py::array& a) { return py::isinstance<py::array_t<double>>(a); }
inline bool isFloat(const py::array& a) { return py::isinstance<py::array_t<float>>(a); }
inline bool isCContiguous(const py::array& a) { return (a.flags() & py::array::c_style) != 0; }

/// Error unless `a` has exactly the shape `expected` (the argument named, the shape expected and
/// the shape given, before any element is read).
inline void requireShape(const py::array& a, const std::string& what, std::initializer_list<py::ssize_t> expected,
                         const std::string& note = "")
{
    bool ok = a.ndim() == static_cast<py::ssize_t>(expected.size());
    std::string e = "(";
    py::ssize_t d = 0;
    for (const py::ssize_t x : expected) {
        if (ok && a.shape(d) != x) ok = false;
        e += (d ? ", " : "") + std::to_string(x);
        ++d;
    }
    e += expected.size() == 1 ? ",)" : ")";
    if (!ok)
        throw freeform::Error(what + ": expected an array of shape " + e + note + ", got shape " + shapeText(a));
}

/// A Python int for threads= (0: the hardware concurrency); Error for anything else, a negative
/// count or one above kMaxThreads (no TypeError listing the other arguments).
constexpr long long kMaxThreads = 4096;
inline int threadCount(py::handle h)
{
    if (!py::isinstance<py::int_>(h) || py::isinstance<py::bool_>(h))
        throw freeform::Error("threads: expected an int (0: one per hardware thread), got " +
                              std::string(py::str(py::type::handle_of(h).attr("__name__"))));
    int overflow = 0;
    const long long t = PyLong_AsLongLongAndOverflow(h.ptr(), &overflow);
    if (overflow != 0 || t < 0 || t > kMaxThreads)
        throw freeform::Error("threads: " + std::string(py::str(h)) + " is outside [0, " + std::to_string(kMaxThreads) +
                              "] (0: one per hardware thread)");
    return static_cast<int>(t);
}

/// An (N, cols) array: float64/float32 C-contiguous as given (no copy) when allowFloat, float64
/// C-contiguous as given; anything else converted once to float64 C-contiguous.
inline py::array rows(py::handle h, const std::string& what, py::ssize_t cols, bool allowFloat = true)
{
    py::array a = numericArray(h, what);
    if (a.ndim() != 2 || a.shape(1) != cols)
        throw freeform::Error(what + ": expected an array of shape (N, " + std::to_string(cols) + "), got shape " +
                              shapeText(a));
    if (isCContiguous(a) && (isDouble(a) || (allowFloat && isFloat(a)))) return a;
    return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
}

/// A 1-D array of parameters (a scalar becomes one value), converted to float64 when needed.
inline py::array_t<double, py::array::c_style> vector(py::handle h, const std::string& what)
{
    py::array a = numericArray(h, what);
    if (a.ndim() > 1) throw freeform::Error(what + ": expected a 1-D array, got shape " + shapeText(a));
    auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    return py::array_t<double, py::array::c_style>(d.attr("reshape")(-1));
}

/// Error naming the first non-finite row of an (n, cols) block.
template <typename Scalar>
void requireFiniteRows(const Scalar* data, std::size_t n, std::size_t cols, const std::string& what)
{
    for (std::size_t i = 0; i < n * cols; ++i)
        if (!std::isfinite(data[i]))
            throw freeform::Error(what + ": row " + std::to_string(i / cols) + " is not finite (" +
                                  num(static_cast<double>(data[i])) + ")");
}

/// An (N, 3) float64 array copied into a 3 x N Eigen matrix (checked finite).
inline Points3 toPoints(py::handle h, const std::string& what)
{
    py::array a = rows(h, what, 3, false);
    const auto n = static_cast<std::size_t>(a.shape(0));
    const double* p = static_cast<const double*>(a.data());
    requireFiniteRows(p, n, 3, what);
    return Eigen::Map<const Points3>(p, 3, static_cast<Eigen::Index>(n));
}

/// A (rows x cols) Eigen matrix (column-major, points as columns) as an (cols, rows) float64 array (copy).
template <typename Derived>
py::array_t<double> fromColumns(const Eigen::MatrixBase<Derived>& m)
{
    py::array_t<double> out({static_cast<py::ssize_t>(m.cols()), static_cast<py::ssize_t>(m.rows())});
    double* o = out.mutable_data();
    for (Eigen::Index c = 0; c < m.cols(); ++c)
        for (Eigen::Index r = 0; r < m.rows(); ++r) *o++ = m(r, c);
    return out;
}

inline py::array_t<double> fromVector(const Eigen::VectorXd& v)
{
    py::array_t<double> out(static_cast<py::ssize_t>(v.size()));
    std::copy(v.data(), v.data() + v.size(), out.mutable_data());
    return out;
}

} // namespace ffpy
