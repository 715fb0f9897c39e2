// freeform continuity: the continuity report of every joint of a spline (curve/continuity.h).

#include "command.h"
#include "freeform/curve/continuity.h"
#include "spline_object.h"

namespace freeform::cli {
namespace {

template <int Dim>
Json report(const Document& doc, const DocumentObject& object, const ContinuityTolerances<double>& tol)
{
    const BezierSpline<double, Dim> spline = splineFromObject<Dim>(doc, object);
    Json joints = Json::array();
    for (const auto& j : continuityReport(spline, tol)) {
        Json e;
        e["joint"] = j.joint;
        e["t"] = j.t;
        e["C"] = j.C;
        e["G"] = j.G;
        e["jumps"] = j.jumps;
        joints.push_back(std::move(e));
    }
    Json out;
    out["object"] = object.name;
    out["joints"] = std::move(joints);
    return out;
}

int runContinuity(const std::vector<std::string>& argv)
{
    const Args args(argv, {"object", "tolerance"}, {});
    args.expectPositional(1, "the document (freeform continuity DOC.json --object NAME)");
    const std::string name = args.required("object");
    ContinuityTolerances<double> tol;
    if (const auto e = args.get("tolerance")) {
        const double v = parseNumber(*e, "--tolerance");
        if (!(v > 0)) throw UsageError("option --tolerance: must be positive");
        tol.relative = tol.angle = v;
    }
    const Document doc = readDocument(args.positional()[0]);
    const DocumentObject& object = doc.object(name);
    printJson(splineDimension(doc, object) == 2 ? report<2>(doc, object, tol) : report<3>(doc, object, tol));
    return 0;
}

const RegisterCommand reg({"continuity", "continuity of every joint of a spline (C and G levels, jumps)",
                           "usage: freeform continuity DOC.json --object NAME [--tolerance E]\n"
                           "\n"
                           "Analyses every joint where two segments of the spline NAME meet (bezier_spline, or\n"
                           "deboor_spline through the A-frame); a closed spline's closing joint (joint 0, t = 0)\n"
                           "comes first.\n"
                           "\n"
                           "  --object NAME    the spline\n"
                           "  --tolerance E    relative tolerance (default 1e-9): derivative k agrees when its jump\n"
                           "                   is at most E times the size of the k-th derivative on the two\n"
                           "                   segments; also the largest difference of the unit tangents for G1\n"
                           "\n"
                           "Output: {\"object\": NAME, \"joints\": [{\"joint\": J, \"t\": T, \"C\": C, \"G\": G,\n"
                           "\"jumps\": [...]}, ...]} with C the highest order k whose derivatives 0..k agree (-1: the\n"
                           "points differ; C = degree: one polynomial), G the geometric level (0..2, -1 when the\n"
                           "points differ) and jumps[k] = |f_R^(k) - f_L^(k)| for k = 0..degree, derivatives with\n"
                           "respect to the global parameter.\n"
                           "Exit status: 0 ok, 1 bad input, 2 bad usage.\n",
                           runContinuity});

} // namespace
} // namespace freeform::cli
