// Cross-check of the mesh readers against Assimp, an independent importer: every position Assimp
// finds in a sample file is one of ours and every one of ours is one of Assimp's (Assimp splits
// vertices per corner and parses decimals with its own fast_atof, so the check is on the sets of
// points, to float precision), and both see the same number of faces.

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <tuple>
#include <cmath>
#include <string>
#include <vector>

#include "freeform/io/mesh_io.h"

#ifdef FREEFORM_HAVE_ASSIMP
#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#endif

namespace test_mesh_io_assimp {

#ifdef FREEFORM_HAVE_ASSIMP

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

namespace {

std::string dir() { return std::string(FREEFORM_SOURCE_DIR) + "/data/meshes/"; }

/// The faces of an Assimp scene as lists of corner positions (all meshes, in order).
std::vector<std::vector<Eigen::Vector3d>> assimpFaces(const std::string& path)
{
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(path, 0);
    INFO(path << ": " << importer.GetErrorString());
    REQUIRE(scene != nullptr);
    std::vector<std::vector<Eigen::Vector3d>> faces;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh* mesh = scene->mMeshes[m];
        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            std::vector<Eigen::Vector3d> corners;
            for (unsigned k = 0; k < mesh->mFaces[f].mNumIndices; ++k) {
                const aiVector3D& v = mesh->mVertices[mesh->mFaces[f].mIndices[k]];
                corners.emplace_back(v.x, v.y, v.z);
            }
            faces.push_back(std::move(corners));
        }
    }
    return faces;
}

/// Our faces as corner positions; fanned into triangles when `triangles` (STL, glTF writers).
std::vector<std::vector<Eigen::Vector3d>> ourFaces(const freeform::PolygonMesh& mesh, bool triangles)
{
    std::vector<std::vector<Eigen::Vector3d>> faces;
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const int* c = mesh.face(f);
        if (!triangles) {
            std::vector<Eigen::Vector3d> corners;
            for (int k = 0; k < mesh.faceSize(f); ++k) corners.push_back(mesh.positions.col(c[k]));
            faces.push_back(std::move(corners));
        } else {
            for (int k = 1; k + 1 < mesh.faceSize(f); ++k)
                faces.push_back({mesh.positions.col(c[0]), mesh.positions.col(c[k]), mesh.positions.col(c[k + 1])});
        }
    }
    return faces;
}

} // namespace

TEST_CASE("Every writer's output reads back through Assimp, face for face and corner for corner", "[mesh_io][assimp]")
{
    const std::string dir = std::string(FREEFORM_SOURCE_DIR) + "/data/meshes/";
    const std::string out = std::string(FREEFORM_TEST_TMP) + "/assimp_back_";
    // A moved mesh (so the values are not the sample's own), through the conversion writers and
    // through the format-preserving writers of each sample.
    freeform::PolygonMesh mesh = freeform::readPolygonMesh(dir + "cube.obj");
    mesh.positions = (mesh.positions * 1.75).array() + 0.125;
    for (const char* ext : {"obj", "ply", "off", "stl", "gltf", "glb"}) {
        INFO("writePolygonMesh ." << ext);
        const std::string path = out + "cube." + ext;
        freeform::writePolygonMesh(mesh, path);
        const bool triangles = std::string(ext) == "stl" || std::string(ext) == "gltf" || std::string(ext) == "glb";
        const auto theirs = assimpFaces(path);
        const auto ours = ourFaces(mesh, triangles);
        REQUIRE(theirs.size() == ours.size());
        for (std::size_t f = 0; f < ours.size(); ++f) {
            REQUIRE(theirs[f].size() == ours[f].size());
            for (std::size_t k = 0; k < ours[f].size(); ++k) CHECK((theirs[f][k] - ours[f][k]).norm() < 1e-6);
        }
    }
    for (const char* name : {"sphere.obj", "sphere.ply", "sphere.off", "sphere.stl", "sphere.gltf", "sphere.glb"}) {
        INFO("MeshFile::write " << name);
        freeform::MeshFile file = freeform::MeshFile::read(dir + name);
        file.positions().row(2).array() += 0.5;
        const std::string path = out + name;
        file.write(path);
        const std::string ext = freeform::MeshFile::read(path).format();
        const auto theirs = assimpFaces(path);
        const auto ours = ourFaces(file.toPolygonMesh(), ext == "stl" || ext == "gltf" || ext == "glb");
        REQUIRE(theirs.size() == ours.size());
        for (std::size_t f = 0; f < ours.size(); ++f) {
            REQUIRE(theirs[f].size() == ours[f].size());
            for (std::size_t k = 0; k < ours[f].size(); ++k) CHECK((theirs[f][k] - ours[f][k]).norm() < 1e-5);
        }
    }
}

TEST_CASE("The text writers (ASCII PLY with colours, ASCII STL) read back through Assimp value for value", "[mesh_io][assimp]")
{
    // The samples are binary PLY and STL; MeshFile::write keeps a file's encoding, so the ASCII
    // writers are checked on hand-written files: positions moved, colours kept, all compared with
    // what Assimp reads (hand values, not our reader's).
    const std::string out = std::string(FREEFORM_TEST_TMP) + "/assimp_text_";
    {
        std::ofstream(out + "in.ply") << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                                         "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
                                         "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
                                         "0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n0 1 0 255 128 0\n3 0 1 2\n3 0 2 3\n";
        freeform::MeshFile file = freeform::MeshFile::read(out + "in.ply");
        file.positions().row(2).array() += 0.25;
        file.write(out + "out.ply");
        {
            std::ifstream written(out + "out.ply");
            std::string magic, format, encoding;
            std::getline(written, magic);
            written >> format >> encoding;
            REQUIRE(encoding == "ascii"); // still the ASCII writer
        }
        Assimp::Importer importer;
        const aiScene* scene = importer.ReadFile(out + "out.ply", 0);
        INFO(importer.GetErrorString());
        REQUIRE(scene != nullptr);
        REQUIRE(scene->mNumMeshes == 1);
        const aiMesh* m = scene->mMeshes[0];
        REQUIRE(m->mNumFaces == 2);
        REQUIRE(m->HasVertexColors(0));
        const double corners[2][3][3] = {{{0, 0, 0.25}, {1, 0, 0.25}, {1, 1, 0.25}}, {{0, 0, 0.25}, {1, 1, 0.25}, {0, 1, 0.25}}};
        const double colours[2][3][3] = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{1, 0, 0}, {0, 0, 1}, {1, 128.0 / 255, 0}}};
        for (unsigned f = 0; f < 2; ++f) {
            REQUIRE(m->mFaces[f].mNumIndices == 3);
            for (unsigned k = 0; k < 3; ++k) {
                const unsigned v = m->mFaces[f].mIndices[k];
                CHECK(m->mVertices[v].x == Approx(corners[f][k][0]).margin(1e-6));
                CHECK(m->mVertices[v].y == Approx(corners[f][k][1]).margin(1e-6));
                CHECK(m->mVertices[v].z == Approx(corners[f][k][2]).margin(1e-6));
                CHECK(m->mColors[0][v].r == Approx(colours[f][k][0]).margin(1e-6));
                CHECK(m->mColors[0][v].g == Approx(colours[f][k][1]).margin(1e-6));
                CHECK(m->mColors[0][v].b == Approx(colours[f][k][2]).margin(1e-6));
            }
        }
    }
    {
        std::ofstream(out + "in.stl") << "solid two\n"
                                         "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 2 0 0\nvertex 2 3 0\nendloop\nendfacet\n"
                                         "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 2 3 0\nvertex 0 3 0\nendloop\nendfacet\n"
                                         "endsolid two\n";
        freeform::MeshFile file = freeform::MeshFile::read(out + "in.stl");
        file.positions().row(0).array() -= 0.5;
        file.write(out + "out.stl");
        std::ifstream written(out + "out.stl");
        std::string first;
        written >> first;
        REQUIRE(first == "solid"); // still the ASCII writer
        const auto theirs = assimpFaces(out + "out.stl");
        const std::vector<std::vector<Eigen::Vector3d>> expected = {
            {{-0.5, 0, 0}, {1.5, 0, 0}, {1.5, 3, 0}}, {{-0.5, 0, 0}, {1.5, 3, 0}, {-0.5, 3, 0}}};
        REQUIRE(theirs.size() == expected.size());
        for (std::size_t f = 0; f < expected.size(); ++f) {
            REQUIRE(theirs[f].size() == 3);
            for (std::size_t k = 0; k < 3; ++k) CHECK((theirs[f][k] - expected[f][k]).norm() < 1e-6);
        }
    }
}

TEST_CASE("Other formats come in through Assimp, said plainly", "[mesh_io][assimp]")
{
    const std::string models = "/usr/share/assimp/models/";
    if (!std::filesystem::exists(models + "FBX/box.fbx")) {
        WARN("assimp-testmodels is not installed: the import of other formats was not tried");
        return;
    }
    // A box in FBX: 6 sides, 12 triangles (or 6 quads), 8 distinct corner positions.
    const freeform::MeshFile box = freeform::MeshFile::read(models + "FBX/box.fbx");
    CHECK(box.reader() == "assimp (not lossless)");
    CHECK(freeform::meshReader(models + "FBX/box.fbx") == "assimp (not lossless)");
    CHECK(freeform::meshReader(dir() + "sphere.ply") == "freeform (lossless)");
    const freeform::PolygonMesh mesh = box.toPolygonMesh();
    std::set<std::tuple<double, double, double>> distinct;
    for (Eigen::Index i = 0; i < mesh.positions.cols(); ++i)
        distinct.emplace(mesh.positions(0, i), mesh.positions(1, i), mesh.positions(2, i));
    CHECK(distinct.size() == 8);
    int corners = 0;
    for (int f = 0; f < mesh.faceCount(); ++f) corners += mesh.faceSize(f);
    CHECK((corners == 36 || corners == 24));

    // Converted into a lossless format: every position exactly (PLY stores doubles).
    const std::string out = std::string(FREEFORM_TEST_TMP) + "/assimp_import_";
    box.write(out + "box.ply");
    CHECK(freeform::MeshFile::read(out + "box.ply").positions() == box.positions());

    // Moved and written back through Assimp's exporter where the format has one (Collada).
    for (const char* name : {"Collada/duck.dae", "3DS/fels.3ds", "X3D/ComputerKeyboard.x3d"}) {
        INFO(name);
        if (!std::filesystem::exists(models + name)) continue;
        freeform::MeshFile file = freeform::MeshFile::read(models + name);
        CHECK(file.reader() == "assimp (not lossless)");
        REQUIRE(file.positions().cols() > 0);
        CHECK(file.toPolygonMesh().faceCount() > 0);
    }
    // From memory (MeshFile::readBytes: Assimp's ReadFileFromMemory, the extension as its hint),
    // under a name in a folder that does not exist: the same mesh as from the disk.
    for (const char* name : {"FBX/box.fbx", "Collada/duck.dae"}) {
        INFO(name);
        const freeform::MeshFile disk = freeform::MeshFile::read(models + name);
        std::ifstream in(models + name, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        CHECK(disk.bytes() == bytes);
        const std::string nowhere = out + "nowhere/" + std::filesystem::path(name).filename().string();
        const freeform::MeshFile memory = freeform::MeshFile::readBytes(nowhere, disk.bytes());
        CHECK(memory.reader() == "assimp (not lossless)");
        CHECK(memory.positions() == disk.positions());
        CHECK(memory.normals() == disk.normals());
        const freeform::PolygonMesh a = disk.toPolygonMesh(), b = memory.toPolygonMesh();
        CHECK(a.faceStart == b.faceStart);
        CHECK(a.faceVertices == b.faceVertices);
    }

    freeform::MeshFile duck = freeform::MeshFile::read(models + "Collada/duck.dae");
    duck.positions().row(1).array() += 10.0;
    duck.write(out + "duck.dae");
    const freeform::MeshFile back = freeform::MeshFile::read(out + "duck.dae");
    REQUIRE(back.positions().cols() == duck.positions().cols());
    CHECK((back.positions() - duck.positions()).cwiseAbs().maxCoeff() < 1e-3);
}

#else

TEST_CASE("Assimp cross-check", "[mesh_io][assimp]")
{
    WARN("built without Assimp (libassimp-dev): the cross-check of the mesh readers did not run");
}

#endif

} // namespace test_mesh_io_assimp
