#pragma once
// The document's plain data of geometry: toData, the inverse of buildGeometry for every kind (the
// fields as docs/format.md spells them; declared beside buildGeometry in document/model.h, so a
// kind's two directions sit together), and the control points of any object's data.

#include "freeform/brep/part.h"
#include "freeform/curve/nurbs_curve.h"
#include "freeform/curve/rational_bezier_curve.h"
#include "freeform/document/model.h"
#include "freeform/io/document.h"
#include "freeform/surface/nurbs_surface.h"
#include "freeform/surface/rational_bezier_surface.h"

namespace freeform {

/// The control points of an object as its data holds them (dim x count): a curve's, surface's or
/// lattice's points, a subdivision cage's inline vertices (empty when its mesh is a file), a
/// trimmed surface's NURBS grid; nullptr for a part (its faces are not edited point by point).
const PointColumns* dataPoints(const ObjectData& data);
PointColumns* dataPoints(ObjectData& data);

} // namespace freeform
