#pragma once
// The document layer: a freeform document as typed objects with stable ids, and the operations
// both front ends need, so neither writes its own bridge from document data to geometry.
// Layers (docs/architecture.md): core -> geometry -> io -> document (this) -> cli, editor.
//
// How a front end uses it:
//
//   TypedDocument doc = TypedDocument::read(path);   // readDocument + geometry of every object
//   const TypedObject& o = doc.object(name);         // or doc.find(id): ids stay stable
//
//   AnyCurve::of(o) / AnySurface::of(o)   every curve kind and every (u, v) surface kind, rational
//                                         and NURBS included (dimension(), derivatives(), domain,
//                                         polyline; jet(), normal(), patches() of the polynomial ones)
//   evaluate(doc, o, parameters, K)       cli/eval_*.cpp, Python's Document.evaluate
//   continuity(doc, o, tolerances)        cli/cmd_continuity.cpp
//   surfacePatches / documentPatches      cli/cmd_tessellate.cpp, then tessellate()
//   convertObject(doc, id, to, end)       cli/cmd_convert_kind.cpp, Python's Document.convert
//   deformDocument(doc, lattice, options) cli/cmd_ffd.cpp (DOC), the editor's lattice tool
//   controlNet(o), objectPolyline(o, tol), tessellateObject(o, options)
//                                         the editor's scene geometry (editor/scene/geometry.cpp)
//   latticeFromData / latticeToData, cageFromData (io/geometry_data.h)
//                                         lattices and cages from plain data, in every front end
//
// Adding an object kind: the files, one by one, are in docs/architecture.md ("Adding an object
// kind"). Everything the document layer does per kind is in that kind's one file,
// src/document/kinds/TYPE.cpp (the functions of src/document/kind_file.h, declared for every line
// of FREEFORM_OBJECT_KINDS, so a kind whose file lacks one does not link). A curve that joins
// AnyCurve there (its alternatives in model.h) is taken by evaluate, polylines and continuity
// unchanged; a new surface class also adds its cases to AnySurface's domain and jet and to
// tessellateObject, where the compiler asks for them.

#include "freeform/document/model.h"
#include "freeform/document/operations.h"
