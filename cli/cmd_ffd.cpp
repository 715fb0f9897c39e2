// freeform ffd: deform a mesh file through a lattice, losslessly (only positions, normals and
// tangents change; everything else in the file is written back as read).

#include <algorithm>
#include <cctype>
#include <memory>

#include "command.h"
#include "freeform/document/document.h"
#include "freeform/io/geometry_data.h"
#include "freeform/io/mesh_io.h"
#include "freeform/volume/deform.h"
#include "freeform/io/deform_file.h"

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

/// freeform ffd DOC.json: the document layer's deformDocument (docs/ffd.md, "Documents": one rule
/// for every object type, the same the editor applies); the report prints its objects and skipped.
Json runFfdDocument(const std::string& input, const std::string& output, const DocumentObject& latticeObject,
                    const Lattice& lattice, const DeformOptions& options, const std::optional<std::string>& reportPath)
{
    TypedDocument doc = TypedDocument::read(input);
    DeformDocumentOptions deform;
    deform.strength = options.strength;
    deform.threads = options.threads;
    const DeformDocumentReport r = deformDocument(doc, lattice, deform);
    Json deformed = Json::array(), skipped = Json::array();
    for (const DeformedObject& o : r.objects) {
        Json d;
        d["name"] = o.name;
        d["from"] = o.from;
        d["type"] = o.type;
        if (o.degree.size() == 1) d["degree"] = o.degree[0];
        else d["degree"] = o.degree; // [p, q] for surfaces; [] for a subdivision cage
        d["inside"] = o.inside;
        deformed.push_back(std::move(d));
    }
    for (const SkippedObject& o : r.skipped) {
        Json s;
        s["name"] = o.name;
        s["type"] = o.type;
        s["reason"] = o.reason;
        skipped.push_back(std::move(s));
    }
    Json j;
    j["input"] = input;
    j["output"] = output;
    j["lattice"] = latticeObject.name;
    j["objects"] = std::move(deformed);
    j["skipped"] = std::move(skipped);
    j["certificate"] = certificateJson(lattice, options.strength, r.certificate, r.certificate.verdict);

    writeDocument(doc.toDocument(), output);
    if (reportPath) writeFileAtomically(*reportPath, j.dump(2) + "\n");
    return j;
}

struct FfdOptions {
    std::vector<std::string> positional;
    std::string lattice, object, output, normals = "jacobian", report;
    double strength = 1, tolerance = 0;
    int threads = 0;
    const CLI::Option* objectGiven = nullptr;
    const CLI::Option* normalsGiven = nullptr;
    const CLI::Option* reportGiven = nullptr;
    const CLI::Option* toleranceGiven = nullptr;
};

/// freeform ffd PART.step: the exact deformation of a part, written as STEP or IGES.
Json ffdPart(const FfdOptions& o, const DocumentObject& object, const Lattice& lattice,
             const std::optional<std::string>& reportPath)
{
    const std::string& input = o.positional[0];
    if (!isPartFileName(o.output) && lowerExtension(o.output) != ".json")
        throw UsageError("option -o: a part is written as STEP, IGES, BRep (.step .stp .iges .igs .brep) or a document (.json)");
    if (given(o.normalsGiven)) throw UsageError("option --normals: applies to meshes only, not to a part");
    if (given(o.toleranceGiven) && !(o.tolerance > 0)) throw UsageError("option --tolerance: must be positive");
    Json j = partFfd(input, o.output, object.name, lattice, o.strength, o.tolerance, o.threads);
    if (reportPath) writeFileAtomically(*reportPath, j.dump(2) + "\n");
    return j;
}

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
    if (!isPartFileName(meshPath) && given(o.toleranceGiven))
        throw UsageError("option --tolerance: applies to parts (STEP, IGES) only");
    if (!isPartFileName(meshPath) && endsWithJson(meshPath) != endsWithJson(output))
        throw UsageError(endsWithJson(meshPath) ? "option -o: a document is deformed into a document (OUT.json)"
                                                : "option -o: a mesh is deformed into a mesh file, not a document");
    if (!isPartFileName(meshPath) && endsWithJson(meshPath) && given(o.normalsGiven))
        throw UsageError("option --normals: applies to meshes only, not to a document");

    const Document doc = readDocument(o.lattice);
    const DocumentObject& object =
        findLattice(doc, given(o.objectGiven) ? std::optional<std::string>(o.object) : std::nullopt,
                        "choose one with --object");
    const Lattice lattice = latticeFromData(std::get<LatticeData>(object.data));
    if (isPartFileName(meshPath)) return ffdPart(o, object, lattice, reportPath);
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
    j["reader"] = file.reader(); // "freeform (lossless)" or "assimp (not lossless)"
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
    app.footer("Three forms:\n"
               "  freeform ffd MESH --lattice LATTICE.json -o OUT [--object NAME] [--normals jacobian|recompute]\n"
               "               [--strength W] [--threads T] [--report REPORT.json]\n"
               "  freeform ffd DOC.json --lattice LATTICE.json -o OUT.json [--object NAME] [--strength W]\n"
               "               [--report REPORT.json]\n"
               "  freeform ffd PART.step|.iges --lattice LATTICE.json -o OUT.step|.iges [--object NAME]\n"
               "               [--strength W] [--tolerance E] [--threads T] [--report REPORT.json]\n"
               "\n"
               "Moves every vertex of MESH through the lattice (p' = p + W sum B (P - R)) and writes\n"
               "OUT in the format of its extension. Written back in the same format, the file keeps\n"
               "everything but positions, normals and tangents as it was (faces, texture\n"
               "coordinates, groups, materials, colours, vertex order). See docs/ffd.md.\n"
               "\n"
               "A document (DOC.json) is deformed exactly: every 3D bezier_curve of degree d and\n"
               "bezier_spline becomes one of degree d (l+m+n), every bezier_surface of degrees (p, q)\n"
               "one of degrees (p (l+m+n), q (l+m+n)) (composition, not control points moved);\n"
               "a deboor_spline becomes a bezier_spline of degree 3 (l+m+n) (under an affine lattice\n"
               "it stays a deboor_spline, its de Boor points mapped; a deboor_surface likewise, else it\n"
               "is skipped); 3D rational_bezier_curve, nurbs_curve, rational_bezier_surface and\n"
               "nurbs_surface objects are composed exactly and keep their type (a surface of degrees\n"
               "(m, n) gets (m (l+m+n), n (l+m+n)), a NURBS keeps its breakpoints); a\n"
               "subdivision_surface has its cage deformed as a cage. 2D objects and\n"
               "lattices are copied unchanged and listed under \"skipped\". The result equals\n"
               "point-wise FFD where the geometry lies in the lattice box (\"inside\": its control\n"
               "points do); outside it is the lattice polynomial continued, whatever the outside\n"
               "policy. The same rule as the editor's \"apply exactly\" (docs/ffd.md, Documents).\n"
               "\n"
               "Prints the report: {\"input\", \"output\", \"lattice\", \"vertices\", \"outside\",\n"
               "\"min_det_j\", \"max_det_j\", \"fold_count\", \"folds\" (first 1000 vertex indices with\n"
               "det J <= 0), \"certificate\": {\"verdict\": \"certified injective\" | \"folds\" |\n"
               "\"undecided\", \"degree\", \"min_coefficient\", \"max_coefficient\"[, \"witness\"]}}.\n"
               "For a document it prints {\"input\", \"output\", \"lattice\", \"objects\": [{\"name\",\n"
               "\"from\", \"type\", \"degree\", \"inside\"}], \"skipped\": [{\"name\", \"type\", \"reason\"}],\n"
               "\"certificate\"}. --normals applies to meshes only.\n"
               "\n"
               "A part (STEP or IGES) is deformed exactly (docs/cad.md, Deformation): every face's\n"
               "surface and every edge's curve composed with the lattice, trims kept, vertices mapped;\n"
               "a face or edge above Open CASCADE's degree 25 is degree reduced within --tolerance E\n"
               "(default 1e-6 of the part's size, certified). Prints {\"input\", \"output\",\n"
               "\"lattice\", \"faces\", \"exact_faces\", \"approximated_faces\",\n"
               "\"max_approximation_error\", \"max_degree\", \"max_gap\", \"valid\", ...}.\n"
               "Exit status: 0 ok, 1 bad input (mesh, document, lattice, a degree above 67), 2 bad\n"
               "usage. On error no output file is written.");
    addPositionals(app, "MESH", o->positional,
                   "the mesh (.obj .ply .stl .off .gltf .glb), document (.json) or part (.step .stp .iges .igs .brep) "
                   "to deform");
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
    o->toleranceGiven = addNumber(app, "--tolerance", o->tolerance,
                                  "a part: the largest error of a face or edge degree reduced to 25")
                            ->type_name("E");
    o->reportGiven = app.add_option("--report", o->report, "also write the report (below) to FILE")->type_name("FILE");
    return [o] { return ffd(*o); };
}

} // namespace freeform::cli
