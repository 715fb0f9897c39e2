// The derived items of a Scene (scene/derived.h): the lattice -> mesh links and their evaluation,
// the one path by which a deformed mesh is written.

#include "scene/derived.h"

#include <chrono>
#include <map>
#include <optional>

#include "freeform/io/geometry_data.h"
#include "freeform/core/error.h"
#include "scene/scene.h"

namespace freeform::editor {

void Scene::resolveLink(SceneItem& item) const
{
    const int m = item.settings.ffd.mesh.empty() ? -1 : indexOf(item.settings.ffd.mesh);
    item.deforms = m >= 0 ? items_[static_cast<std::size_t>(m)].id : 0;
}

const FfdLink* Scene::ffdLink(int i) const
{
    const auto it = ffdLinks_.find(item(i).id);
    return it == ffdLinks_.end() ? nullptr : &it->second;
}

void Scene::setCertificate(int i, const Certificate& certificate)
{
    if (const auto it = ffdLinks_.find(item(i).id); it != ffdLinks_.end()) it->second.certificate = certificate;
}

void Scene::updateDerived()
{
    // Puts the rest mesh back into the mesh of a link that goes away.
    auto restoreRest = [&](const FfdLink& link) {
        const int m = indexOf(link.meshId);
        if (m < 0 || !link.session) return;
        SceneItem& it = items_[static_cast<std::size_t>(m)];
        if (it.key != link.meshKey || !it.geometry.surface ||
            it.geometry.surface->positions.cols() != link.session->rest().positions.cols())
            return;
        it.geometry.surface->positions = link.session->rest().positions;
        it.geometry.surface->normals = link.session->rest().normals;
        setScalars(m, {});
    };
    // Lattices that deform a mesh, by id. A name the document gave before its mesh was there
    // (a mesh imported later under that name) is resolved now.
    std::map<long, int> lattices;
    for (std::size_t i = 0; i < items_.size(); ++i) {
        SceneItem& it = items_[i];
        if (!it.is(ObjectKind::Lattice)) continue;
        if (it.deforms == 0 && !it.settings.ffd.mesh.empty()) resolveLink(it);
        if (it.deforms != 0) lattices[it.id] = static_cast<int>(i);
    }
    for (auto it = ffdLinks_.begin(); it != ffdLinks_.end();) {
        const auto found = lattices.find(it->first);
        if (found == lattices.end() || items_[static_cast<std::size_t>(found->second)].deforms != it->second.meshId) {
            restoreRest(it->second);
            it = ffdLinks_.erase(it);
        } else {
            ++it;
        }
    }
    for (const auto& [id, li] : lattices) {
        const SceneItem& latticeItem = items_[static_cast<std::size_t>(li)];
        const int m = indexOf(latticeItem.deforms);
        if (m < 0 || !isFfdTarget(items_[static_cast<std::size_t>(m)])) continue;
        SceneItem& mesh = items_[static_cast<std::size_t>(m)];
        if (!mesh.geometry.surface) continue;
        FfdLink& link = ffdLinks_[id];
        const auto& data = std::get<LatticeData>(document_.objects[static_cast<std::size_t>(li)].data);
        const double strength = latticeItem.settings.ffd.strength;
        try {
            const Lattice& lattice = this->lattice(li); // the typed document's (Error: the lattice is invalid)
            const bool rebind = !link.session || link.meshId != mesh.id || link.meshKey != mesh.key ||
                                link.meshTopology != mesh.topology || !link.session->matches(lattice);
            if (rebind) {
                // The rest mesh: the item's geometry as read (or as tessellated), unless this link deformed it.
                PolygonMesh rest = *mesh.geometry.surface;
                if (link.session && link.meshKey == mesh.key && link.meshTopology == mesh.topology && link.appliedRevision == mesh.revision)
                    rest = link.session->rest();
                link = FfdLink{};
                link.meshId = mesh.id;
                link.meshKey = mesh.key;
                link.meshTopology = mesh.topology;
                link.session = std::make_shared<FfdSession>(lattice, std::move(rest));
            }
            // While a drag goes on (the history merges its changes), a frame may be the linear
            // update (FfdSession::deform, live); the first update after it is the full evaluation,
            // also when nothing else changed: what the drag leaves is exact. With background work
            // on (the editor's window), that release evaluation runs on a worker thread: the
            // release frame keeps the drag's last linear frame, and a later update swaps the exact
            // result in once it is done (docs/architecture.md, "A lattice drag").
            const bool live = history_.merging();
            const bool inputs = rebind || link.appliedRevision != mesh.revision || link.appliedPoints != data.points ||
                                link.appliedStrength != strength;
            if (link.pending && !inputs && link.session->backgroundPending()) {
                const auto t0 = std::chrono::steady_clock::now();
                std::vector<float> scalars = std::move(mesh.scalars);
                std::optional<DeformReport> report;
                try {
                    report = link.session->takeBackground(*mesh.geometry.surface, scalars, mesh.geometry.bounds, waitDeformation_,
                                                          &mesh.geometry.drawn);
                } catch (...) {
                    mesh.scalars = std::move(scalars);
                    link.pending = false;
                    throw;
                }
                if (!report) { // still running: the linear frame stays
                    mesh.scalars = std::move(scalars);
                    continue;
                }
                link.report = std::move(*report);
                link.approximate = false;
                link.pending = false;
                setScalars(m, std::move(scalars)); // a new revision: the drawer uploads the exact mesh
                link.appliedRevision = mesh.revision;
                mesh.geometry.drawn.revision = mesh.revision;
                link.deformMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
                link.certificate.reset();
                link.error.clear();
                continue;
            }
            // (Inputs changed meanwhile: deform() waits for the job and starts from its result. A
            // copy of the scene that shares the session may have taken the result: evaluate here.)
            link.pending = false;
            const bool changed = inputs || (link.approximate && !live);
            if (!changed) continue;
            if (!inputs && backgroundOn_ && !waitDeformation_) {
                // The release: the exact evaluation in the background; nothing changes this frame.
                const auto t0 = std::chrono::steady_clock::now();
                link.session->deformInBackground(lattice, strength);
                link.pending = true;
                link.deformMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
                continue;
            }
            const auto t0 = std::chrono::steady_clock::now();
            // det J straight into the colour scalars, in the last frame's memory (no fresh pages).
            std::vector<float> scalars = std::move(mesh.scalars);
            // The bounds come from the same pass that writes the double positions.
            // The float copies the GPU takes, from the same pass (the drawer converts nothing).
            link.report = link.session->deform(lattice, strength, *mesh.geometry.surface, &scalars, &mesh.geometry.bounds, live,
                                               &mesh.geometry.drawn);
            link.approximate = link.session->approximate();
            link.deformMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
            setScalars(m, std::move(scalars)); // also a new revision: the drawer uploads the vertices
            link.appliedRevision = mesh.revision;
            const bool normals = mesh.geometry.surface->normals.cols() == mesh.geometry.surface->positions.cols();
            mesh.geometry.drawn.revision = normals ? mesh.revision : -1; // (deform writes them only with normals)
            link.appliedPoints = data.points;
            link.appliedStrength = strength;
            link.certificate.reset();
            link.error.clear();
        } catch (const Error& e) {
            link.error = e.what();
        }
    }
}

} // namespace freeform::editor

namespace freeform::editor {

void Scene::finishDeformation()
{
    struct Waiting {
        bool& flag;
        ~Waiting() { flag = false; }
    } waiting{waitDeformation_ = true};
    updateDerived();
}

} // namespace freeform::editor
