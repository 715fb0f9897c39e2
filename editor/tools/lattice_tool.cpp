#include "tools/lattice_tool.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <limits>

#include "freeform/document/document.h"
#include "freeform/io/geometry_data.h"
#include "freeform/core/error.h"
#include "freeform/volume/deform.h"
#include "interaction/picking.h"
#include "tools/ffd_tools.h"
#include "tools/tool_util.h"

namespace freeform::editor {

using namespace tool_util;

namespace {

/// Error naming the item unless item i is a lattice object (the lattice operations' argument).
void requireLattice(const Scene& scene, int i)
{
    std::string why;
    if (i < 0 || i >= scene.itemCount()) {
        why = "there is no item ";
        why += std::to_string(i);
    } else if (scene.item(i).kind != SceneItem::Kind::DocumentObject || !std::holds_alternative<LatticeData>(scene.object(i).data)) {
        why = scene.item(i).name;
        why += " is not a lattice";
    }
    if (!why.empty()) throw Error(why);
}

} // namespace

bool LatticeTool::onKey(ToolContext& c, KeyAction action)
{
    switch (action) {
    case KeyAction::FitLattice: {
        const int item = c.selection.item;
        if (item < 0 || item >= c.scene.itemCount() || !isFfdTarget(c.scene.item(item))) return false;
        return fitLattice(c, item), true;
    }
    case KeyAction::DirectManipulation:
        direct = !direct;
        status() = direct ? "direct manipulation: drag a point of a deformed mesh" : "";
        return true;
    case KeyAction::ApplyLattice: {
        const int item = c.selection.item;
        if (item < 0 || item >= c.scene.itemCount() || !c.scene.item(item).is(ObjectKind::Lattice)) return false;
        applyLatticeToObjects(c, item); // the panel's "apply exactly to curves and patches"
        return true;
    }
    default: return false;
    }
}

bool LatticeTool::onPointer(ToolContext& c, const PointerEvent& e)
{
    Scene& scene = c.scene;
    if (dragLattice_ != 0) {
        if (e.type == PointerEvent::Type::Release) {
            dragLattice_ = 0;
            scene.endMerge();
            return true;
        }
        if (e.type != PointerEvent::Type::Move) return true;
        const auto hit = rayPlane(e, dragPlanePoint_, dragPlaneNormal_);
        const int li = scene.indexOf(dragLattice_);
        if (!hit || li < 0) return true;
        try {
            DocumentObject next = scene.object(li);
            directTarget_ = *hit;
            const DirectManipulation dm = directManipulation(*dragStart_, directRest_, directTarget_, scene.item(li).settings.ffd.strength);
            next.data = latticeToData(dm.lattice);
            scene.replaceObject(li, next, "direct manipulation");
        } catch (const Error& err) {
            status() = err.what();
        }
        return true;
    }
    if (!direct || e.type != PointerEvent::Type::Press || e.button != 0 || e.mods != 0) return false;
    // A point of a mesh deformed by a lattice: the nearest hit over all links.
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& [latticeId, link] : scene.ffdLinks()) {
        const int m = scene.indexOf(link.meshId), li = scene.indexOf(latticeId);
        if (m < 0 || li < 0 || !link.session || !scene.item(m).geometry.surface || !scene.item(m).settings.visible) continue;
        const PolygonMesh& shown = *scene.item(m).geometry.surface;
        const auto hit = rayMeshHit(e.rayOrigin, e.rayDirection, shown);
        if (!hit || hit->distance >= nearest) continue;
        nearest = hit->distance;
        dragLattice_ = latticeId;
        dragStart_ = scene.lattice(li);
        directRest_ = pointAt(link.session->rest(), link.session->rest().positions, *hit);
        dragPlanePoint_ = pointAt(shown, shown.positions, *hit);
        directTarget_ = dragPlanePoint_;
        dragPlaneNormal_ = scene.camera.back();
    }
    if (dragLattice_ == 0) return false;
    c.selection.selectItem(scene.indexOf(dragLattice_));
    scene.beginMerge();
    return true;
}

void LatticeTool::update(ToolContext& c, Overlay& o)
{
    // A deformation the scene could not compute says why (e.g. a lattice made invalid).
    for (const auto& [id, link] : c.scene.ffdLinks())
        if (!link.error.empty()) status() = link.error;
    if (dragLattice_ != 0) o.addPoint(f3(directTarget_), kCurvePoint);
}

void LatticeTool::reset()
{
    degree[0] = degree[1] = degree[2] = 3;
    margin = 0.05;
    direct = false;
    std::strcpy(exportPath, "deformed.obj");
    dragLattice_ = 0;
}

bool LatticeTool::fitLattice(ToolContext& c, int meshItem)
{
    if (meshItem < 0 || meshItem >= c.scene.itemCount() || !isFfdTarget(c.scene.item(meshItem))) {
        status() = "select an imported mesh or a part to fit a lattice to";
        return false;
    }
    c.scene.updateGeometry();
    const SceneItem& mesh = c.scene.item(meshItem);
    if (!mesh.geometry.surface) {
        status() = "the mesh has no geometry";
        return false;
    }
    // Fit to the rest mesh (a mesh already deformed by a lattice is fitted as it was read).
    const PolygonMesh* rest = &*mesh.geometry.surface;
    for (const auto& [id, link] : c.scene.ffdLinks())
        if (link.meshId == mesh.id && link.session && link.meshKey == mesh.key) rest = &link.session->rest();
    try {
        std::array<int, 3> degrees{};
        for (int a = 0; a < 3; ++a) degrees[static_cast<std::size_t>(a)] = std::clamp(degree[a], 1, 20);
        const Lattice lattice = Lattice::fit(rest->positions, degrees, margin);
        ObjectSettings settings;
        settings.ffd.mesh = mesh.name; // the document's form; the scene links by the mesh's id
        const std::string meshName = mesh.name;
        c.scene.beginMerge();
        const int i = c.scene.addObject({meshName + "_lattice", latticeToData(lattice), ""}, "fit lattice");
        c.scene.setSettings(i, settings, "fit lattice");
        c.scene.endMerge();
        c.selection.selectItem(i);
        fitted_ = i;
        status().clear();
        return true;
    } catch (const Error& e) {
        c.scene.endMerge();
        status() = e.what();
        return false;
    }
}

bool LatticeTool::resetLattice(ToolContext& c, int latticeItem)
{
    try {
        requireLattice(c.scene, latticeItem);
        DocumentObject o = c.scene.object(latticeItem);
        std::get<LatticeData>(o.data).points = c.scene.lattice(latticeItem).restPoints();
        c.scene.replaceObject(latticeItem, o, "reset lattice");
        return true;
    } catch (const std::exception& e) {
        status() = e.what();
        return false;
    }
}

bool LatticeTool::exportDeformed(ToolContext& c, int latticeItem, const std::string& path)
{
    try {
        requireLattice(c.scene, latticeItem);
        const SceneItem& item = c.scene.item(latticeItem);
        const int m = c.scene.indexOf(item.deforms);
        if (m < 0 || !isFfdTarget(c.scene.item(m))) throw Error("the lattice is bound to no imported mesh or part");
        if (c.scene.item(m).kind == SceneItem::Kind::DocumentObject) {
            // A part: composed exactly, written as STEP or IGES (faces over degree 25 approximated,
            // with the certified error reported: docs/cad.md, "In the editor").
            const Scene::PartExport e = c.scene.exportPart(m, path, &c.scene.lattice(latticeItem), item.settings.ffd.strength);
            status() = "wrote " + path + ": " + std::to_string(e.deform.exactFaces) + " of " + std::to_string(e.faces) + " faces exact" +
                       Scene::approximationText(e.deform);
            status() += e.valid ? ", a valid shape" : ", Open CASCADE's check finds the shape invalid";
            return true;
        }
        // The lattice in the file's own axes (a Y-up file is written back Y-up: docs/format.md, meshes[].up).
        const Lattice lattice = latticeToFile(c.scene.lattice(latticeItem), c.scene.item(m).up);
        const DeformReport report = exportDeformedMesh(meshFilePath(c.scene, m), lattice, item.settings.ffd.strength, path);
        status() = "wrote " + path + " (" + std::to_string(report.vertices) + " positions)";
        return true;
    } catch (const std::exception& e) {
        status() = e.what();
        return false;
    }
}

bool LatticeTool::applyLatticeToObjects(ToolContext& c, int latticeItem)
{
    try {
        requireLattice(c.scene, latticeItem);
        const Lattice lattice = c.scene.lattice(latticeItem); // a copy: the scene changes below
        // The document layer's one rule for every object type (docs/ffd.md, "Documents"), the same
        // deformDocument `freeform ffd DOC` runs, with the same options: an object whose control
        // points leave the box is composed all the same (the lattice polynomial continued) and
        // counted as "outside the box" in the status line, as the command reports "inside": false.
        // A cage in a mesh file is written inline (the file stays as it is), as when one of its
        // vertices is dragged.
        DeformDocumentOptions options;
        options.strength = c.scene.item(latticeItem).settings.ffd.strength;
        // On a copy of the scene's typed document (its geometry copied, not built again): the scene
        // takes the results through replaceObject, one undo step. Objects the document layer
        // refuses are not in it, so they stay as they are.
        TypedDocument doc = c.scene.model();
        const DeformDocumentReport report = deformDocument(doc, lattice, options);
        c.scene.beginMerge();
        for (const DeformedObject& d : report.objects) {
            const int k = c.scene.itemOfObject(d.id);
            if (k < 0) continue;
            DocumentObject next = c.scene.object(k);
            next.data = doc.object(d.id).data();
            c.scene.replaceObject(k, next, "apply lattice");
        }
        // A part the lattice previews (its link): the exact image is in the document now, so the
        // lattice goes back to rest in the same step, else the preview would deform it twice.
        const int target = c.scene.indexOf(c.scene.item(latticeItem).deforms);
        const bool baked = target >= 0 && c.scene.item(target).kind == SceneItem::Kind::DocumentObject && !report.objects.empty();
        if (baked) {
            DocumentObject rest = c.scene.object(latticeItem);
            std::get<LatticeData>(rest.data).points = lattice.restPoints();
            c.scene.replaceObject(latticeItem, rest, "apply lattice");
        }
        c.scene.endMerge();
        std::string why;
        int skipped = 0;
        for (const SkippedObject& s : report.skipped) {
            if (kindNamed(s.type) == ObjectKind::Lattice) continue;
            ++skipped;
            why = s.name + ": " + s.reason;
        }
        for (int i = 0; i < c.scene.itemCount(); ++i)
            if (!c.scene.item(i).invalid.empty()) {
                ++skipped;
                why = c.scene.item(i).name + ": " + c.scene.item(i).invalid;
            }
        const auto outside = std::count_if(report.objects.begin(), report.objects.end(),
                                           [](const DeformedObject& d) { return !d.inside; });
        status() = "deformed " + std::to_string(report.objects.size()) + " object(s) exactly";
        if (outside)
            status() += ", " + std::to_string(outside) +
                        " of them outside the box (the lattice polynomial continued there, docs/ffd.md)";
        if (skipped) status() += ", left " + std::to_string(skipped) + " (" + why + ")";
        if (baked) status() += "; the lattice is back at rest around " + c.scene.item(target).name;
        return !report.objects.empty();
    } catch (const std::exception& e) {
        c.scene.endMerge();
        status() = e.what();
        return false;
    }
}

bool LatticeTool::certifyLattice(ToolContext& c, int latticeItem)
{
    try {
        requireLattice(c.scene, latticeItem);
        const Certificate cert = certify(c.scene.lattice(latticeItem), c.scene.item(latticeItem).settings.ffd.strength);
        c.scene.setCertificate(latticeItem, cert);
        status() = "certificate: " + toString(cert.verdict);
        return true;
    } catch (const std::exception& e) { // also a wrong item (not a lattice, out of range)
        status() = e.what();
        return false;
    }
}

} // namespace freeform::editor
