#pragma once
// Surface objects of a document as patch complexes, shared by `freeform eval` (eval_surface.cpp)
// and `freeform tessellate` (cmd_tessellate.cpp).

#include <string>

#include "freeform/io/document.h"
#include "freeform/surface/patch_complex.h"

namespace freeform::cli {

inline bool isSurfaceObject(const DocumentObject& object)
{
    return std::holds_alternative<BezierSurfaceData>(object.data) || std::holds_alternative<DeBoorSurfaceData>(object.data);
}

/// The patches of a bezier_surface (one) or a deboor_surface (segmentsU x segmentsV, patch (a, b)
/// at a * segmentsV + b); segments receives the counts.
inline PatchComplex surfacePatches(const Document& doc, const DocumentObject& object, std::array<int, 2>* segments = nullptr)
{
    const std::string what = doc.source + ": object \"" + object.name + "\"";
    if (const auto* b = std::get_if<BezierSurfaceData>(&object.data)) {
        if (segments) *segments = {1, 1};
        return PatchComplex{{Patch(b->degree[0], b->degree[1], PointMatrix<double, 3>(b->points))}};
    }
    if (const auto* d = std::get_if<DeBoorSurfaceData>(&object.data)) {
        const EndCondition eu = parseEndCondition(d->end[0], what + ": field \"end[0]\"");
        const EndCondition ev = parseEndCondition(d->end[1], what + ": field \"end[1]\"");
        if (segments) *segments = deboorSurfaceSegments(d->rows, d->cols, eu, ev);
        try {
            return deboorSurfacePatches(PointMatrix<double, 3>(d->points), d->rows, d->cols, eu, ev);
        } catch (const Error& e) {
            throw Error(what + ": " + e.what());
        }
    }
    throw Error(what + ": type " + objectType(object.data) + " is not a surface (bezier_surface, deboor_surface)");
}

} // namespace freeform::cli
