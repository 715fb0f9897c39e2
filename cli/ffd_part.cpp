// freeform ffd and freeform convert on a STEP or IGES part: the exact deformation and the writer
// (docs/cli.md, docs/cad.md "Deformation" and "Writing").

#include "command.h"
#include "freeform/brep/part_deform.h"
#include "freeform/cad/cad_file.h"

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

} // namespace

Json partFfd(const std::string& path, const std::string& output, const std::string& latticeName,
             const Lattice& lattice, double strength, double tolerance, int threads)
{
    const Part part = readCadFile(path);
    PartDeformOptions options;
    options.strength = strength;
    options.maxDegree = cadMaxDegree();
    options.tolerance = tolerance;
    options.threads = threads;
    DeformedPart deformed = deformPart(part, RationalLattice(lattice), options);
    const CadWriteReport written = writeCadFile(deformed.part, output);
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

Lattice::Points partBoxCorners(const std::string& path, long long& vertices)
{
    const Part part = readCadFile(path);
    vertices = static_cast<long long>(part.vertices.size());
    const Box<double, 3> box = part.bounds();
    Lattice::Points corners(3, 2);
    corners.col(0) = box.min();
    corners.col(1) = box.max();
    return corners;
}

Json partConvert(const std::string& path, const std::string& output)
{
    const Part part = readCadFile(path);
    const CadWriteReport written = writeCadFile(part, output);
    const PartCheck check = checkPart(part);
    Json j;
    j["input"] = path;
    j["output"] = output;
    addPartCounts(j, part, check);
    addWriteReport(j, written);
    return j;
}

} // namespace freeform::cli
