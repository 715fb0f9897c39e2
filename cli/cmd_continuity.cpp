// freeform continuity: the continuity report of every joint of a spline (curve/continuity.h).

#include <memory>

#include "command.h"
#include "freeform/document/operations.h"

namespace freeform::cli {
namespace {

/// The joints from the document layer's continuity() (a bezier_spline, a deboor_spline through the
/// A-frame, a nurbs_curve at its knots; 2D or 3D).
Json report(const TypedDocument& doc, const TypedObject& object, const ContinuityTolerances<double>& tol)
{
    Json joints = Json::array();
    for (const auto& j : freeform::continuity(doc, object, tol)) {
        Json e;
        e["joint"] = j.joint;
        e["t"] = j.t;
        e["C"] = j.C;
        e["G"] = j.G;
        e["jumps"] = j.jumps;
        joints.push_back(std::move(e));
    }
    Json out;
    out["object"] = object.name();
    out["joints"] = std::move(joints);
    return out;
}

struct ContinuityOptions {
    std::vector<std::string> positional;
    std::string object;
    double tolerance = 1e-9;
    const CLI::Option* toleranceGiven = nullptr;
};

Json continuity(const ContinuityOptions& o)
{
    expectPositional(o.positional, 1, "the document (freeform continuity DOC.json --object NAME)");
    ContinuityTolerances<double> tol;
    if (given(o.toleranceGiven)) {
        if (!(o.tolerance > 0)) throw UsageError("option --tolerance: must be positive");
        tol.relative = tol.angle = o.tolerance;
    }
    const TypedDocument doc = TypedDocument::read(o.positional[0]);
    return report(doc, doc.object(o.object), tol); // every curve type, nurbs_curve included
}

} // namespace

Action defineContinuity(CLI::App& app)
{
    auto o = std::make_shared<ContinuityOptions>();
    app.footer("Analyses every joint where two segments of the spline NAME meet (bezier_spline, or\n"
               "deboor_spline through the A-frame); a closed spline's closing joint (joint 0, t = 0)\n"
               "comes first.\n"
               "\n"
               "Output: {\"object\": NAME, \"joints\": [{\"joint\": J, \"t\": T, \"C\": C, \"G\": G,\n"
               "\"jumps\": [...]}, ...]} with C the highest order k whose derivatives 0..k agree (-1: the\n"
               "points differ; C = degree: one polynomial), G the geometric level (0..2, -1 when the\n"
               "points differ) and jumps[k] = |f_R^(k) - f_L^(k)| for k = 0..degree, derivatives with\n"
               "respect to the global parameter.\n"
               "Exit status: 0 ok, 1 bad input, 2 bad usage.");
    addPositionals(app, "DOC.json", o->positional, "the document");
    app.add_option("--object", o->object, "the spline")->type_name("NAME")->required();
    o->toleranceGiven = addNumber(app, "--tolerance", o->tolerance,
                                  "relative tolerance (positive): derivative k agrees when its jump is at most E "
                                  "times the size of the k-th derivative on the two segments; also the largest "
                                  "difference of the unit tangents for G1")
                            ->type_name("E")
                            ->default_str("1e-9");
    return [o] { return continuity(*o); };
}

} // namespace freeform::cli
