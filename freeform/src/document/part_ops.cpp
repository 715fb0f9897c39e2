// eval, tessellate and the control net of trimmed_surface and part objects (document/operations.h;
// docs/format.md, "Trimmed surfaces and parts"). A part's faces are meshed together by
// tessellatePart (brep/part_mesh.h: each edge discretised once, so a closed solid gives a closed
// mesh); a trimmed surface alone is a part of one face without edges.

#include "part_ops.h"

#include <map>

#include "freeform/brep/part_mesh.h"
#include "freeform/core/error.h"
#include "freeform/core/format.h"
#include "evaluation.h"

namespace freeform::detail {
namespace {

/// The mesh with each face's triangles on vertices of their own and area-weighted normals of that
/// face's triangles only.
PolygonMesh splitByFace(const PolygonMesh& mesh, const std::vector<int>& triangleFace)
{
    PolygonMesh out;
    std::map<std::pair<int, int>, int> index; // (face, vertex) -> new vertex
    std::vector<Eigen::Vector3d> positions, normals;
    std::vector<int> triangles;
    for (int t = 0; t < mesh.faceCount(); ++t) {
        const int face = triangleFace[static_cast<std::size_t>(t)];
        int corner[3];
        for (int k = 0; k < 3; ++k) {
            const int v = mesh.faceVertices[static_cast<std::size_t>(3 * t + k)];
            const auto [it, added] = index.try_emplace({face, v}, static_cast<int>(positions.size()));
            if (added) {
                positions.push_back(mesh.positions.col(v));
                normals.push_back(Eigen::Vector3d::Zero());
            }
            corner[k] = it->second;
        }
        const Eigen::Vector3d a = positions[static_cast<std::size_t>(corner[0])];
        const Eigen::Vector3d n = (positions[static_cast<std::size_t>(corner[1])] - a).cross(positions[static_cast<std::size_t>(corner[2])] - a);
        for (int k = 0; k < 3; ++k) {
            normals[static_cast<std::size_t>(corner[k])] += n;
            triangles.push_back(corner[k]);
        }
    }
    out.positions.resize(3, static_cast<Eigen::Index>(positions.size()));
    out.normals.resize(3, static_cast<Eigen::Index>(positions.size()));
    for (std::size_t i = 0; i < positions.size(); ++i) {
        out.positions.col(static_cast<Eigen::Index>(i)) = positions[i];
        const double length = normals[i].norm();
        out.normals.col(static_cast<Eigen::Index>(i)) = length > 0 ? Eigen::Vector3d(normals[i] / length) : Eigen::Vector3d::Zero();
    }
    for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) out.addFace({triangles[t], triangles[t + 1], triangles[t + 2]});
    return out;
}

/// A trimmed surface at (u, v) in the file's parameters: the point, the unit normal (negated for a
/// reversed face), and with order 1 the first derivatives in those parameters (the NURBS's at
/// (mapU(u), mapV(v)) times the maps' slopes).
Evaluation evaluateFace(const std::string& what, const TrimmedSurface& face, bool reversed, double u, double v, int order)
{
    if (order > 1)
        throw Error(what + ": a trimmed surface gives first derivatives only (--derivatives 0 or 1), not " + std::to_string(order));
    const Box<double, 2>& box = face.domain();
    inDomain(what, "u", u, box.min().x(), box.max().x(), "face");
    inDomain(what, "v", v, box.min().y(), box.max().y(), "face");
    const MappedSurface& s = face.surface();
    const auto jet = s.nurbs.jet(s.mapU(u), s.mapV(v), order);
    Evaluation e;
    e.point = jet.col(0);
    const Eigen::Vector3d n = face.normal(u, v);
    e.normal = reversed ? Eigen::Vector3d(-n) : n;
    if (order == 1) {
        e.keys = {"u", "v"};
        e.derivatives = {jet.col(1) * s.mapU.derivative(u), jet.col(2) * s.mapV.derivative(v)};
    }
    e.trim = face.classify(Eigen::Vector2d(u, v));
    return e;
}

} // namespace

std::optional<Evaluation> evaluatePartObject(const std::string& what, const TypedObject& object,
                                             const std::vector<double>& at, int order)
{
    if (const auto* t = std::get_if<TrimmedSurface>(&object.geometry())) {
        expectCount(what, at, 2, "U,V");
        return evaluateFace(what, *t, false, at[0], at[1], order);
    }
    if (const auto* p = std::get_if<Part>(&object.geometry())) {
        expectCount(what, at, 3, "FACE,U,V");
        const auto faces = static_cast<double>(p->faces.size());
        if (at[0] != std::floor(at[0]) || at[0] < 0 || at[0] >= faces)
            throw Error(what + ": FACE must be an integer in 0.." + std::to_string(p->faces.size() - 1) + " (FACE,U,V)");
        const int f = static_cast<int>(at[0]);
        const PartFace& face = p->faces[static_cast<std::size_t>(f)];
        Evaluation e = evaluateFace(what + ": face " + std::to_string(f), face.surface, face.reversed, at[1], at[2], order);
        e.face = f;
        return e;
    }
    return std::nullopt;
}

std::optional<std::vector<double>> partDomain(const TypedObject& object)
{
    if (const auto* t = std::get_if<TrimmedSurface>(&object.geometry())) {
        const Box<double, 2>& b = t->domain();
        return std::vector<double>{b.min().x(), b.max().x(), b.min().y(), b.max().y()};
    }
    if (const auto* p = std::get_if<Part>(&object.geometry())) return std::vector<double>{static_cast<double>(p->faces.size())};
    return std::nullopt;
}

std::optional<PolygonMesh> tessellatePartObject(const TypedObject& object, const ObjectTessellation& options,
                                                TessellationReport* report)
{
    const Part* part = std::get_if<Part>(&object.geometry());
    Part single;
    if (const auto* t = std::get_if<TrimmedSurface>(&object.geometry())) {
        single = singleFacePart(*t);
        part = &single;
    }
    if (!part) return std::nullopt;
    PartMeshOptions o;
    // Without a tolerance (the editor's uniform mode): a fixed fraction of the part's size, finer
    // as the segment count grows (8 segments: 1/400 of the box diagonal).
    const double diagonal = part->bounds().diagonal().norm();
    o.tolerance = options.tolerance > 0 ? options.tolerance : diagonal / (50.0 * std::max(1, options.segments));
    PartMesh mesh = tessellatePart(*part, o);
    if (options.splitFaces) mesh.mesh = splitByFace(mesh.mesh, mesh.triangleFace);
    if (options.flip) {
        for (int f = 0; f < mesh.mesh.faceCount(); ++f)
            std::swap(mesh.mesh.faceVertices[3 * f + 1], mesh.mesh.faceVertices[3 * f + 2]);
        mesh.mesh.normals = -mesh.mesh.normals;
    }
    if (report) {
        *report = {};
        report->errorBound = mesh.report.errorBound;
        report->patchBound = mesh.report.faceBound;
        report->worstRatio = o.tolerance > 0 ? mesh.report.errorBound / o.tolerance : 0;
        report->triangleFace = mesh.triangleFace; // splitByFace keeps the triangles' order
    }
    return std::move(mesh.mesh);
}

} // namespace freeform::detail

namespace freeform {

std::optional<Part> objectPart(const TypedObject& object)
{
    if (const auto* p = std::get_if<Part>(&object.geometry())) return *p;
    if (const auto* t = std::get_if<TrimmedSurface>(&object.geometry())) return singleFacePart(*t);
    return std::nullopt;
}

const TypedObject& documentPart(const TypedDocument& doc, const std::optional<std::string>& name)
{
    auto isPart = [](const TypedObject& o) { return o.info().supports(KindOperation::Part); };
    if (name) {
        const TypedObject& o = doc.object(*name);
        if (!isPart(o)) throw Error(doc.what(o) + ": is a " + o.type() + ", not a part or trimmed_surface");
        return o;
    }
    std::vector<const TypedObject*> found;
    for (const TypedObject& o : doc.objects())
        if (isPart(o)) found.push_back(&o);
    if (found.empty()) throw Error(doc.source + ": has no part or trimmed_surface object");
    if (found.size() > 1) {
        std::string list;
        for (const TypedObject* o : found) list += (list.empty() ? "" : ", ") + o->name();
        throw Error(doc.source + ": has several parts (" + list + "): name the one to take");
    }
    return *found.front();
}

} // namespace freeform
