#pragma once
// OBJ free-form geometry: Bézier, rational Bézier and B-spline (NURBS) curves and surfaces in the
// Wavefront OBJ statements `v` (x y z [w]), `cstype [rat] bezier|bspline`, `deg`, `curv`, `surf`,
// `parm`, `end` (and `o`/`g` for names), read into and written from the document's plain data
// (docs/surfaces.md, "OBJ free-form geometry").
//
// Mapping: a bezier_curve is `curv 0 1` with its n+1 control points and `deg n`; an open
// bezier_spline of L segments is one `curv 0 T` with L*degree + 1 points and `parm u` at the
// cumulative interval ends (0 = t_0 < ... < t_L = T); a bezier_surface of degree (m, n) is
// `deg m n` and `surf 0 1 0 1` with its (m+1)(n+1) points listed with u varying fastest (point
// (i, j) is the (j*(m+1) + i)-th reference). 2D curves are written with z = 0 and read back as 3D.
// Rational types (`cstype rat ...`) carry the weight as the 4th `v` coordinate (x y z are the
// Cartesian point, not w times it; an absent w is 1). rational_bezier_curve / rational_bezier_surface
// are `cstype rat bezier` like their polynomial forms; a piecewise `rat bezier` curve reads as a
// nurbs_curve (interior knots of multiplicity degree). nurbs_curve / nurbs_surface are
// `cstype bspline` (no weights) or `cstype rat bspline`, `parm u` (and `parm v`) the whole knot
// vector, `curv` / `surf` over the whole domain [knot p, knot count] (a sub-range is an Error), the
// surface grid u fastest with its size from the knot counts (rows = |parm u| - p - 1).
// A trimmed_surface is its trim curves as `curv2` elements (2D B-splines on `vp u v [w]` lines),
// then its surface as a `cstype [rat] bspline` surf over its domain (a part of the knot domain) with
// `trim u0 u1 k ...` (the outer loop: curv2 number k from u0 to u1; u0 > u1 runs it backwards) and
// a `hole ...` per inner loop. Reading, a surf with trim or hole statements (Bézier or B-spline), or
// a B-spline surf over a part of its domain, is a trimmed_surface; holes without a trim are inside
// the surf range; a curv2 no surface trims with is a 2D nurbs_curve of its own. Parameter maps (a
// CAD face's angles) have no OBJ form: writing one is an Error naming the field.
// Numbers are written in the shortest form that reads back to the same double, so
// document -> OBJ -> document keeps every coordinate exactly.
//
// The reader is strict: other types (cardinal, taylor, bmat), special curves and points (scrv, sp),
// a second trim loop, non-positive weights, invalid knot vectors, a point count that does not fit
// the degree, a bad `parm` list, an index out of range, a trim range outside its curve, an element
// without `end`, or a statement it does not know are Errors naming the file and line.
// Polygonal statements (f, l, p, vt, vn, s, usemtl, mtllib) are skipped.

#include <string>

#include "freeform/io/document.h"

namespace freeform {

/// The free-form elements of OBJ text as document objects (names from `o`/`g`, else
/// curve1, surface1, ...; repeated names get a suffix _2, _3, ...). source names the text in errors.
Document parseObjFreeform(const std::string& text, const std::string& source = "obj");

/// Reads an OBJ file (Error naming the path when it cannot be read or parsed).
Document readObjFreeform(const std::string& path);

/// The bezier_curve, bezier_spline (open), bezier_surface, rational_bezier_curve,
/// rational_bezier_surface, nurbs_curve, nurbs_surface and trimmed_surface objects of the document
/// as OBJ text;
/// objectName non-empty: only that object. Error naming the object for any other type (a closed
/// spline, a de Boor form, a lattice: convert them to Bézier form first).
std::string formatObjFreeform(const Document& document, const std::string& objectName = "");

/// formatObjFreeform written atomically to path.
void writeObjFreeform(const Document& document, const std::string& path, const std::string& objectName = "");

} // namespace freeform
