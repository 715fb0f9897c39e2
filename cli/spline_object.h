#pragma once
// Splines from document objects for the command-line tool: a bezier_spline as it is, a
// deboor_spline through the A-frame. Library errors are re-thrown naming the source and the object.

#include <string>
#include <variant>

#include "freeform/core/error.h"
#include "freeform/curve/aframe.h"
#include "freeform/curve/bezier_spline.h"
#include "freeform/io/document.h"

namespace freeform::cli {

/// The dimension (2 or 3) of a bezier_spline or deboor_spline object; Error for other types.
inline int splineDimension(const Document& doc, const DocumentObject& object)
{
    if (const auto* b = std::get_if<BezierSplineData>(&object.data)) return static_cast<int>(b->points.rows());
    if (const auto* d = std::get_if<DeBoorSplineData>(&object.data)) return static_cast<int>(d->points.rows());
    throw Error(doc.source + ": object \"" + object.name + "\" is a " + objectType(object.data) +
                ", not a spline (bezier_spline or deboor_spline)");
}

/// The object as a BezierSpline (the A-frame for deboor_spline).
template <int Dim>
BezierSpline<double, Dim> splineFromObject(const Document& doc, const DocumentObject& object)
{
    using Points = PointMatrix<double, Dim>;
    splineDimension(doc, object);
    try {
        if (const auto* b = std::get_if<BezierSplineData>(&object.data))
            return BezierSpline<double, Dim>(b->degree, b->closed, Points(b->points), b->intervals);
        const auto& d = std::get<DeBoorSplineData>(object.data);
        return BezierSpline<double, Dim>::fromDeBoor(Points(d.points), parseEndCondition(d.end, "end"), d.intervals);
    } catch (const Error& e) {
        throw Error(doc.source + ": object \"" + object.name + "\": " + e.what());
    }
}

} // namespace freeform::cli
