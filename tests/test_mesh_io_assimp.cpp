// Cross-check of the mesh readers against Assimp, an independent importer: every position Assimp
// finds in a sample file is one of ours and every one of ours is one of Assimp's (Assimp splits
// vertices per corner and parses decimals with its own fast_atof, so the check is on the sets of
// points, to float precision), and both see the same number of faces.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "freeform/io/mesh_io.h"

#ifdef FREEFORM_HAVE_ASSIMP
#include <assimp/Importer.hpp>
#include <assimp/scene.h>

namespace {

/// Largest distance from a point of `a` to the nearest point of `b` (brute force).
double oneSidedDistance(const Eigen::Matrix<double, 3, Eigen::Dynamic>& a, const Eigen::Matrix<double, 3, Eigen::Dynamic>& b)
{
    double worst = 0;
    for (Eigen::Index i = 0; i < a.cols(); ++i) {
        double best = INFINITY;
        for (Eigen::Index j = 0; j < b.cols(); ++j) best = std::min(best, (a.col(i) - b.col(j)).norm());
        worst = std::max(worst, best);
    }
    return worst;
}

} // namespace

TEST_CASE("Assimp finds the same points and faces in the sample meshes", "[mesh_io][assimp]")
{
    const std::string dir = std::string(FREEFORM_SOURCE_DIR) + "/data/meshes/";
    for (const char* name : {"cube.obj", "sphere.obj", "sphere.ply", "sphere.off", "sphere.stl", "sphere.gltf", "sphere.glb"}) {
        INFO(name);
        Assimp::Importer importer;
        const aiScene* scene = importer.ReadFile(dir + name, 0);
        REQUIRE(scene != nullptr);
        std::vector<Eigen::Vector3d> points;
        int faces = 0;
        for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
            const aiMesh* mesh = scene->mMeshes[m];
            for (unsigned v = 0; v < mesh->mNumVertices; ++v)
                points.emplace_back(mesh->mVertices[v].x, mesh->mVertices[v].y, mesh->mVertices[v].z);
            faces += static_cast<int>(mesh->mNumFaces);
        }
        Eigen::Matrix<double, 3, Eigen::Dynamic> theirs(3, static_cast<Eigen::Index>(points.size()));
        for (std::size_t i = 0; i < points.size(); ++i) theirs.col(static_cast<Eigen::Index>(i)) = points[i];

        const freeform::MeshFile file = freeform::MeshFile::read(dir + name);
        const freeform::PolygonMesh ours = file.toPolygonMesh();
        CHECK(faces == ours.faceCount());
        CHECK(oneSidedDistance(theirs, ours.positions) < 1e-6);
        CHECK(oneSidedDistance(ours.positions, theirs) < 1e-6);
    }
}

#else

TEST_CASE("Assimp cross-check", "[mesh_io][assimp]")
{
    WARN("built without Assimp (libassimp-dev): the cross-check of the mesh readers did not run");
}

#endif
