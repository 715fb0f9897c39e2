// freeform interpolate: the C2 cubic spline through points (curve/interpolation.h), written as a
// document with one bezier_spline object named "interpolant".

#include <cmath>
#include <memory>

#include "command.h"
#include "freeform/core/error.h"
#include "freeform/curve/interpolation.h"
#include "freeform/document/object_data.h"
#include "freeform/io/file.h"
#include "freeform/io/json_check.h"
#include "points_file.h"

namespace freeform::cli {
namespace {

template <int Dim>
BezierSplineData interpolate(const PointsFile& in, InterpolationOptions<double, Dim> opt,
                             const std::vector<double>& start, const std::vector<double>& end,
                             const std::string& source)
{
    if (opt.end == InterpolationEnd::Clamped) {
        if (start.size() != Dim || end.size() != Dim)
            throw UsageError("options --start-derivative and --end-derivative: expected " + std::to_string(Dim) +
                             " numbers each for " + std::to_string(Dim) + "D points");
        for (int k = 0; k < Dim; ++k) {
            opt.startDerivative[k] = start[k];
            opt.endDerivative[k] = end[k];
        }
    }
    opt.params = in.params;
    BezierSpline<double, Dim> spline = [&] {
        try {
            return interpolateCubic<double, Dim>(PointMatrix<double, Dim>(in.points), opt);
        } catch (const Error& e) {
            throw Error(source + ": " + e.what());
        }
    }();
    return toData(spline);
}

struct InterpolateOptions {
    std::vector<std::string> positional;
    std::string output, end = "natural", param = "chord", startDerivative, endDerivative;
    int degree = 3;
    const CLI::Option* degreeGiven = nullptr;
    const CLI::Option* endConditionGiven = nullptr;
    const CLI::Option* paramGiven = nullptr;
    const CLI::Option* startGiven = nullptr;
    const CLI::Option* endGiven = nullptr;
};

Json interpolate(const InterpolateOptions& o)
{
    expectPositional(o.positional, 1, "the points file (freeform interpolate POINTS.json -o OUT.json)");
    const std::string& output = o.output;
    InterpolationOptions<double, 3> base;
    try {
        base.end = parseInterpolationEnd(o.end, "option --end");
        base.parametrization = parseParametrization(o.param, "option --param");
    } catch (const Error& e) {
        throw UsageError(e.what());
    }
    const bool clamped = base.end == InterpolationEnd::Clamped;
    const bool hasStart = given(o.startGiven), hasEnd = given(o.endGiven);
    if (clamped && !(hasStart && hasEnd))
        throw UsageError("--end clamped needs --start-derivative and --end-derivative");
    if (!clamped && (hasStart || hasEnd))
        throw UsageError("--start-derivative and --end-derivative go with --end clamped only");
    std::vector<double> start, end;
    if (clamped) {
        start = parseNumberList(o.startDerivative, "--start-derivative", 0);
        end = parseNumberList(o.endDerivative, "--end-derivative", 0);
    }

    const std::string source = o.positional[0];
    const PointsFile in = readPointsFile(source);
    if (!in.params.empty() && given(o.paramGiven))
        throw UsageError("give the parameters either in the points file (\"params\") or by --param, not both");
    if (given(o.degreeGiven)) {
        // Any degree: global NURBS interpolation (cli/interpolate_nurbs.cpp); --end clamped only.
        if (given(o.endConditionGiven) && !clamped) throw UsageError("option --degree: goes with --end clamped or no --end");
        return interpolateNurbsCommand(in.points, in.params, base.parametrization, o.degree, start, end, source, output);
    }

    BezierSplineData data;
    if (in.points.rows() == 2) {
        InterpolationOptions<double, 2> opt;
        opt.end = base.end;
        opt.parametrization = base.parametrization;
        data = interpolate<2>(in, opt, start, end, source);
    } else {
        data = interpolate<3>(in, base, start, end, source);
    }
    Document doc;
    doc.objects.push_back({"interpolant", data, {}});
    writeDocument(doc, output);

    Json out;
    out["object"] = "interpolant";
    out["output"] = output;
    out["points"] = in.points.cols();
    out["segments"] = data.intervals.size();
    out["end"] = toString(base.end);
    out["param"] = in.params.empty() ? toString(base.parametrization) : std::string("given");
    return out;
}

} // namespace

Action defineInterpolate(CLI::App& app)
{
    auto o = std::make_shared<InterpolateOptions>();
    app.footer("POINTS.json is {\"points\": [[x, y(, z)], ...]} with optionally \"params\": [...], the\n"
               "parameter values (strictly increasing; for periodic one more than there are distinct\n"
               "points: where the curve returns to the first point). Writes a document with one\n"
               "bezier_spline object \"interpolant\" whose intervals are the parameter gaps.\n"
               "\n"
               "Output: {\"object\": \"interpolant\", \"output\": F, \"points\": N, \"segments\": L,\n"
               "\"end\": E, \"param\": P or \"given\"}.\n"
               "Exit status: 0 ok, 1 bad input, 2 bad usage.");
    addPositionals(app, "POINTS.json", o->positional, "the points to interpolate");
    app.add_option("-o,--output", o->output, "the document to write (atomically)")->type_name("FILE")->required();
    // --end and --param are checked by the library's parsers (their messages name the choices).
    o->degreeGiven = addNumber(app, "--degree", o->degree,
                               "any degree P: a nurbs_curve by global interpolation (averaged knots on [0, 1]) "
                               "instead of the C2 cubic bezier_spline")
                         ->type_name("P");
    o->endConditionGiven = app.add_option("--end", o->end,
                   "natural: zero second derivative at both ends; clamped: the end derivatives are given; "
                   "periodic: a closed spline, C2 at the first point too (a last point equal to the first is dropped)")
        ->type_name("natural|clamped|periodic")
        ->capture_default_str();
    o->paramGiven = app.add_option("--param", o->param,
                                   "uniform, chord or centripetal (square root of the chord); not together with "
                                   "\"params\" in the file")
                        ->type_name("uniform|chord|centripetal")
                        ->capture_default_str();
    o->startGiven = app.add_option("--start-derivative", o->startDerivative,
                                   "f' at the first point (with --end clamped), comma-separated")
                        ->type_name("x,y[,z]");
    o->endGiven = app.add_option("--end-derivative", o->endDerivative, "f' at the last point (with --end clamped)")
                      ->type_name("x,y[,z]");
    return [o] { return interpolate(*o); };
}

} // namespace freeform::cli
