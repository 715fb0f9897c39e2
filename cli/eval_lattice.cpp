// `freeform eval` for lattice objects: the lattice map at (s, t, u), its partial derivatives and
// det J of the world-space deformation, from the document layer's evaluate().

#include "command.h"
#include "freeform/document/operations.h"

namespace freeform::cli {

Json evalLattice(const TypedDocument& doc, const TypedObject& object, const std::string& at, int order)
{
    const std::vector<double> stu = parseNumberList(at, "--at", 3);
    for (double x : stu)
        if (x < 0 || x > 1)
            throw Error(doc.what(object) + ": (s, t, u) = " + at + " is outside the lattice's domain [0, 1]^3");
    const Evaluation e = evaluate(doc, object, stu, order);
    Json out;
    out["object"] = object.name();
    out["at"] = Json::array({stu[0], stu[1], stu[2]});
    out["point"] = pointJson(e.point.data(), 3);
    if (order == 1) {
        Json d;
        for (std::size_t k = 0; k < e.keys.size(); ++k) d[e.keys[k]] = pointJson(e.derivatives[k].data(), 3);
        d["det"] = *e.det; // det J of p -> p' (document/operations.h)
        out["derivatives"] = Json::array({d});
    }
    return out;
}

} // namespace freeform::cli
