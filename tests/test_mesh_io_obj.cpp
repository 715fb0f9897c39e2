// OBJ through MeshFile and readPolygonMesh: faces, per-corner attributes, groups and materials as
// in the file; identity round trips byte for byte; a moved mesh changes only the v / vn numbers.

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "freeform/io/mesh_io.h"
#include "support/process.h"
#include "support/text_lines.h"

namespace test_mesh_io_obj {

using freeform::MeshFile;
using freeform::test::lines;
using freeform::test::words;
using freeform::PolygonMesh;
using freeform::test::slurp;
using freeform::test::writeText;

namespace {

std::string tmp(const std::string& name) { return std::string(FREEFORM_TEST_TMP) + "/meshio_obj_" + name; }

// A cube made of quads with per-corner texture coordinates and six face normals (shared by the
// four corners of a side), two groups, two materials, vertex colours, a comment and CRLF line ends
// in one place.
const char* const kCube =
    "# cube\n"
    "mtllib cube.mtl\n"
    "o Cube\n"
    "v 0 0 0 1 0 0\n"
    "v 1 0 0 0 1 0\n"
    "v 1 1 0 0 0 1\n"
    "v 0 1 0 1 1 0\n"
    "v 0 0 1 0 1 1\n"
    "v 1 0 1 1 0 1\n"
    "v 1 1 1 0.5 0.5 0.5\n"
    "v 0 1 1 0.25 0.75 0.125\r\n"
    "vt 0 0\n"
    "vt 1 0\n"
    "vt 1 1\n"
    "vt 0 1\n"
    "vn 0 0 -1\n"
    "vn 0 0 1\n"
    "vn 0 -1 0\n"
    "vn 1 0 0\n"
    "vn 0 1 0\n"
    "vn -1 0 0\n"
    "g bottom_top\n"
    "usemtl red\n"
    "s off\n"
    "f 1/1/1 4/4/1 3/3/1 2/2/1\n"
    "f 5/1/2 6/2/2 7/3/2 8/4/2\n"
    "g sides\n"
    "usemtl blue\n"
    "f 1/1/3 2/2/3 6/3/3 5/4/3\n"
    "f 2/1/4 3/2/4 7/3/4 6/4/4\n"
    "f -6/1/5 -2/2/5 -1/3/5 -5/4/5\n"
    "f 4/1/6 1/2/6 5/3/6 8/4/6\n";

} // namespace

TEST_CASE("OBJ: a quad cube reads with its faces as in the file", "[mesh_io][obj]")
{
    const std::string path = tmp("cube.obj");
    writeText(path, kCube);
    const PolygonMesh mesh = freeform::readPolygonMesh(path);
    REQUIRE(mesh.vertexCount() == 8);
    REQUIRE(mesh.faceCount() == 6);
    for (int f = 0; f < 6; ++f) CHECK(mesh.faceSize(f) == 4);
    CHECK(mesh.positions.col(6) == Eigen::Vector3d(1, 1, 1));
    // "f -6/1/5 -2/2/5 -1/3/5 -5/4/5" after 8 vertices is 3 7 8 4 (1-based).
    CHECK(std::vector<int>(mesh.face(4), mesh.face(4) + 4) == std::vector<int>{2, 6, 7, 3});
    // Each vertex has three different face normals and several uvs: not per vertex.
    CHECK(mesh.normals.size() == 0);
    CHECK(mesh.texcoords.size() == 0);

    const MeshFile file = MeshFile::read(path);
    CHECK(file.format() == "obj");
    CHECK(file.positions().cols() == 8);
    REQUIRE(file.normals().cols() == 6);
    CHECK(file.normals().col(3) == Eigen::Vector3d(1, 0, 0));
    // Normal 4 (+x) is first used by "f 2/1/4 ..." at vertex 2 (index 1).
    CHECK(file.normalAnchors() == std::vector<int>{0, 4, 0, 1, 2, 3});
}

TEST_CASE("OBJ: an identity round trip reproduces the file byte for byte", "[mesh_io][obj]")
{
    const std::string in = tmp("identity_in.obj");
    const std::string out = tmp("identity_out.obj");
    writeText(in, kCube);
    MeshFile::read(in).write(out);
    CHECK(slurp(out) == kCube);
}

TEST_CASE("OBJ: a translation changes only the numbers of the v records", "[mesh_io][obj]")
{
    const std::string in = tmp("move_in.obj");
    const std::string out = tmp("move_out.obj");
    writeText(in, kCube);
    MeshFile file = MeshFile::read(in);
    file.positions().colwise() += Eigen::Vector3d(0.1, -2, 1e-3);
    file.write(out);

    const std::vector<std::string> a = lines(kCube);
    const std::vector<std::string> b = lines(slurp(out));
    REQUIRE(a.size() == b.size());
    int vIndex = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        INFO("line " << i + 1 << ": " << a[i] << " -> " << b[i]);
        const std::vector<std::string> wa = words(a[i]);
        const std::vector<std::string> wb = words(b[i]);
        if (!wa.empty() && wa[0] == "v") {
            REQUIRE(wb.size() == wa.size());
            const double shift[3] = {0.1, -2, 1e-3};
            for (int k = 0; k < 3; ++k) {
                // Independent: the input's number plus the shift, in double, read back with strtod.
                const double expected = std::strtod(wa[static_cast<std::size_t>(k + 1)].c_str(), nullptr) + shift[k];
                CHECK(std::strtod(wb[static_cast<std::size_t>(k + 1)].c_str(), nullptr) == expected);
            }
            for (std::size_t k = 4; k < wa.size(); ++k) CHECK(wb[k] == wa[k]); // the colours as they were
            ++vIndex;
        } else {
            CHECK(b[i] == a[i]);
        }
    }
    CHECK(vIndex == 8);
    // The CRLF line end of the last vertex survives the edit.
    CHECK(slurp(out).find("\r\n") != std::string::npos);
}

TEST_CASE("OBJ: per-vertex normals and texcoords fill the PolygonMesh", "[mesh_io][obj]")
{
    const std::string path = tmp("smooth.obj");
    writeText(path,
              "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
              "vt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\n"
              "vn 0 0 1\nvn 0 0 1\nvn 0 0 1\nvn 0.6 0 0.8\n"
              "f 1/1/1 2/2/2 3/3/3\nf 2/2/2 4/4/4 3/3/3\n");
    const PolygonMesh mesh = freeform::readPolygonMesh(path);
    REQUIRE(mesh.normals.cols() == 4);
    REQUIRE(mesh.texcoords.cols() == 4);
    CHECK(mesh.normals.col(3) == Eigen::Vector3d(0.6, 0, 0.8));
    CHECK(mesh.texcoords.col(1) == Eigen::Vector2d(1, 0));
    const MeshFile file = MeshFile::read(path);
    CHECK(file.normalAnchors() == std::vector<int>{0, 1, 2, 3});
}

TEST_CASE("OBJ: writePolygonMesh writes numbers that read back exactly", "[mesh_io][obj]")
{
    PolygonMesh mesh;
    mesh.positions.resize(3, 4);
    mesh.positions << 0.1, 1.0 / 3, -2e-300, 7, 0.2, 2.0 / 3, 1e300, -0.0, 0.30000000000000004, 5, 6, 8;
    mesh.normals = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, 4);
    mesh.normals.row(2).setOnes();
    mesh.addFace({0, 1, 2, 3});
    const std::string path = tmp("written.obj");
    freeform::writePolygonMesh(mesh, path);
    const PolygonMesh back = freeform::readPolygonMesh(path);
    CHECK(back.positions == mesh.positions);
    CHECK(back.normals == mesh.normals);
    CHECK(back.faceVertices == mesh.faceVertices);
    CHECK(back.faceStart == mesh.faceStart);
}

} // namespace test_mesh_io_obj
