// freeform info on a STEP or IGES part: counts, closedness, units, bounds (docs/cli.md, docs/cad.md).

#include <map>

#include "command.h"
#include "freeform/brep/part.h"
#include "freeform/cad/cad_file.h"
#include "freeform/document/model.h"

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
    auto partOf = [&](const TypedObject& o) -> std::optional<Part> {
        if (const auto* p = std::get_if<Part>(&o.geometry())) return *p;
        if (const auto* t = std::get_if<TrimmedSurface>(&o.geometry())) return singleFacePart(*t);
        return std::nullopt;
    };
    if (name) {
        const TypedObject& o = doc.object(*name);
        std::optional<Part> p = partOf(o);
        if (!p) throw Error(doc.what(o) + ": is a " + o.type() + ", not a part or trimmed_surface");
        chosen = o.name();
        return std::move(*p);
    }
    std::vector<const TypedObject*> found;
    for (const TypedObject& o : doc.objects())
        if (partOf(o)) found.push_back(&o);
    if (found.empty()) throw Error(path + ": has no part or trimmed_surface object");
    if (found.size() > 1) {
        std::string list;
        for (const TypedObject* o : found) list += (list.empty() ? "" : ", ") + o->name();
        throw Error(path + ": has several parts (" + list + "); choose one with --object");
    }
    chosen = found.front()->name();
    return std::move(*partOf(*found.front()));
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
