// The lattice kind in the document layer (src/document/kind_file.h): a trivariate Bézier FFD
// lattice, its degrees, box, points and outside policy (docs/format.md, docs/ffd.md). It deforms
// the other objects and is not deformed itself.

#include "freeform/io/geometry_data.h"

#include "../kind_file.h"

namespace freeform {

LatticeData toData(const Lattice& lattice) { return latticeToData(lattice); }

namespace detail {

KindRow kindRow(std::type_identity<LatticeData>)
{
    return {"FFD lattice", KindNature::Volume, KindParameters::STU, 3, false, false, false,
            kindOps({KindOperation::Evaluate, KindOperation::DeformsOthers})};
}

Geometry kindBuild(const LatticeData& d, const KindBuild&) { return latticeFromData(d); }

void kindNet(const LatticeData& d, const Geometry&, ControlNet& net)
{
    net.points = d.points;
    const int a = d.degree[0] + 1, b = d.degree[1] + 1, c = d.degree[2] + 1;
    auto index = [&](int i, int j, int k) { return (i * b + j) * c + k; };
    for (int i = 0; i < a; ++i)
        for (int j = 0; j < b; ++j)
            for (int k = 0; k < c; ++k) {
                if (i + 1 < a) net.edges.emplace_back(index(i, j, k), index(i + 1, j, k));
                if (j + 1 < b) net.edges.emplace_back(index(i, j, k), index(i, j + 1, k));
                if (k + 1 < c) net.edges.emplace_back(index(i, j, k), index(i, j, k + 1));
            }
}

std::string kindDetails(const LatticeData& d) { return degreeWords(d.degree[0], d.degree[1], d.degree[2]); }

std::optional<AnyCurve> kindCurve(const Geometry&, std::type_identity<LatticeData>) { return std::nullopt; }

std::optional<AnySurface> kindSurface(const Geometry&, std::type_identity<LatticeData>) { return std::nullopt; }

KindDeform kindDeform(const LatticeData&, const Geometry&, const KindDeformInput&)
{
    return KindDeform::skipped("no exact deformation for a " + std::string(kindName(ObjectKind::Lattice)));
}

std::optional<ObjectData> kindToNurbs(const LatticeData&, const Geometry&, const std::string&) { return std::nullopt; }

std::optional<ObjectData> kindFromNurbs(const LatticeData&, const Geometry&, const std::string&) { return std::nullopt; }

PointColumns* kindPoints(LatticeData& d) { return &d.points; }

std::string kindNonFinite(const LatticeData& d) { return nonFinitePointsWeights(d); }

} // namespace detail
} // namespace freeform
