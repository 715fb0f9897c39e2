// freeform info on a STEP or IGES part: counts, closedness, units, bounds (docs/cli.md, docs/cad.md).

#include <map>

#include "command.h"
#include "freeform/brep/part.h"
#include "freeform/cad/cad_file.h"
#include "freeform/document/model.h"
#include "freeform/document/operations.h"

namespace freeform::cli {

void addPartCounts(Json& j, const Part& part, const PartCheck& check)
{
    j["faces"] = part.faces.size();
    j["edges"] = part.edges.size();
    j["vertices"] = part.vertices.size();
    j["shells"] = part.shells.size();
    j["solids"] = part.solids.size();
    j["closed"] = check.closed;
    j["units"] = part.units;
}

/// The part of a document: the object called `name`, or its only part (or trimmed surface, as a
/// part of one face). Error naming the document when there is none, several, or the object is of
/// another kind.
Part documentPart(const std::string& path, const std::optional<std::string>& name, std::string& chosen)
{
    const TypedDocument doc = TypedDocument::read(path);
    const TypedObject& o = freeform::documentPart(doc, name);
    chosen = o.name();
    return *objectPart(o);
}

Json partReport(const Part& part, bool details)
{
    const PartCheck check = checkPart(part);
    Json j;
    addPartCounts(j, part, check);
    const Box<double, 3> box = part.bounds();
    j["bounds"] = {{"min", pointJson(box.min().data(), 3)}, {"max", pointJson(box.max().data(), 3)}};
    j["loose_faces"] = part.looseFaces().size();
    j["open_edges"] = check.openEdges;
    j["non_manifold_edges"] = check.nonManifoldEdges;
    j["max_gap"] = check.maxGap;
    j["gaps_over_tolerance"] = check.gapsOverTolerance;
    std::map<std::string, int> kinds;
    for (const PartFace& f : part.faces) ++kinds[f.surfaceKind];
    j["surfaces"] = Json::object();
    for (const auto& [kind, count] : kinds) j["surfaces"][kind] = count;
    if (details) {
        // The areas are integrals over every face (docs/cad.md, "Area"): seconds on a part of many
        // B-spline faces with many knots, so only on request.
        j["area"] = 0.0;
        double area = 0;
        j["face_reports"] = Json::array();
        for (const PartFace& f : part.faces) {
            const auto& s = f.surface.surface().nurbs;
            Json face;
            face["surface"] = f.surfaceKind;
            face["degree"] = {s.degreeU(), s.degreeV()};
            face["rational"] = s.isRational();
            face["loops"] = f.surface.loops().size();
            face["reversed"] = f.reversed;
            face["area"] = f.surface.area();
            area += face["area"].get<double>();
            j["face_reports"].push_back(face);
        }
        j["area"] = area; // Part::area(), without integrating every face twice
    }
    return j;
}

Json partInfo(const std::string& path, bool details)
{
    if (lowerExtension(path) == ".json") {
        std::string name;
        const Part part = documentPart(path, std::nullopt, name);
        Json j;
        j["object"] = name;
        j.update(partReport(part, details));
        return j;
    }
    return partReport(readCadFile(path), details);
}

} // namespace freeform::cli
