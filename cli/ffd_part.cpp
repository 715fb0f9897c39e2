// freeform ffd and freeform convert on a STEP or IGES part: the exact deformation and the writer
// (docs/cli.md, docs/cad.md "Deformation" and "Writing").

#include <filesystem>

#include "command.h"
#include "freeform/brep/part_deform.h"
#include "freeform/cad/cad_file.h"
#include "freeform/document/model.h"
#include "freeform/document/object_data.h"

namespace freeform::cli {
namespace {

/// The written file's facts, as both commands print them.
void addWriteReport(Json& j, const CadWriteReport& w)
{
    j["valid"] = w.valid;
    j["fitted_trims"] = w.fittedPcurves;
    j["max_trim_gap"] = w.maxPcurveGap;
    j["raised_tolerances"] = w.raisedTolerances;
    j["max_tolerance"] = w.maxTolerance;
}

bool isJson(const std::string& path) { return lowerExtension(path) == ".json"; }

/// The name of the part object a document written from `source` holds: the file's stem.
std::string partObjectName(const std::string& source)
{
    const std::string stem = std::filesystem::path(source).stem().string();
    return stem.empty() ? std::string("unnamed") : stem;
}

/// A document holding the part as one object, named after the file it came from ("plate" for
/// plate.step), written atomically.
void writePartDocument(const Part& part, const std::string& source, const std::string& output)
{
    Document doc;
    doc.objects.push_back({partObjectName(source), toData(part), {}});
    writeDocument(doc, output);
}

} // namespace

Json partFfd(const std::string& path, const std::string& output, const std::string& latticeName,
             const Lattice& lattice, double strength, double tolerance, int threads)
{
    const Part part = readCadFile(path);
    PartDeformOptions options;
    options.strength = strength;
    // A document holds degrees up to 67: no approximation there; STEP and IGES cap them.
    const bool document = isJson(output);
    options.maxDegree = document ? 0 : cadMaxDegree();
    options.tolerance = tolerance;
    options.threads = threads;
    DeformedPart deformed = deformPart(part, RationalLattice(lattice), options);
    CadWriteReport written;
    if (document) {
        writePartDocument(deformed.part, path, output);
        // No writer's check: valid means the deformation added no sampled gap over its edge's
        // tolerance (checkPart; a file may have such gaps already: screw.step has two).
        written.valid = checkPart(deformed.part).gapsOverTolerance <= checkPart(part).gapsOverTolerance;
        written.maxTolerance = deformed.report.maxTolerance;
    } else {
        written = writeCadFile(deformed.part, output);
    }
    const PartDeformReport& r = deformed.report;
    Json j;
    j["input"] = path;
    j["output"] = output;
    j["lattice"] = latticeName;
    j["faces"] = r.faces;
    j["exact_faces"] = r.exactFaces;
    j["approximated_faces"] = r.approximatedFaces.size();
    j["max_approximation_error"] = r.maxApproximationError;
    j["max_degree"] = r.maxDegree;
    j["max_gap"] = r.maxGap;
    addWriteReport(j, written);
    j["outside_faces"] = r.outsideFaces;
    j["approximated_edges"] = r.approximatedEdges;
    j["affine"] = r.affine;
    j["lipschitz"] = r.lipschitz;
    j["tolerance"] = options.tolerance > 0 ? options.tolerance : 1e-6 * part.bounds().diagonal().norm();
    Json approximated = Json::array();
    for (int f : r.approximatedFaces) {
        Json a;
        a["face"] = f + 1;
        a["error"] = r.faceErrors[static_cast<std::size_t>(f)];
        approximated.push_back(std::move(a));
    }
    j["approximated"] = std::move(approximated);
    return j;
}

Lattice::Points partBoxCorners(const std::string& path, const std::optional<std::string>& object, long long& vertices)
{
    std::string name;
    const Part part = isJson(path) ? documentPart(path, object, name) : readCadFile(path);
    vertices = static_cast<long long>(part.vertices.size());
    const Box<double, 3> box = part.bounds();
    Lattice::Points corners(3, 2);
    corners.col(0) = box.min();
    corners.col(1) = box.max();
    return corners;
}

Json partConvert(const std::string& path, const std::string& output, const std::optional<std::string>& object)
{
    std::string name;
    const Part part = isJson(path) ? documentPart(path, object, name) : readCadFile(path);
    const PartCheck check = checkPart(part);
    Json j;
    j["input"] = path;
    j["output"] = output;
    if (isJson(output)) {
        writePartDocument(part, path, output);
        addPartCounts(j, part, check);
        j["object"] = partObjectName(path);
        return j;
    }
    const CadWriteReport written = writeCadFile(part, output);
    if (!name.empty()) j["object"] = name;
    addPartCounts(j, part, check);
    addWriteReport(j, written);
    return j;
}

} // namespace freeform::cli
