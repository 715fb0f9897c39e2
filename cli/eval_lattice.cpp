// `freeform eval` for lattice objects: the lattice map at (s, t, u), its partial derivatives and
// det J of the world-space deformation.

#include <Eigen/LU>

#include "command.h"
#include "freeform/io/geometry_data.h"
#include "freeform/volume/lattice.h"

namespace freeform::cli {
namespace {

Json evalLattice(const Document& doc, const DocumentObject& object, const std::string& at, int order)
{
    const std::vector<double> stu = parseNumberList(at, "--at", 3);
    for (double x : stu)
        if (x < 0 || x > 1)
            throw Error(doc.source + ": object \"" + object.name + "\": (s, t, u) = " + at +
                        " is outside the lattice's domain [0, 1]^3");
    if (order > 1)
        throw Error(doc.source + ": object \"" + object.name + "\": a lattice has --derivatives 0 or 1, not " +
                    std::to_string(order));
    const Lattice lattice = latticeFromData(std::get<LatticeData>(object.data));
    const auto jet = lattice.map(Eigen::Vector3d(stu[0], stu[1], stu[2]));
    Json out;
    out["object"] = object.name;
    out["at"] = Json::array({stu[0], stu[1], stu[2]});
    out["point"] = pointJson(jet.point.data(), 3);
    if (order == 1) {
        Json d;
        d["s"] = pointJson(jet.ds.data(), 3);
        d["t"] = pointJson(jet.dt.data(), 3);
        d["u"] = pointJson(jet.du.data(), 3);
        // det J of p -> p' = det[f_s f_t f_u] / det[S T U] (chain rule through the frame).
        d["det"] = jet.jacobian().determinant() / lattice.axes().determinant();
        out["derivatives"] = Json::array({d});
    }
    return out;
}

} // namespace

void addLatticeEvaluators(std::map<std::string, Evaluator>& table)
{
    table["lattice"] = evalLattice;
}

} // namespace freeform::cli
