// mergeMeshes (mesh/polygon_mesh.h).

#include "freeform/mesh/polygon_mesh.h"

namespace freeform {

PolygonMesh mergeMeshes(const std::vector<const PolygonMesh*>& meshes)
{
    Eigen::Index total = 0;
    bool normals = true, texcoords = true;
    for (const PolygonMesh* m : meshes) {
        total += m->positions.cols();
        normals = normals && m->normals.cols() == m->positions.cols();
        texcoords = texcoords && m->texcoords.cols() == m->positions.cols();
    }
    PolygonMesh out;
    out.positions.resize(3, total);
    if (normals) out.normals.resize(3, total);
    if (texcoords) out.texcoords.resize(2, total);
    Eigen::Index at = 0;
    for (const PolygonMesh* m : meshes) {
        const Eigen::Index n = m->positions.cols();
        out.positions.middleCols(at, n) = m->positions;
        if (normals) out.normals.middleCols(at, n) = m->normals;
        if (texcoords) out.texcoords.middleCols(at, n) = m->texcoords;
        for (int f = 0; f < m->faceCount(); ++f) {
            std::vector<int> face(m->face(f), m->face(f) + m->faceSize(f));
            for (int& v : face) v += static_cast<int>(at);
            out.addFace(face.begin(), face.end());
        }
        at += n;
    }
    return out;
}

} // namespace freeform
