#pragma once
// Open CASCADE shapes into parts: for code that already holds a TopoDS_Shape (the tests build
// parts with Open CASCADE's modelling algorithms). Including this header needs Open CASCADE's
// include folder; freeform/cad/cad_file.h does not.

#include <string>

#include <TopoDS_Shape.hxx>

#include "freeform/brep/part.h"
#include "freeform/cad/cad_file.h"

namespace freeform {

/// Every face, edge, vertex, shell and solid of the shape, indexed as TopExp::MapShapes indexes
/// them (minus one), in the exact forms of brep/exact_forms.h. Throws freeform::Error naming the
/// face or edge (counted from 1) whose geometry has no exact rational form.
Part partFromShape(const TopoDS_Shape& shape, const std::string& units = "mm");

/// The part as an Open CASCADE shape (a solid, a shell, a face, or a compound of them), as
/// writeCadFile writes it; `report` receives the fitted trims and BRepCheck's verdict.
TopoDS_Shape shapeFromPart(const Part& part, CadWriteReport* report = nullptr);

} // namespace freeform
