#pragma once
// The Python Lattice: a freeform::Lattice, its control points as a writable (K, 3) NumPy array
// (the array the user edits; synced into the lattice, checked, before every call), the strength
// and the object name used by save().

#include "arrays.h"

#include <freeform/volume/lattice.h>

namespace ffpy {

struct PyLattice {
    explicit PyLattice(freeform::Lattice lattice, std::string name = "lattice");

    /// The lattice with the current control points (Error when one is not finite), copied so that
    /// the computation can run without the GIL while Python threads edit this object.
    freeform::Lattice snapshot();

    freeform::Lattice lattice;
    py::array_t<double> points; // (K, 3), index i*(m+1)*(n+1) + j*(n+1) + k
    double strength = 1;
    std::string name;
};

void bindLattice(py::module_& m);

} // namespace ffpy
