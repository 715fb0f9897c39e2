// deformDocument (document/operations.h): one rule for every object kind under free-form
// deformation, written out in docs/ffd.md ("Documents"). What a kind becomes is its file's word
// (kindDeform, src/document/kinds/TYPE.cpp); the checks and the report are the same for all.

#include <cmath>

#include "freeform/core/error.h"
#include "freeform/core/format.h"
#include "freeform/document/operations.h"
#include "kind_file.h"

namespace freeform {
namespace detail {

bool pointsInsideLattice(const Lattice& lattice, const Eigen::Ref<const Eigen::Matrix<double, 3, Eigen::Dynamic>>& points)
{
    for (Eigen::Index i = 0; i < points.cols(); ++i)
        if (!Lattice::insideBox(lattice.toLattice(points.col(i)))) return false;
    return true;
}

PointColumns mapByPolynomial(const Lattice& lattice, const PointColumns& points, double strength)
{
    Lattice continued = lattice;
    continued.setOutside(OutsidePolicy::Extrapolate);
    PointColumns out(3, points.cols());
    for (Eigen::Index i = 0; i < points.cols(); ++i) out.col(i) = continued.deform(points.col(i), strength).point;
    return out;
}

} // namespace detail

bool isAffineLattice(const Lattice& lattice, double strength)
{
    return affineMap(lattice, strength).has_value();
}

DeformDocumentReport deformDocument(TypedDocument& doc, const Lattice& lattice, const DeformDocumentOptions& options)
{
    const double w = options.strength;
    const bool extrapolate = lattice.outside() == OutsidePolicy::Extrapolate;
    const bool affine = isAffineLattice(lattice, w);
    DeformDocumentReport report;
    std::vector<std::pair<ObjectId, ObjectData>> changes;
    const detail::KindDeformInput input{lattice, w, affine, options};

    for (const TypedObject& o : doc.objects()) {
        const std::string type = o.type();
        auto skip = [&](const std::string& reason) { report.skipped.push_back({o.id(), o.name(), type, reason}); };
        if (o.dimension() != 3) {
            skip("a 2D object (the lattice deforms 3D space)");
            continue;
        }
        detail::KindDeform step;
        try {
            step = std::visit([&](const auto& d) { return detail::kindDeform(d, o.geometry(), input); }, o.data());
        } catch (const Error& e) {
            throw Error(doc.what(o) + ": " + e.what());
        }
        if (!step.result) {
            skip(step.skip);
            continue;
        }
        ObjectData result = std::move(*step.result);
        DeformedObject r;
        r.id = o.id();
        r.name = o.name();
        r.from = type;
        r.inside = step.inside;
        r.degree = std::move(step.degree);
        std::string note = std::move(step.note);
        // Far outside the box the lattice polynomial (continued there for the exact compositions, and
        // for a cage under the extrapolate policy) can overflow: refuse before the document changes
        // (JSON has no number for infinity or NaN).
        if (const std::string field = std::visit([](const auto& d) { return detail::kindNonFinite(d); }, result);
            !field.empty())
            throw Error(doc.what(o) + ": the deformed " + field +
                        " are not finite (the lattice polynomial overflows this far outside its box: use a lattice "
                        "that covers the object)");
        // Subdivision cages follow the outside policy point by point (as meshes); everything else is
        // the polynomial continued, which equals point-wise FFD inside the box or under extrapolate.
        const bool pointwise = step.pointwise;
        r.exact = pointwise ? affine && (r.inside || extrapolate) : (r.inside || extrapolate);
        if (!pointwise && !r.exact) {
            if (options.skipInexact) {
                skip("control points outside the lattice box (exact only inside, or with the extrapolate policy)");
                continue;
            }
            if (!note.empty()) note += "; ";
            note += "control points outside the lattice box: the lattice polynomial is continued there, not the " +
                    toString(lattice.outside()) + " policy";
        }
        r.type = objectType(result);
        r.note = std::move(note);
        report.objects.push_back(std::move(r));
        changes.emplace_back(o.id(), std::move(result));
    }
    report.certificate = certify(lattice, w);
    // Build every new geometry before changing the document, so an error leaves it as it was.
    TypedDocument next = doc;
    for (auto& [id, data] : changes) next.replace(id, std::move(data));
    doc = std::move(next);
    return report;
}

} // namespace freeform
