#include "tools/ffd_tools.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "freeform/core/error.h"
#include "freeform/core/parallel.h"
#include "freeform/curve/bezier_spline.h"
#include "freeform/io/mesh_io.h"
#include "freeform/io/deform_file.h"
#include "freeform/surface/bezier_surface.h"

namespace freeform::editor {

namespace {

using Points3 = Eigen::Matrix<double, 3, Eigen::Dynamic>;

bool insideBox(const Lattice& lattice, const PointColumns& points)
{
    for (Eigen::Index i = 0; i < points.cols(); ++i)
        if (!Lattice::insideBox(lattice.toLattice(Eigen::Vector3d(points.col(i))))) return false;
    return true;
}

} // namespace

DeformReport exportDeformedMesh(const std::string& input, const Lattice& lattice, double strength, const std::string& output)
{
    MeshFile file = MeshFile::read(input);
    DeformOptions options;
    options.strength = strength;
    const DeformReport report = deformMeshFile(lattice, file, options).report; // what `freeform ffd` does
    file.write(output);
    return report;
}

std::optional<ObjectData> deformObject(const Lattice& lattice, const ObjectData& object, double strength, std::string& why)
{
    const bool extrapolate = lattice.outside() == OutsidePolicy::Extrapolate;
    const auto outside = [&](const PointColumns& p) {
        if (extrapolate || insideBox(lattice, p)) return false;
        why = "control points outside the lattice box (exact only inside, or with the extrapolate policy)";
        return true;
    };
    if (const auto* c = std::get_if<BezierCurveData>(&object)) {
        if (c->points.rows() != 3) {
            why = "a 2D curve (the lattice deforms 3D space)";
            return std::nullopt;
        }
        if (outside(c->points)) return std::nullopt;
        BezierCurveData d;
        d.points = deformCurve(lattice, BezierCurve<double, 3>(Points3(c->points)), strength).controlPoints();
        return d;
    }
    if (const auto* s = std::get_if<BezierSplineData>(&object)) {
        if (s->points.rows() != 3) {
            why = "a 2D spline (the lattice deforms 3D space)";
            return std::nullopt;
        }
        if (outside(s->points)) return std::nullopt;
        const BezierSpline<double, 3> spline(s->degree, s->closed, Points3(s->points), s->intervals);
        BezierSplineData d;
        d.closed = s->closed;
        d.intervals = s->intervals;
        const int L = spline.segmentCount();
        for (int i = 0; i < L; ++i) {
            const BezierCurve<double, 3> piece = deformCurve(lattice, spline.segment(i), strength);
            const int n = piece.degree();
            if (i == 0) {
                d.degree = n;
                d.points.resize(3, s->closed ? L * n : L * n + 1);
            }
            // Segment i owns its first n points (the joint from its own composition); the last
            // segment of an open spline its end point too.
            d.points.middleCols(static_cast<Eigen::Index>(i) * n, n) = piece.controlPoints().leftCols(n);
            if (!s->closed && i + 1 == L) d.points.col(d.points.cols() - 1) = piece.controlPoints().col(n);
        }
        return d;
    }
    if (const auto* p = std::get_if<BezierSurfaceData>(&object)) {
        if (outside(p->points)) return std::nullopt;
        const BezierSurface<double, 3> patch(p->degree[0], p->degree[1], Points3(p->points));
        const BezierSurface<double, 3> moved = deformSurface(lattice, patch, strength);
        BezierSurfaceData d;
        d.degree = {moved.degreeU(), moved.degreeV()};
        d.points = moved.controlPoints();
        return d;
    }
    if (const auto* g = std::get_if<SubdivisionSurfaceData>(&object)) {
        if (g->vertices.cols() == 0) {
            why = "the cage is in a mesh file (only inline cages are deformed)";
            return std::nullopt;
        }
        SubdivisionSurfaceData d = *g;
        Points3 v = g->vertices;
        DeformOptions options;
        options.strength = strength;
        deformPoints(lattice, v, options);
        d.vertices = v;
        return d;
    }
    why = "no exact deformation for this object type";
    return std::nullopt;
}

} // namespace freeform::editor
