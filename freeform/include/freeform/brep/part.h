#pragma once
// A part: the boundary representation of a CAD model (docs/cad.md, "Parts").
//
// Faces are trimmed surfaces (brep/trimmed_surface.h) whose trim curves name the edges they lie
// on; an edge has a 3D curve (none when it is degenerate, e.g. at a sphere's pole, or when the
// file gave only its pcurves), its parameter range, its end vertices and a tolerance: the file's
// promise that the 3D curve and every pcurve of the edge, mapped through its face, stay within it
// at the same parameter. Shells are sets of faces, solids sets of shells.
//
// checkPart() reports what a mesh or an exact deformation must know: edges used by one face of
// a shell (open) or by more than two (non-manifold), whether every shell is closed, and the
// largest gap between an edge's curve and its faces, sampled, against the edge's tolerance.

#include <optional>
#include <string>
#include <vector>

#include "freeform/brep/trimmed_surface.h"

namespace freeform {

struct PartVertex {
    Eigen::Vector3d point;
    double tolerance = 0;
};

struct PartEdge {
    std::optional<MappedCurve<3>> curve; // none: degenerate, or only pcurves in the file
    double first = 0, last = 0;          // the parameter range shared with its pcurves
    int start = -1, end = -1;            // vertices
    double tolerance = 0;
    bool degenerate = false;
};

struct PartFace {
    TrimmedSurface surface;
    bool reversed = false;   // the face's outward normal is -(S_u x S_v)
    std::string surfaceKind; // what the file said: "plane", "cylinder", "bspline", ...
    double tolerance = 0;
};

struct PartShell {
    std::vector<int> faces;
};

struct PartSolid {
    std::vector<int> shells;
};

struct Part {
    std::vector<PartFace> faces;
    std::vector<PartEdge> edges;
    std::vector<PartVertex> vertices;
    std::vector<PartShell> shells; // faces in no shell are listed by looseFaces()
    std::vector<PartSolid> solids;
    std::string units = "mm"; // the file's length unit; coordinates are in it

    /// Faces that belong to no shell (an IGES file's faces, typically).
    std::vector<int> looseFaces() const;
    /// A box holding every face (the union of TrimmedSurface::bounds()) and every vertex.
    Box<double, 3> bounds() const;
    /// The sum of the faces' areas (TrimmedSurface::area).
    double area(double relative = 1e-10) const;
    /// The largest degree of a face's surface (either direction) or an edge's 3D curve; 0 for none.
    int maxDegree() const;
};

/// A trimmed surface as a part of one face (no shell): each of its trim curves becomes an edge of
/// its own, without a 3D curve (the trim through the surface is the edge), from a vertex where it
/// starts to the next trim's; a vertex's and an edge's tolerance is the gap in space between the
/// two trim ends that meet there. So the part's mesh, deformation and writers apply to a surface
/// that stands alone.
Part singleFacePart(const TrimmedSurface& surface);

struct PartCheck {
    int openEdges = 0;        // used by exactly one face of a shell
    int nonManifoldEdges = 0; // used by more than two faces of a shell
    bool closed = false;      // there is a shell, and every shell has neither
    double maxGap = 0;        // largest sampled distance between an edge's curve and its faces
    int gapsOverTolerance = 0; // edge uses whose gap exceeds the edge's tolerance
};

/// samples: points per edge use where the gap is measured.
PartCheck checkPart(const Part& part, int samples = 16);

} // namespace freeform
