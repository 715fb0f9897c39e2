// freeform ffd: deform a mesh file through a lattice, losslessly (only positions, normals and
// tangents change; everything else in the file is written back as read).

#include <algorithm>
#include <cctype>
#include <memory>

#include "command.h"
#include "freeform/io/geometry_data.h"
#include "freeform/io/mesh_io.h"
#include "freeform/volume/deform.h"
#include "freeform/io/deform_file.h"
#include "spline_object.h"

namespace freeform::cli {
namespace {

bool endsWithJson(const std::string& path)
{
    if (path.size() < 5) return false;
    std::string ext = path.substr(path.size() - 5);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".json";
}

/// The certificate of the lattice box as JSON; `verdict` may be stronger than the certificate's
/// own (a folded vertex inside the box).
Json certificateJson(const Lattice& lattice, double strength, const Certificate& cert, Verdict verdict)
{
    Json c;
    c["verdict"] = toString(verdict);
    const auto degree = jacobianPolynomial(lattice, strength).degree;
    c["degree"] = Json::array({degree[0], degree[1], degree[2]});
    c["min_coefficient"] = cert.minCoefficient;
    c["max_coefficient"] = cert.maxCoefficient;
    if (cert.verdict == Verdict::Folds) c["witness"] = pointJson(cert.witness.data(), 3);
    return c;
}

/// Whether every control point (column) lies in the lattice box: then, by the convex hull
/// property, so does the whole curve or patch, and the exact composition equals point-wise FFD.
bool controlPointsInside(const Lattice& lattice, const PointColumns& points)
{
    for (Eigen::Index i = 0; i < points.cols(); ++i)
        if (!Lattice::insideBox(lattice.toLattice(points.col(i)))) return false;
    return true;
}

/// A spline's segments pushed through the lattice exactly, as a bezier_spline of degree
/// d (l+m+n) on the same intervals (joints shared, as the format stores them).
BezierSplineData deformSpline(const Lattice& lattice, const BezierSpline<double, 3>& spline, double strength)
{
    BezierSplineData out;
    out.closed = spline.closed();
    out.intervals = spline.intervals();
    const int segments = spline.segmentCount();
    for (int i = 0; i < segments; ++i) {
        const BezierCurve<double, 3> piece = deformCurve(lattice, spline.segment(i), strength);
        const int d = piece.degree();
        if (i == 0) {
            out.degree = d;
            out.points.resize(3, static_cast<Eigen::Index>(spline.closed() ? segments * d : segments * d + 1));
        }
        // Segment i owns its first d points; the last open segment also its end point.
        out.points.middleCols(static_cast<Eigen::Index>(i) * d, d) = piece.controlPoints().leftCols(d);
        if (!spline.closed() && i + 1 == segments) out.points.col(out.points.cols() - 1) = piece.controlPoints().col(d);
    }
    return out;
}

/// A bezier_spline or (through the A-frame) deboor_spline object in 3D; library errors unprefixed.
BezierSpline<double, 3> splineFromObjectUnprefixed(const DocumentObject& object)
{
    using Points = PointMatrix<double, 3>;
    if (const auto* b = std::get_if<BezierSplineData>(&object.data))
        return BezierSpline<double, 3>(b->degree, b->closed, Points(b->points), b->intervals);
    const auto& d = std::get<DeBoorSplineData>(object.data);
    return BezierSpline<double, 3>::fromDeBoor(Points(d.points), parseEndCondition(d.end, "end"), d.intervals);
}

/// freeform ffd DOC.json: every 3D Bézier curve, spline and patch of the document through the
/// lattice, exactly (by composition); other objects are copied unchanged and listed as skipped.
Json runFfdDocument(const std::string& input, const std::string& output, const DocumentObject& latticeObject,
                    const Lattice& lattice, const DeformOptions& options, const std::optional<std::string>& reportPath)
{
    Document doc = readDocument(input);
    const double w = options.strength;
    Json deformed = Json::array(), skipped = Json::array();
    auto skip = [&](const DocumentObject& o, const std::string& reason) {
        Json s;
        s["name"] = o.name;
        s["type"] = objectType(o.data);
        s["reason"] = reason;
        skipped.push_back(std::move(s));
    };
    for (DocumentObject& o : doc.objects) {
        const std::string type = objectType(o.data);
        // The rational types are composed by deformDocument (document layer); this bridge skips them.
        if (type == "deboor_surface" || type == "subdivision_surface" || type == "lattice" ||
            type.find("rational_") == 0 || type.find("nurbs_") == 0) {
            skip(o, "no exact deformation for a " + type);
            continue;
        }
        int dim = 3;
        if (const auto* c = std::get_if<BezierCurveData>(&o.data)) dim = static_cast<int>(c->points.rows());
        else if (type == "bezier_spline" || type == "deboor_spline") dim = splineDimension(doc, o);
        if (dim != 3) {
            skip(o, "a 2D object (the lattice deforms 3D space)");
            continue;
        }
        bool inside = true;
        Json degree;
        try {
            if (auto* c = std::get_if<BezierCurveData>(&o.data)) {
                inside = controlPointsInside(lattice, c->points);
                const BezierCurve<double, 3> curve((Eigen::Matrix<double, 3, Eigen::Dynamic>(c->points)));
                c->points = deformCurve(lattice, curve, w).controlPoints();
                degree = c->points.cols() - 1;
            } else if (auto* s = std::get_if<BezierSurfaceData>(&o.data)) {
                inside = controlPointsInside(lattice, s->points);
                const BezierSurface<double, 3> patch(s->degree[0], s->degree[1],
                                                     Eigen::Matrix<double, 3, Eigen::Dynamic>(s->points));
                const BezierSurface<double, 3> moved = deformSurface(lattice, patch, w);
                s->degree = {moved.degreeU(), moved.degreeV()};
                s->points = moved.controlPoints();
                degree = Json::array({moved.degreeU(), moved.degreeV()});
            } else {
                const BezierSpline<double, 3> spline = splineFromObjectUnprefixed(o);
                inside = controlPointsInside(lattice, spline.controlPoints());
                BezierSplineData moved = deformSpline(lattice, spline, w);
                degree = moved.degree;
                o.data = std::move(moved);
            }
        } catch (const Error& e) {
            throw Error(doc.source + ": object \"" + o.name + "\": " + e.what());
        }
        Json d;
        d["name"] = o.name;
        d["from"] = type;
        d["type"] = objectType(o.data);
        d["degree"] = std::move(degree);
        d["inside"] = inside;
        deformed.push_back(std::move(d));
    }

    const Certificate cert = certify(lattice, w);
    Json j;
    j["input"] = input;
    j["output"] = output;
    j["lattice"] = latticeObject.name;
    j["objects"] = std::move(deformed);
    j["skipped"] = std::move(skipped);
    j["certificate"] = certificateJson(lattice, w, cert, cert.verdict);

    writeDocument(doc, output);
    if (reportPath) writeFileAtomically(*reportPath, j.dump(2) + "\n");
    return j;
}

struct FfdOptions {
    std::vector<std::string> positional;
    std::string lattice, object, output, normals = "jacobian", report;
    double strength = 1;
    int threads = 0;
    const CLI::Option* objectGiven = nullptr;
    const CLI::Option* normalsGiven = nullptr;
    const CLI::Option* reportGiven = nullptr;
};

Json ffd(const FfdOptions& o)
{
    expectPositional(o.positional, 1, "the mesh file (freeform ffd MESH --lattice LATTICE.json -o OUT)");
    const std::string& meshPath = o.positional[0];
    const std::string& output = o.output;
    const NormalMode normals = parseNormalMode(o.normals, "--normals");
    DeformOptions options;
    options.strength = o.strength;
    options.threads = o.threads;
    if (options.threads < 0) throw UsageError("option --threads: must not be negative");
    const std::optional<std::string> reportPath = given(o.reportGiven) ? std::optional<std::string>(o.report) : std::nullopt;
    if (endsWithJson(meshPath) != endsWithJson(output))
        throw UsageError(endsWithJson(meshPath) ? "option -o: a document is deformed into a document (OUT.json)"
                                                : "option -o: a mesh is deformed into a mesh file, not a document");
    if (endsWithJson(meshPath) && given(o.normalsGiven))
        throw UsageError("option --normals: applies to meshes only, not to a document");

    const Document doc = readDocument(o.lattice);
    const DocumentObject& object =
        findLattice(doc, given(o.objectGiven) ? std::optional<std::string>(o.object) : std::nullopt);
    const Lattice lattice = latticeFromData(std::get<LatticeData>(object.data));
    if (endsWithJson(meshPath)) return runFfdDocument(meshPath, output, object, lattice, options, reportPath);
    MeshFile file = MeshFile::read(meshPath);

    const MeshFileDeformation deformed = deformMeshFile(lattice, file, options, normals);
    const DeformReport& report = deformed.report;

    // The certificate for the lattice box; a vertex inside the box with det J <= 0 decides "folds".
    const Certificate cert = certify(lattice, options.strength);
    const auto& outsideList = deformed.outside;
    std::size_t insideFolds = 0;
    for (int v : report.folds)
        if (!std::binary_search(outsideList.begin(), outsideList.end(), v)) ++insideFolds;
    const Verdict verdict = insideFolds > 0 ? Verdict::Folds : cert.verdict;

    Json j;
    j["input"] = meshPath;
    j["output"] = output;
    j["lattice"] = object.name;
    j["vertices"] = report.vertices;
    j["outside"] = report.outside;
    j["min_det_j"] = report.minDetJ;
    j["max_det_j"] = report.maxDetJ;
    j["fold_count"] = report.foldCount;
    Json folds = Json::array();
    for (std::size_t i = 0; i < std::min<std::size_t>(report.folds.size(), 1000); ++i) folds.push_back(report.folds[i]);
    j["folds"] = std::move(folds); // the first 1000 fold-over vertices (0-based, file order)
    j["certificate"] = certificateJson(lattice, options.strength, cert, verdict);

    file.write(output);
    if (reportPath) writeFileAtomically(*reportPath, j.dump(2) + "\n");
    return j;
}

} // namespace

Action defineFfd(CLI::App& app)
{
    auto o = std::make_shared<FfdOptions>();
    app.footer("Two forms:\n"
               "  freeform ffd MESH --lattice LATTICE.json -o OUT [--object NAME] [--normals jacobian|recompute]\n"
               "               [--strength W] [--threads T] [--report REPORT.json]\n"
               "  freeform ffd DOC.json --lattice LATTICE.json -o OUT.json [--object NAME] [--strength W]\n"
               "               [--report REPORT.json]\n"
               "\n"
               "Moves every vertex of MESH through the lattice (p' = p + W sum B (P - R)) and writes\n"
               "OUT in the format of its extension. Written back in the same format, the file keeps\n"
               "everything but positions, normals and tangents as it was (faces, texture\n"
               "coordinates, groups, materials, colours, vertex order). See docs/ffd.md.\n"
               "\n"
               "A document (DOC.json) is deformed exactly: every 3D bezier_curve of degree d and\n"
               "bezier_spline becomes one of degree d (l+m+n), every bezier_surface of degrees (p, q)\n"
               "one of degrees (p (l+m+n), q (l+m+n)) (composition, not control points moved);\n"
               "a deboor_spline becomes a bezier_spline of degree 3 (l+m+n). Other objects are\n"
               "copied unchanged and listed under \"skipped\". The result equals point-wise FFD\n"
               "where the geometry lies in the lattice box (\"inside\": its control points do); outside\n"
               "it is the lattice polynomial continued, whatever the outside policy.\n"
               "\n"
               "Prints the report: {\"input\", \"output\", \"lattice\", \"vertices\", \"outside\",\n"
               "\"min_det_j\", \"max_det_j\", \"fold_count\", \"folds\" (first 1000 vertex indices with\n"
               "det J <= 0), \"certificate\": {\"verdict\": \"certified injective\" | \"folds\" |\n"
               "\"undecided\", \"degree\", \"min_coefficient\", \"max_coefficient\"[, \"witness\"]}}.\n"
               "For a document it prints {\"input\", \"output\", \"lattice\", \"objects\": [{\"name\",\n"
               "\"from\", \"type\", \"degree\", \"inside\"}], \"skipped\": [{\"name\", \"type\", \"reason\"}],\n"
               "\"certificate\"}. --normals applies to meshes only.\n"
               "Exit status: 0 ok, 1 bad input (mesh, document, lattice, a degree above 67), 2 bad\n"
               "usage. On error no output file is written.");
    addPositionals(app, "MESH", o->positional, "the mesh (.obj .ply .stl .off .gltf .glb) or document (.json) to deform");
    app.add_option("--lattice", o->lattice, "a document with the lattice object")->type_name("FILE")->required();
    o->objectGiven = app.add_option("--object", o->object, "which lattice, when the document has several")->type_name("NAME");
    app.add_option("-o,--output", o->output, "the deformed mesh (.obj .ply .stl .off .gltf .glb) or document, atomically")
        ->type_name("OUT")
        ->required();
    o->normalsGiven = app.add_option("--normals", o->normals,
                                     "jacobian: cof(J) n renormalised; recompute: area-weighted vertex normals of "
                                     "the deformed mesh")
                          ->type_name("MODE")
                          ->check(CLI::IsMember({"jacobian", "recompute"}))
                          ->capture_default_str();
    addNumber(app, "--strength", o->strength, "scales the deformation")->type_name("W")->capture_default_str();
    addNumber(app, "--threads", o->threads, "worker threads (0: all cores)")->type_name("T")->capture_default_str();
    o->reportGiven = app.add_option("--report", o->report, "also write the report (below) to FILE")->type_name("FILE");
    return [o] { return ffd(*o); };
}

} // namespace freeform::cli
