// Bad mesh files give a freeform::Error that names the file and the line / byte / element; a failed
// write leaves an existing output as it was and no temporary file behind.

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>

#include "freeform/io/mesh_io.h"
#include "support/bytes.h"
#include "support/process.h"

namespace test_mesh_io_errors {

using freeform::MeshFile;
using freeform::test::putBytes;
using freeform::test::slurp;
using freeform::test::writeText;
using Catch::Matchers::Contains;

namespace {

std::string tmp(const std::string& name) { return std::string(FREEFORM_TEST_TMP) + "/meshio_err_" + name; }

/// Writes `content` to a scratch file and returns the message of the Error that reading it throws.
std::string readError(const std::string& name, const std::string& content)
{
    const std::string path = tmp(name);
    writeText(path, content);
    try {
        (void)MeshFile::read(path);
    } catch (const freeform::Error& e) {
        // readPolygonMesh goes the same way and must agree.
        try {
            (void)freeform::readPolygonMesh(path);
        } catch (const freeform::Error& e2) {
            CHECK(std::string(e2.what()) == e.what());
            return e.what();
        }
        FAIL("readPolygonMesh accepted what MeshFile::read rejected");
    }
    FAIL("no error for " << name);
    return {};
}

std::string binaryPlyHeader(int vertices)
{
    return "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(vertices) +
           "\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
}

} // namespace

TEST_CASE("Missing files and unknown formats", "[mesh_io][errors]")
{
    const std::string missing = tmp("does_not_exist.obj");
    CHECK_THROWS_WITH(MeshFile::read(missing), Contains(missing) && Contains("cannot open"));
    CHECK_THROWS_WITH(freeform::readPolygonMesh(tmp("mesh.xyz")), Contains("mesh.xyz") && Contains("unknown mesh format '.xyz'"));
    CHECK_THROWS_WITH(freeform::readPolygonMesh(tmp("noextension")), Contains("(no extension)"));
    CHECK_THROWS_WITH(freeform::writePolygonMesh(freeform::PolygonMesh(), tmp("out.fbx")), Contains("unknown mesh format '.fbx'"));
}

TEST_CASE("OBJ errors name the line", "[mesh_io][errors][obj]")
{
    CHECK_THAT(readError("nan.obj", "v 0 0 0\nv nan 1 2\n"), Contains("nan.obj:2:") && Contains("not finite"));
    CHECK_THAT(readError("inf.obj", "# c\nv 0 0 0\nv 1 -inf 2\n"), Contains("inf.obj:3:") && Contains("not finite"));
    CHECK_THAT(readError("short.obj", "v 0 0\n"), Contains("short.obj:1:") && Contains("too few numbers"));
    CHECK_THAT(readError("word.obj", "v 0 zero 0\n"), Contains("word.obj:1:") && Contains("'zero' is not a number"));
    CHECK_THAT(readError("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"),
               Contains("range.obj:4:") && Contains("refers to vertex 9, the file has 3"));
    CHECK_THAT(readError("relative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n"), Contains("relative.obj:4:"));
    CHECK_THAT(readError("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"), Contains("zero.obj:4:") && Contains("start at 1"));
    CHECK_THAT(readError("normal.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//2 3//1\n"),
               Contains("normal.obj:5:") && Contains("normal 2, the file has 1"));
    CHECK_THAT(readError("twocorners.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n"), Contains("twocorners.obj:3:") && Contains("at least 3"));
}

TEST_CASE("PLY errors: truncated, wrong counts, bad indices, NaN", "[mesh_io][errors][ply]")
{
    std::string good = binaryPlyHeader(3);
    for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) putBytes<float>(good, v);
    putBytes<std::uint8_t>(good, 3);
    for (int i : {0, 1, 2}) putBytes<std::int32_t>(good, i);
    REQUIRE_NOTHROW(MeshFile::read((writeText(tmp("good.ply"), good), tmp("good.ply"))));

    CHECK_THAT(readError("truncated.ply", good.substr(0, good.size() - 5)), Contains("truncated.ply") && Contains("truncated"));
    CHECK_THAT(readError("cut_vertex.ply", good.substr(0, binaryPlyHeader(3).size() + 20)),
               Contains("element 'vertex' 1 property 'z'"));
    CHECK_THAT(readError("extra.ply", good + "abcd"), Contains("after the last element"));

    std::string badIndex = good;
    badIndex[badIndex.size() - 4] = 7; // the last index becomes 7
    CHECK_THAT(readError("index.ply", badIndex), Contains("face 0 refers to vertex 7, the file has 3"));

    std::string nan = binaryPlyHeader(3);
    for (float v : {0.f, 0.f, 0.f, 1.f, NAN, 0.f, 0.f, 1.f, 0.f}) putBytes<float>(nan, v);
    putBytes<std::uint8_t>(nan, 3);
    for (int i : {0, 1, 2}) putBytes<std::int32_t>(nan, i);
    CHECK_THAT(readError("nan.ply", nan), Contains("nan.ply: byte ") && Contains("vertex 1 coordinate y is not finite"));

    const std::string asciiHeader = "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\n"
                                    "property double z\nend_header\n";
    CHECK_THAT(readError("few.ply", asciiHeader + "0 0 0\n1 0 0\n0 1 0\n"),
               Contains("few.ply:") && Contains("ends inside element 'vertex' 3"));
    CHECK_THAT(readError("many.ply", asciiHeader + "0 0 0\n1 0 0\n0 1 0\n1 1 0\n2 2 2\n"), Contains("many.ply:12:"));
    CHECK_THAT(readError("header.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"), Contains("no end_header"));
    CHECK_THAT(readError("notply.ply", "solid x\n"), Contains("notply.ply:1: not a PLY file"));
    CHECK_THAT(readError("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n"),
               Contains("type.ply:4:") && Contains("unknown property type 'quad'"));
}

TEST_CASE("STL errors", "[mesh_io][errors][stl]")
{
    std::string binary(80, '\0');
    putBytes<std::uint32_t>(binary, 2);
    binary += std::string(50 * 2, '\0');
    REQUIRE_NOTHROW(MeshFile::read((writeText(tmp("good.stl"), binary), tmp("good.stl"))));
    CHECK_THAT(readError("truncated.stl", binary.substr(0, binary.size() - 10)),
               Contains("truncated.stl") && Contains("2 triangles (184 bytes), the file has 174 bytes"));
    CHECK_THAT(readError("tiny.stl", "abc"), Contains("too short"));

    std::string nan = binary;
    const float bad = NAN;
    std::memcpy(&nan[84 + 50 + 16], &bad, 4); // facet 1, first vertex, y
    CHECK_THAT(readError("nan.stl", nan), Contains("byte 150") && Contains("facet 1 vertex coordinate is not finite"));

    CHECK_THAT(readError("ascii.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n"),
               Contains("ascii.stl:6:") && Contains("facet 0 has 2 vertices"));
    CHECK_THAT(readError("cut.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0"),
               Contains("cut.stl:5:") && Contains("ends inside a facet"));
    CHECK_THAT(readError("word.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 O\n"),
               Contains("word.stl:6:") && Contains("'O' is not a number"));
}

TEST_CASE("OFF errors", "[mesh_io][errors][off]")
{
    CHECK_THAT(readError("counts.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n"), Contains("ends after 3 of 4 vertices"));
    CHECK_THAT(readError("index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
               Contains("index.off:6:") && Contains("refers to vertex 3, the file has 3"));
    CHECK_THAT(readError("nan.off", "OFF\n3 1 0\n0 0 0\n1 NaN 0\n0 1 0\n3 0 1 2\n"), Contains("nan.off:4:") && Contains("not finite"));
    CHECK_THAT(readError("extra.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n"), Contains("extra.off:7:"));
    CHECK_THAT(readError("magic.off", "PLY\n"), Contains("not an OFF file"));
}

TEST_CASE("glTF errors", "[mesh_io][errors][gltf]")
{
    CHECK_THAT(readError("json.gltf", "{\"asset\": {\"version\": \"2.0\"},, }"), Contains("json.gltf: invalid JSON at byte"));
    CHECK_THAT(readError("version.gltf", "{\"asset\": {\"version\": \"1.0\"}}"), Contains("version '1.0'"));
    const std::string buffer12 = "{\"asset\": {\"version\": \"2.0\"}, \"buffers\": [{\"uri\": \"data:application/octet-stream;base64,"
                                 "AAAAAAAAAAAAAAAA\", \"byteLength\": 12}], \"bufferViews\": [{\"buffer\": 0, \"byteLength\": 12}],"
                                 " \"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": ";
    const std::string mesh = ", \"type\": \"VEC3\"}], \"meshes\": [{\"primitives\": [{\"mode\": 0, \"attributes\": {\"POSITION\": 0}";
    REQUIRE_NOTHROW(MeshFile::read((writeText(tmp("ok.gltf"), buffer12 + "1" + mesh + "}]}]}"), tmp("ok.gltf"))));
    CHECK_THAT(readError("count.gltf", buffer12 + "2" + mesh + "}]}]}"), Contains("accessor 0") && Contains("past the end"));
    CHECK_THAT(readError("accessor.gltf", buffer12 + "1" + mesh + ", \"indices\": 5}]}]}"),
               Contains("refers to accessor 5, the file has 1"));
    CHECK_THAT(readError("missing_bin.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"buffers\": [{\"uri\": \"nothere.bin\", \"byteLength\": 4}]}"),
               Contains("buffer 0") && Contains("nothere.bin"));

    std::string glb;
    putBytes<std::uint32_t>(glb, 0x46546C67);
    putBytes<std::uint32_t>(glb, 2);
    putBytes<std::uint32_t>(glb, 100);
    putBytes<std::uint32_t>(glb, 80);
    putBytes<std::uint32_t>(glb, 0x4E4F534A);
    glb += "{\"asset\":{\"version\":\"2.0\"}}";
    CHECK_THAT(readError("truncated.glb", glb), Contains("truncated.glb: the GLB header says 100 bytes, the file has 47 (truncated?)"));
    CHECK_THAT(readError("magic.glb", "glTX and more bytes than twenty"), Contains("not a GLB file"));
}

TEST_CASE("A failed write leaves the existing output untouched", "[mesh_io][errors][write]")
{
    const std::string in = tmp("w.obj");
    writeText(in, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const std::string out = tmp("w_out.obj");
    writeText(out, "precious\n");

    MeshFile file = MeshFile::read(in);
    file.positions()(1, 2) = std::nan("");
    CHECK_THROWS_WITH(file.write(out), Contains("position 2 is not finite"));
    CHECK(slurp(out) == "precious\n");

    MeshFile resized = MeshFile::read(in);
    resized.positions().conservativeResize(3, 2);
    CHECK_THROWS_WITH(resized.write(out), Contains("changed from 3 to 2 columns"));
    CHECK(slurp(out) == "precious\n");

    // Float overflow in a float32 format fails before the output is replaced.
    writeText(tmp("w.stl"), "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n");
    std::string binary(80, '\0');
    putBytes<std::uint32_t>(binary, 1);
    binary += std::string(50, '\0');
    writeText(tmp("wb.stl"), binary);
    MeshFile stl = MeshFile::read(tmp("wb.stl"));
    stl.positions()(0, 1) = 1e300;
    const std::string stlOut = tmp("wb_out.stl");
    writeText(stlOut, "precious\n");
    CHECK_THROWS_WITH(stl.write(stlOut), Contains("overflows float32"));
    CHECK(slurp(stlOut) == "precious\n");

    // An output directory that does not exist: nothing is created.
    const std::string dir = tmp("no_such_dir");
    CHECK_THROWS_AS(MeshFile::read(in).write(dir + "/x.obj"), freeform::Error);
    CHECK_FALSE(std::filesystem::exists(dir));

    // No temporary file is left beside the output.
    for (const auto& entry : std::filesystem::directory_iterator(FREEFORM_TEST_TMP))
        CHECK(entry.path().filename().string().find(".w_out.obj.tmp") == std::string::npos);
    CHECK_THROWS_WITH(freeform::writePolygonMesh(file.toPolygonMesh(), out), Contains("vertex 2 is not finite"));
    CHECK(slurp(out) == "precious\n");
}

} // namespace test_mesh_io_errors
