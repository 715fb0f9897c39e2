#pragma once
// The document layer: a freeform document as typed objects with stable ids, and the operations
// both front ends need, so neither writes its own bridge from document data to geometry.
// Layers (docs/architecture.md): core -> geometry -> io -> document (this) -> cli, editor.
//
// How a front end uses this (the call that replaced each former bridge; cli/ and the editor's FFD
// and scene geometry now call these):
//
//   TypedDocument doc = TypedDocument::read(path);         // readDocument + geometry of every object
//   const TypedObject& o = doc.object(name);               // or doc.find(id): ids stay stable
//
//   cli/spline_object.h   splineDimension / splineFromObject<Dim>
//                                  -> AnyCurve::of(o) (dimension(), derivatives(), spline3(), ...)
//   cli/surface_objects.h isSurfaceObject / surfacePatches
//                                  -> AnySurface::of(o), surfacePatches(doc, o, &segments)
//   cli/eval_*.cpp        -> Evaluation e = evaluate(doc, o, {numbers of --at}, K);
//                                     print e.point, e.derivatives (keys e.keys; empty for curves),
//                                     e.normal, e.det, e.face. The CLI keeps parsing --at and its
//                                     usage errors (FACE not an integer: exit 2) before calling.
//   cli/cmd_continuity.cpp -> continuity(doc, o, tolerances)
//   cli/cmd_tessellate.cpp -> surfacePatches(doc, o) / documentPatches(doc), then
//                                     tessellate() (the .bpt path: io/bpt.h)
//   cli/cmd_convert_spline.cpp -> convertSpline(doc, o.id(), to, end);
//                                     writeDocument(doc.toDocument(), out)
//   cli/cmd_ffd.cpp (DOC)  -> DeformDocumentReport r = deformDocument(doc, lattice, {w});
//                                     the report's objects[i] {name, from, type, degree (one number
//                                     for curves, [p, q] for surfaces), inside} and skipped[i]
//                                     {name, type, reason} are the fields the CLI prints today;
//                                     r.certificate is certify(lattice, w).
//   cli/eval_lattice.cpp, cmd_ffd.cpp, editor: Lattice::fromData/toData
//                                  -> latticeFromData / latticeToData (io/geometry_data.h)
//   editor/scene/geometry.cpp      Builder -> controlNet(o) (points + edges), objectPolyline(o, tol)
//                                     for curves, tessellateObject(o, {tolerance, segments, flip})
//                                     for surfaces and subdivision surfaces
//   editor/tools/ffd_tools.cpp     deformObject -> deformDocument with the CLI's options, called
//                                     from LatticeTool::applyLatticeToObjects; the rule for every
//                                     type is in docs/ffd.md ("Documents")
//   editor/scene/scene.cpp         cageFromData -> io/geometry_data.h (or SubdivisionObject::cage())
//
// Adding an object type (rational Bézier, NURBS): its data struct in io/document.h, one
// alternative in Geometry (model.h) plus its case in buildGeometry (src/document/model.cpp; that
// visitor has no catch-all, so the compiler asks for it, as it does in controlNet), then its
// operations in one new file src/document/<type>.cpp, called from evaluate, tessellateObject and
// deformDocument. A curve or a surface only has to join AnyCurve / AnySurface: evaluate, polylines,
// continuity and tessellation then take it unchanged. Until deformDocument knows it, a new type is
// listed as skipped ("no exact deformation for a TYPE"), never silently dropped.

#include "freeform/document/model.h"
#include "freeform/document/operations.h"
