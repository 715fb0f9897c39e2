// `freeform tessellate` for rational_bezier_surface and nurbs_surface objects: through the
// document layer (tessellateObject, the certified rational bound of tessellate_rational.h).

#include "command.h"
#include "freeform/document/operations.h"

namespace freeform::cli {

bool isRationalSurface(const TypedObject& object)
{
    return object.type() == "rational_bezier_surface" || object.type() == "nurbs_surface";
}

RationalMeshes tessellateRationalSurfaces(const TypedDocument& doc, const std::vector<const TypedObject*>& objects,
                                          const TessellationOptions& options)
{
    RationalMeshes out;
    ObjectTessellation settings;
    settings.tolerance = options.tolerance;
    settings.segments = options.segmentsU;
    settings.flip = options.flipNormals;
    for (const TypedObject* o : objects) {
        TessellationReport report;
        const auto mesh = tessellateObject(*o, settings, &report);
        if (!mesh) throw Error(doc.what(*o) + ": type " + o->type() + " is not a surface");
        out.patches += static_cast<int>(report.segments.size());
        out.errorBound = std::max(out.errorBound, report.errorBound);
        out.meshes.push_back(*mesh);
    }
    return out;
}

PolygonMesh mergeMeshes(const std::vector<PolygonMesh>& meshes)
{
    PolygonMesh out;
    Eigen::Index total = 0;
    for (const PolygonMesh& m : meshes) total += m.positions.cols();
    out.positions.resize(3, total);
    out.normals.resize(3, total);
    out.texcoords.resize(2, total);
    Eigen::Index at = 0;
    for (const PolygonMesh& m : meshes) {
        const Eigen::Index n = m.positions.cols();
        out.positions.middleCols(at, n) = m.positions;
        out.normals.middleCols(at, n) = m.normals;
        out.texcoords.middleCols(at, n) = m.texcoords;
        for (int f = 0; f < m.faceCount(); ++f) {
            std::vector<int> face(m.face(f), m.face(f) + m.faceSize(f));
            for (int& v : face) v += static_cast<int>(at);
            out.addFace(face.begin(), face.end());
        }
        at += n;
    }
    return out;
}

} // namespace freeform::cli
