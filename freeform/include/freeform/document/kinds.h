#pragma once
// The kind table: every object kind of a freeform document described once (its "type" name, what
// it is, its parameters, what the document layer can do with it), so that the front ends (CLI,
// editor, Python) dispatch on a descriptor instead of comparing type strings. A kind's row is in
// its document file (src/document/kinds/TYPE.cpp), beside everything else the document layer does
// with it; the kinds themselves are the lines of FREEFORM_OBJECT_KINDS (io/document.h).
// docs/architecture.md, "Adding an object kind".

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "freeform/io/document.h"

namespace freeform {

/// What an object is.
enum class KindNature {
    Curve,   ///< one parameter, 2D or 3D
    Surface, ///< two parameters (a subdivision surface: FACE,U,V on its cage's faces)
    Volume,  ///< three parameters: the FFD lattice
    Part,    ///< a CAD part: trimmed faces stitched along edges (a B-rep); FACE,U,V on its faces
};

/// The parameter an evaluation takes (`freeform eval --at`, Python's evaluate).
enum class KindParameters {
    T,      ///< a curve's t or a spline's global T
    UV,     ///< a surface's (u, v)
    FaceUV, ///< a subdivision surface's or a part's face and (u, v) in it
    STU,    ///< a lattice's (s, t, u) in [0, 1]^3
};

/// What the document layer does with a kind (document/operations.h), one bit each.
enum class KindOperation : unsigned {
    Evaluate = 1u << 0,      ///< evaluate()
    Polyline = 1u << 1,      ///< objectPolyline(): drawn as a curve
    Tessellate = 1u << 2,    ///< tessellateObject(): drawn as a surface mesh
    Deform = 1u << 3,        ///< deformDocument() moves it through any lattice (3D objects; a
                             ///< deboor_surface only through an affine one, so it has no bit)
    Continuity = 1u << 4,    ///< continuity(): joints between pieces
    ConvertSpline = 1u << 5, ///< convertSpline(): bezier_spline <-> deboor_spline
    ToNurbs = 1u << 6,       ///< toNurbsData()
    FromNurbs = 1u << 7,     ///< fromNurbsData()
    DeformsOthers = 1u << 8, ///< it is the lattice that deforms the others (freeform ffd --lattice)
    Part = 1u << 9,          ///< objectPart(): a part, or a trimmed surface as a part of one face
                             ///< (STEP and IGES out, faces to pick, the part report)
};

struct KindInfo {
    ObjectKind kind;
    std::string_view name;    ///< the "type" string (docs/format.md)
    std::string_view summary; ///< for people: "Bézier curve", "NURBS surface", ...
    KindNature nature;
    KindParameters parameters;
    int dimension;            ///< 3, or 0 for 2 or 3 as its points are
    bool rational;            ///< has weights (rational_bezier_*, nurbs_*)
    bool knots;               ///< has knot vectors (nurbs_*)
    bool pieces;              ///< made of joined pieces (splines, de Boor and NURBS forms)
    unsigned operations;      ///< KindOperation bits

    bool supports(KindOperation op) const { return (operations & static_cast<unsigned>(op)) != 0; }
    bool isCurve() const { return nature == KindNature::Curve; }
    bool isSurface() const { return nature == KindNature::Surface; }
};

/// Every kind, in the order of ObjectKind (and of ObjectData's alternatives).
const std::array<KindInfo, objectKindCount>& objectKinds();

const KindInfo& kindInfo(ObjectKind kind);
inline const KindInfo& kindInfo(const ObjectData& data) { return kindInfo(objectKind(data)); }
/// The kind called name ("nurbs_curve"); nullptr for any other text.
const KindInfo* findKind(std::string_view name);

/// An object's data in words for people (the editor's Properties): its degrees and form, e.g.
/// "degree 3, 2D", "degree 3, closed", "degree 2 x 3", "degree 3, 8 knots, 2D"; a part's counts
/// (partSummary); empty for a subdivision surface (its cage is described by its own panel).
std::string objectDetails(const ObjectData& data);
/// A part's counts in words: "10 faces, 22 edges, 14 vertices, 1 shell, 1 solid, units mm".
std::string partSummary(const PartData& part);

} // namespace freeform
