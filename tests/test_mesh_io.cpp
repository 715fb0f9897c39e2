// PLY, STL, OFF and glTF through MeshFile: each file is built here byte by byte, read, translated
// (and left alone), written, and the output compared with the input record by record: only the
// position / normal numbers differ, and they differ by exactly the translation rounded to the
// file's type. Conversions between formats keep positions and faces.

#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "freeform/io/mesh_io.h"
#include "support/bytes.h"
#include "support/process.h"
#include "support/text_lines.h"

namespace test_mesh_io {

using freeform::MeshFile;
using freeform::test::lines;
using freeform::test::words;
using freeform::PolygonMesh;
using freeform::test::getBytes;
using freeform::test::putBytes;
using freeform::test::slurp;
using freeform::test::writeText;

namespace {

std::string tmp(const std::string& name) { return std::string(FREEFORM_TEST_TMP) + "/meshio_" + name; }

const Eigen::Vector3d kShift(0.25, -1.5, 1.0 / 3.0);

// Four vertices of a quad (float-exact values that are not round in decimal).
const float kQuad[4][3] = {{0.1f, 0.2f, 0.3f}, {1.7f, 0.0f, -0.25f}, {1.5f, 1.1f, 0.0f}, {-0.3f, 1.0f, 1e-3f}};

// ---------------------------------------------------------------------------------------- PLY

/// A binary PLY with colours, a "quality" property, a face element with an extra property, and an
/// extra element; `moved` writes the vertices translated (rounded to float as a writer must).
std::string binaryPly(bool big, bool moved)
{
    std::string s = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                    " 1.0\ncomment made by the test\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                    "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float quality\n"
                    "element face 2\nproperty list uchar int vertex_indices\nproperty uchar flags\n"
                    "element material 1\nproperty list uchar double params\nend_header\n";
    for (int i = 0; i < 4; ++i) {
        for (int k = 0; k < 3; ++k)
            putBytes<float>(s, moved ? static_cast<float>(static_cast<double>(kQuad[i][k]) + kShift(k)) : kQuad[i][k], big);
        putBytes<std::uint8_t>(s, static_cast<std::uint8_t>(10 * i), big);
        putBytes<std::uint8_t>(s, 200, big);
        putBytes<std::uint8_t>(s, 255, big);
        putBytes<float>(s, 0.5f * static_cast<float>(i), big);
    }
    putBytes<std::uint8_t>(s, 4, big); // one quad ...
    for (int v : {0, 1, 2, 3}) putBytes<std::int32_t>(s, v, big);
    putBytes<std::uint8_t>(s, 7, big);
    putBytes<std::uint8_t>(s, 3, big); // ... and one triangle
    for (int v : {0, 2, 3}) putBytes<std::int32_t>(s, v, big);
    putBytes<std::uint8_t>(s, 9, big);
    putBytes<std::uint8_t>(s, 2, big);
    putBytes<double>(s, 0.1, big);
    putBytes<double>(s, -2.5, big);
    return s;
}

} // namespace

TEST_CASE("PLY binary, both byte orders: identity and translation change only x y z", "[mesh_io][ply]")
{
    for (const bool big : {false, true}) {
        INFO((big ? "big" : "little") << " endian");
        const std::string in = tmp(big ? "be.ply" : "le.ply");
        writeText(in, binaryPly(big, false));
        MeshFile file = MeshFile::read(in);
        REQUIRE(file.positions().cols() == 4);
        CHECK(file.normals().cols() == 0);
        CHECK(file.positions()(0, 0) == static_cast<double>(0.1f));
        CHECK(file.positions()(2, 3) == static_cast<double>(1e-3f));

        const PolygonMesh mesh = file.toPolygonMesh();
        REQUIRE(mesh.faceCount() == 2);
        CHECK(mesh.faceSize(0) == 4);
        CHECK(std::vector<int>(mesh.face(1), mesh.face(1) + 3) == std::vector<int>{0, 2, 3});

        const std::string same = tmp(big ? "be_same.ply" : "le_same.ply");
        file.write(same);
        CHECK(slurp(same) == binaryPly(big, false));

        file.positions().colwise() += kShift;
        const std::string out = tmp(big ? "be_moved.ply" : "le_moved.ply");
        file.write(out);
        CHECK(slurp(out) == binaryPly(big, true));
    }
}

TEST_CASE("PLY ASCII with normals and an extra element: only the vertex numbers change", "[mesh_io][ply]")
{
    const std::string text = "ply\r\nformat ascii 1.0\r\ncomment ascii test\r\nelement vertex 3\r\nproperty double x\r\n"
                             "property double y\r\nproperty double z\r\nproperty float nx\r\nproperty float ny\r\n"
                             "property float nz\r\nproperty float s\r\nproperty float t\r\nproperty uchar red\r\n"
                             "element face 1\r\nproperty list uchar uint vertex_indices\r\nelement edge 1\r\n"
                             "property int vertex1\r\nproperty int vertex2\r\nend_header\r\n"
                             "0.1 0.2 0.30000000000000004 0 0 1 0.5 0.25 255\r\n"
                             "1e-3   -7 2.5 0 0 1 1 0 0\r\n"
                             "3 4 5 0.6 0 0.8 0 1 128\r\n"
                             "3 0 1 2\r\n"
                             "0 2\r\n";
    const std::string in = tmp("ascii.ply");
    writeText(in, text);
    MeshFile file = MeshFile::read(in);
    REQUIRE(file.positions().cols() == 3);
    REQUIRE(file.normals().cols() == 3);
    CHECK(file.normalAnchors() == std::vector<int>{0, 1, 2});
    CHECK(file.positions()(2, 0) == 0.30000000000000004);
    const PolygonMesh mesh = freeform::readPolygonMesh(in);
    REQUIRE(mesh.texcoords.cols() == 3);
    CHECK(mesh.texcoords.col(0) == Eigen::Vector2d(0.5, 0.25));
    CHECK(mesh.normals.col(2) == Eigen::Vector3d(0.6, 0, 0.8));

    file.write(tmp("ascii_same.ply"));
    CHECK(slurp(tmp("ascii_same.ply")) == text);

    file.positions().colwise() += kShift;
    file.normals().col(2) = Eigen::Vector3d(0, 0.6, 0.8);
    file.write(tmp("ascii_moved.ply"));
    const std::vector<std::string> a = lines(text), b = lines(slurp(tmp("ascii_moved.ply")));
    REQUIRE(a.size() == b.size());
    const std::size_t firstVertex = 19;
    for (std::size_t i = 0; i < a.size(); ++i) {
        INFO("line " << i + 1 << ": " << a[i] << " -> " << b[i]);
        if (i < firstVertex || i >= firstVertex + 3) {
            CHECK(b[i] == a[i]);
            continue;
        }
        const std::vector<std::string> wa = words(a[i]), wb = words(b[i]);
        REQUIRE(wa.size() == wb.size());
        for (int k = 0; k < 3; ++k) // double properties: the exact double sum
            CHECK(std::strtod(wb[static_cast<std::size_t>(k)].c_str(), nullptr) ==
                  std::strtod(wa[static_cast<std::size_t>(k)].c_str(), nullptr) + kShift(k));
        if (i == firstVertex + 2) {
            CHECK(wb[3] == "0");
            CHECK(wb[4] == "0.6"); // a float property gets the shortest text of the float
            CHECK(wb[5] == "0.8");
        } else {
            for (std::size_t k = 3; k < 6; ++k) CHECK(wb[k] == wa[k]);
        }
        for (std::size_t k = 6; k < wa.size(); ++k) CHECK(wb[k] == wa[k]);
    }
}

// ---------------------------------------------------------------------------------------- STL

namespace {

/// Two facets of a binary STL (header deliberately starting with "solid", as many exporters do).
std::string binaryStl(bool moved)
{
    std::string s = "solid but binary";
    s.resize(80, ' ');
    putBytes<std::uint32_t>(s, 2);
    const int tris[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (int f = 0; f < 2; ++f) {
        for (float n : {0.0f, 0.0f, 1.0f}) putBytes<float>(s, n);
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 3; ++k) {
                const float x = kQuad[tris[f][c]][k];
                putBytes<float>(s, moved ? static_cast<float>(static_cast<double>(x) + kShift(k)) : x);
            }
        putBytes<std::uint16_t>(s, static_cast<std::uint16_t>(0x7C00 + f)); // a colour in the attribute bytes
    }
    return s;
}

} // namespace

TEST_CASE("STL binary: corners are positions, facet normals anchored at the first corner", "[mesh_io][stl]")
{
    const std::string in = tmp("bin.stl");
    writeText(in, binaryStl(false));
    MeshFile file = MeshFile::read(in);
    REQUIRE(file.positions().cols() == 6);
    REQUIRE(file.normals().cols() == 2);
    CHECK(file.normalAnchors() == std::vector<int>{0, 3});
    CHECK(file.positions()(1, 2) == static_cast<double>(1.1f));

    // readPolygonMesh welds the two shared corners: 4 vertices, 2 triangles.
    const PolygonMesh welded = freeform::readPolygonMesh(in);
    CHECK(welded.vertexCount() == 4);
    REQUIRE(welded.faceCount() == 2);
    CHECK(std::vector<int>(welded.face(1), welded.face(1) + 3) == std::vector<int>{0, 2, 3});
    CHECK(file.toPolygonMesh().vertexCount() == 6);

    file.write(tmp("bin_same.stl"));
    CHECK(slurp(tmp("bin_same.stl")) == binaryStl(false));
    file.positions().colwise() += kShift;
    file.write(tmp("bin_moved.stl"));
    CHECK(slurp(tmp("bin_moved.stl")) == binaryStl(true));
}

TEST_CASE("STL ASCII: identity is byte for byte, a translation moves only vertex numbers", "[mesh_io][stl]")
{
    const std::string text = "solid part one\n"
                             "  facet normal 0 0 1\n    outer loop\n      vertex 0.1 0.2 0.3\n      vertex 1.7 0 -0.25\n"
                             "      vertex 1.5 1.1 0\n    endloop\n  endfacet\n"
                             "  facet normal 0 0 1\n    outer loop\n      vertex 0.1 0.2 0.3\n      vertex 1.5 1.1 0\n"
                             "      vertex -0.3 1 0.001\n    endloop\n  endfacet\n"
                             "endsolid part one\n";
    const std::string in = tmp("ascii.stl");
    writeText(in, text);
    MeshFile file = MeshFile::read(in);
    REQUIRE(file.positions().cols() == 6);
    CHECK(file.positions()(0, 0) == 0.1);
    file.write(tmp("ascii_same.stl"));
    CHECK(slurp(tmp("ascii_same.stl")) == text);

    file.positions().colwise() += kShift;
    file.write(tmp("ascii_moved.stl"));
    const std::vector<std::string> a = lines(text), b = lines(slurp(tmp("ascii_moved.stl")));
    REQUIRE(a.size() == b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        INFO(a[i] << " -> " << b[i]);
        const std::vector<std::string> wa = words(a[i]), wb = words(b[i]);
        if (wa.empty() || wa[0] != "vertex") {
            CHECK(b[i] == a[i]);
            continue;
        }
        // STL numbers are float32: the float nearest to the moved value, in its shortest text.
        for (int k = 0; k < 3; ++k)
            CHECK(std::strtof(wb[static_cast<std::size_t>(k + 1)].c_str(), nullptr) ==
                  static_cast<float>(std::strtod(wa[static_cast<std::size_t>(k + 1)].c_str(), nullptr) + kShift(k)));
    }
}

// ---------------------------------------------------------------------------------------- OFF

TEST_CASE("OFF: quads, comments and colours survive; positions move exactly", "[mesh_io][off]")
{
    const std::string text = "COFF\n# a square pyramid\n5 5 0\n"
                             "0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n1 1 0 0 0 255 255\n0 1 0 9 9 9 255\n0.5 0.5 1.25 1 1 1 255\n"
                             "4 0 3 2 1\n3 0 1 4\n3 1 2 4\n3 2 3 4 0.5 0.5 0.5\n3 3 0 4\n";
    const std::string in = tmp("pyramid.off");
    writeText(in, text);
    const PolygonMesh mesh = freeform::readPolygonMesh(in);
    REQUIRE(mesh.vertexCount() == 5);
    REQUIRE(mesh.faceCount() == 5);
    CHECK(mesh.faceSize(0) == 4);
    CHECK(mesh.positions.col(4) == Eigen::Vector3d(0.5, 0.5, 1.25));

    MeshFile file = MeshFile::read(in);
    file.write(tmp("pyramid_same.off"));
    CHECK(slurp(tmp("pyramid_same.off")) == text);
    file.positions().colwise() += kShift;
    file.write(tmp("pyramid_moved.off"));
    const std::vector<std::string> a = lines(text), b = lines(slurp(tmp("pyramid_moved.off")));
    REQUIRE(a.size() == b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (i < 3 || i >= 8) {
            CHECK(b[i] == a[i]);
            continue;
        }
        const std::vector<std::string> wa = words(a[i]), wb = words(b[i]);
        for (int k = 0; k < 3; ++k)
            CHECK(std::strtod(wb[static_cast<std::size_t>(k)].c_str(), nullptr) ==
                  std::strtod(wa[static_cast<std::size_t>(k)].c_str(), nullptr) + kShift(k));
        for (std::size_t k = 3; k < wa.size(); ++k) CHECK(wb[k] == wa[k]);
    }
}

// ---------------------------------------------------------------------------------------- glTF

namespace {

std::string base64(const std::string& bytes)
{
    static const char* const table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        std::uint32_t v = 0;
        const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
        for (std::size_t k = 0; k < 3; ++k)
            v = (v << 8) | (k < n ? static_cast<std::uint8_t>(bytes[i + k]) : 0u);
        for (std::size_t k = 0; k < 4; ++k) out.push_back(k <= n ? table[(v >> (18 - 6 * k)) & 63] : '=');
    }
    return out;
}

std::string unbase64(const std::string& text)
{
    static const std::string table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    std::uint32_t acc = 0;
    int bits = 0;
    for (char c : text) {
        if (c == '=') break;
        acc = (acc << 6) | static_cast<std::uint32_t>(table.find(c));
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out.push_back(static_cast<char>((acc >> bits) & 0xFF));
        }
    }
    return out;
}

/// The buffer of the glTF quad: positions and normals interleaved (stride 24), uvs, ushort indices.
std::string gltfBuffer(bool moved)
{
    std::string s;
    for (int i = 0; i < 4; ++i) {
        for (int k = 0; k < 3; ++k)
            putBytes<float>(s, moved ? static_cast<float>(static_cast<double>(kQuad[i][k]) + kShift(k)) : kQuad[i][k]);
        for (float n : {0.0f, 0.0f, 1.0f}) putBytes<float>(s, n);
    }
    for (float t : {0.0f, 0.0f, 1.0f, 0.0f, 1.0f, 1.0f, 0.0f, 1.0f}) putBytes<float>(s, t);
    for (std::uint16_t i : {0, 1, 2, 0, 2, 3}) putBytes<std::uint16_t>(s, i);
    return s; // 140 bytes, a multiple of 4
}

std::string floatText(float f)
{
    std::ostringstream o;
    o.precision(9);
    o << static_cast<double>(f);
    return o.str();
}

/// The glTF JSON, with `uri` for the buffer (empty: none, the GLB BIN chunk).
std::string gltfJson(const std::string& uri)
{
    std::string lo = "[", hi = "[";
    for (int k = 0; k < 3; ++k) {
        float a = kQuad[0][k], b = kQuad[0][k];
        for (int i = 1; i < 4; ++i) {
            a = std::min(a, kQuad[i][k]);
            b = std::max(b, kQuad[i][k]);
        }
        if (k > 0) {
            lo += ',';
            hi += ',';
        }
        lo += floatText(a);
        hi += floatText(b);
    }
    lo += "]";
    hi += "]";
    return std::string("{\n  \"asset\": {\"version\": \"2.0\", \"generator\": \"freeform test\"},\n") +
           "  \"scene\": 0, \"scenes\": [{\"nodes\": [0]}],\n"
           "  \"nodes\": [{\"mesh\": 0, \"name\": \"quad\", \"translation\": [1, 2, 3], \"extras\": {\"note\": \"kept \\u00e9\"}}],\n"
           "  \"materials\": [{\"name\": \"red\", \"pbrMetallicRoughness\": {\"baseColorFactor\": [1, 0, 0, 1]}}],\n"
           "  \"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": 0, \"NORMAL\": 1, \"TEXCOORD_0\": 2}, "
           "\"indices\": 3, \"material\": 0}]}],\n"
           "  \"buffers\": [{" +
           (uri.empty() ? std::string() : "\"uri\": \"" + uri + "\", ") +
           "\"byteLength\": 140}],\n"
           "  \"bufferViews\": [{\"buffer\": 0, \"byteOffset\": 0, \"byteLength\": 96, \"byteStride\": 24},\n"
           "                  {\"buffer\": 0, \"byteOffset\": 96, \"byteLength\": 32},\n"
           "                  {\"buffer\": 0, \"byteOffset\": 128, \"byteLength\": 12}],\n"
           "  \"accessors\": [{\"bufferView\": 0, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\", \"min\": " +
           lo + ", \"max\": " + hi +
           "},\n"
           "                {\"bufferView\": 0, \"byteOffset\": 12, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC3\"},\n"
           "                {\"bufferView\": 1, \"componentType\": 5126, \"count\": 4, \"type\": \"VEC2\"},\n"
           "                {\"bufferView\": 2, \"componentType\": 5123, \"count\": 6, \"type\": \"SCALAR\"}]\n}\n";
}

std::string glb(std::string json, std::string bin)
{
    while (json.size() % 4) json.push_back(' ');
    while (bin.size() % 4) bin.push_back('\0');
    std::string s;
    putBytes<std::uint32_t>(s, 0x46546C67);
    putBytes<std::uint32_t>(s, 2);
    putBytes<std::uint32_t>(s, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
    putBytes<std::uint32_t>(s, static_cast<std::uint32_t>(json.size()));
    putBytes<std::uint32_t>(s, 0x4E4F534A);
    s += json;
    putBytes<std::uint32_t>(s, static_cast<std::uint32_t>(bin.size()));
    putBytes<std::uint32_t>(s, 0x004E4942);
    s += bin;
    return s;
}

/// Checks that `out` is `in` with only accessor 0's min/max (and the buffer uri) changed, and min/max
/// are those of the moved float positions.
void checkMovedJson(const nlohmann::json& in, nlohmann::json out)
{
    const nlohmann::json lo = out["accessors"][0]["min"], hi = out["accessors"][0]["max"];
    for (int k = 0; k < 3; ++k) {
        float a = INFINITY, b = -INFINITY;
        for (int i = 0; i < 4; ++i) {
            const float x = static_cast<float>(static_cast<double>(kQuad[i][k]) + kShift(k));
            a = std::min(a, x);
            b = std::max(b, x);
        }
        CHECK(static_cast<float>(lo[static_cast<std::size_t>(k)].get<double>()) == a);
        CHECK(static_cast<float>(hi[static_cast<std::size_t>(k)].get<double>()) == b);
    }
    nlohmann::json expected = in;
    expected["accessors"][0]["min"] = lo;
    expected["accessors"][0]["max"] = hi;
    expected["buffers"][0].erase("uri");
    out["buffers"][0].erase("uri");
    CHECK(out == expected);
}

} // namespace

TEST_CASE("glTF with a data: URI: identity is byte for byte; moving rewrites the buffer and min/max only", "[mesh_io][gltf]")
{
    const std::string prefix = "data:application/octet-stream;base64,";
    const std::string text = gltfJson(prefix + base64(gltfBuffer(false)));
    const std::string in = tmp("quad.gltf");
    writeText(in, text);

    MeshFile file = MeshFile::read(in);
    REQUIRE(file.positions().cols() == 4);
    REQUIRE(file.normals().cols() == 4);
    CHECK(file.normalAnchors() == std::vector<int>{0, 1, 2, 3});
    CHECK(file.positions()(1, 2) == static_cast<double>(1.1f));
    const PolygonMesh mesh = file.toPolygonMesh();
    REQUIRE(mesh.faceCount() == 2);
    CHECK(mesh.faceVertices == std::vector<int>{0, 1, 2, 0, 2, 3});
    REQUIRE(mesh.texcoords.cols() == 4);
    CHECK(mesh.texcoords.col(2) == Eigen::Vector2d(1, 1));
    REQUIRE(mesh.normals.cols() == 4);

    file.write(tmp("quad_same.gltf"));
    CHECK(slurp(tmp("quad_same.gltf")) == text);

    file.positions().colwise() += kShift;
    file.write(tmp("quad_moved.gltf"));
    const nlohmann::json out = nlohmann::json::parse(slurp(tmp("quad_moved.gltf")));
    const std::string uri = out["buffers"][0]["uri"].get<std::string>();
    REQUIRE(uri.rfind(prefix, 0) == 0);
    CHECK(unbase64(uri.substr(prefix.size())) == gltfBuffer(true));
    checkMovedJson(nlohmann::json::parse(text), out);
}

TEST_CASE("glTF with an external .bin: written beside the output, the input's buffer untouched", "[mesh_io][gltf]")
{
    const std::string dir = tmp("ext");
    std::filesystem::create_directories(dir);
    writeText(dir + "/quad data.bin", gltfBuffer(false));
    writeText(dir + "/quad.gltf", gltfJson("quad%20data.bin"));
    MeshFile file = MeshFile::read(dir + "/quad.gltf");
    file.positions().colwise() += kShift;
    file.write(dir + "/moved.gltf");
    CHECK(slurp(dir + "/quad data.bin") == gltfBuffer(false));
    CHECK(slurp(dir + "/moved.bin") == gltfBuffer(true));
    const nlohmann::json out = nlohmann::json::parse(slurp(dir + "/moved.gltf"));
    CHECK(out["buffers"][0]["uri"] == "moved.bin");
    checkMovedJson(nlohmann::json::parse(gltfJson("quad%20data.bin")), out);
}

TEST_CASE("GLB: identity is byte for byte, moving rewrites the BIN chunk; .glb <-> .gltf", "[mesh_io][gltf]")
{
    const std::string bytes = glb(gltfJson(""), gltfBuffer(false));
    const std::string in = tmp("quad.glb");
    writeText(in, bytes);
    MeshFile file = MeshFile::read(in);
    CHECK(file.format() == "glb");
    REQUIRE(file.positions().cols() == 4);
    file.write(tmp("quad_same.glb"));
    CHECK(slurp(tmp("quad_same.glb")) == bytes);

    file.positions().colwise() += kShift;
    file.write(tmp("quad_moved.glb"));
    const std::string out = slurp(tmp("quad_moved.glb"));
    REQUIRE(out.size() > 20);
    CHECK(getBytes<std::uint32_t>(out, 8) == out.size());
    const std::uint32_t jsonLength = getBytes<std::uint32_t>(out, 12);
    CHECK(jsonLength % 4 == 0);
    const nlohmann::json json = nlohmann::json::parse(out.substr(20, jsonLength));
    checkMovedJson(nlohmann::json::parse(gltfJson("")), json);
    const std::size_t binAt = 20 + jsonLength;
    CHECK(getBytes<std::uint32_t>(out, binAt + 4) == 0x004E4942u);
    CHECK(out.substr(binAt + 8) == gltfBuffer(true));

    // To .gltf: the BIN chunk becomes OUT.bin; and back to .glb: embedded. Positions stay.
    file.write(tmp("from_glb.gltf"));
    CHECK(slurp(tmp("from_glb.bin")) == gltfBuffer(true));
    const Eigen::Matrix<double, 3, Eigen::Dynamic> stored = file.positions().cast<float>().cast<double>();
    const MeshFile gltf = MeshFile::read(tmp("from_glb.gltf"));
    CHECK(gltf.positions() == stored);
    gltf.write(tmp("from_gltf.glb"));
    const MeshFile back = MeshFile::read(tmp("from_gltf.glb"));
    CHECK(back.positions() == stored);
    CHECK(back.toPolygonMesh().faceVertices == file.toPolygonMesh().faceVertices);
}

// ---------------------------------------------------------------------------------------- conversions

TEST_CASE("Conversions keep positions, faces and what the target can carry", "[mesh_io][convert]")
{
    const std::string in = tmp("conv.obj");
    writeText(in, "v 0.1 0.2 0.3 1 0 0\nv 1 0 0 0 1 0\nv 1 1 0 0 0 1\nv 0 1 1e-7 1 1 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                  "vn 0 0 1\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\nf 1/1/1 2/2/2 3/3/3 4/4/4\n");
    const MeshFile file = MeshFile::read(in);

    SECTION("to PLY and OFF: doubles exact, the quad stays a quad, uvs and normals kept")
    {
        for (const char* ext : {"ply", "off"}) {
            INFO(ext);
            const std::string out = tmp(std::string("conv_out.") + ext);
            file.write(out);
            const PolygonMesh back = freeform::readPolygonMesh(out);
            CHECK(back.positions == file.positions());
            CHECK(back.faceStart == std::vector<int>{0, 4});
            CHECK(back.faceVertices == std::vector<int>{0, 1, 2, 3});
            REQUIRE(back.texcoords.cols() == 4);
            CHECK(back.texcoords.col(2) == Eigen::Vector2d(1, 1));
            REQUIRE(back.normals.cols() == 4);
        }
    }
    SECTION("to glTF and STL: float positions, triangles")
    {
        file.write(tmp("conv_out.glb"));
        const PolygonMesh glb = freeform::readPolygonMesh(tmp("conv_out.glb"));
        REQUIRE(glb.vertexCount() == 4);
        for (int i = 0; i < 4; ++i)
            for (int k = 0; k < 3; ++k) CHECK(glb.positions(k, i) == static_cast<double>(static_cast<float>(file.positions()(k, i))));
        CHECK(glb.faceVertices == std::vector<int>{0, 1, 2, 0, 2, 3});
        CHECK(glb.texcoords.cols() == 4);

        file.write(tmp("conv_out.stl"));
        const MeshFile stl = MeshFile::read(tmp("conv_out.stl"));
        REQUIRE(stl.positions().cols() == 6);
        const Eigen::Vector3d a(0.1, 0.2, 0.3), b(1, 0, 0), c(1, 1, 0);
        const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
        for (int k = 0; k < 3; ++k) CHECK(stl.normals()(k, 0) == Approx(n(k)).epsilon(1e-7));
        CHECK(freeform::readPolygonMesh(tmp("conv_out.stl")).vertexCount() == 4);
    }
}

// ---------------------------------------------------------------------------------------- samples

TEST_CASE("The sample meshes of data/meshes agree across formats and round-trip byte for byte", "[mesh_io][samples]")
{
    const std::string dir = std::string(FREEFORM_SOURCE_DIR) + "/data/meshes/";
    const PolygonMesh obj = freeform::readPolygonMesh(dir + "sphere.obj");
    REQUIRE(obj.vertexCount() == 266);
    REQUIRE(obj.faceCount() == 288);
    CHECK(obj.normals.cols() == 266);
    CHECK(obj.texcoords.cols() == 266);
    const Eigen::Matrix<double, 3, Eigen::Dynamic> asFloat = obj.positions.cast<float>().cast<double>();
    // glTF is Y up (its specification): the glTF samples store the OBJ's point (x, y, z) as
    // (x, z, -y), so that the import's quarter turn (x, y, z) -> (x, -z, y) gives the OBJ's point
    // back and the poles (0, 0, +-1) of the others lie at (0, +-1, 0) in the file. Written out by
    // hand: a row permutation and a sign, exact in float.
    Eigen::Matrix<double, 3, Eigen::Dynamic> yUp(3, asFloat.cols());
    yUp.row(0) = asFloat.row(0);
    yUp.row(1) = asFloat.row(2);
    yUp.row(2) = -asFloat.row(1);
    for (const char* name : {"sphere.ply", "sphere.gltf", "sphere.glb", "sphere.off", "sphere.stl"}) {
        INFO(name);
        const PolygonMesh mesh = freeform::readPolygonMesh(dir + name);
        REQUIRE(mesh.vertexCount() == 266); // STL: welded back to the shared vertices
        const bool single = std::string(name) != "sphere.off";
        const bool gltf = std::string(name).find(".gl") != std::string::npos;
        CHECK(mesh.positions == (gltf ? yUp : single ? asFloat : obj.positions));
        if (gltf) {
            // The poles: vertex 0 is the top (0, 0, 1) of the OBJ, vertex 265 the bottom.
            CHECK(mesh.positions.col(0) == Eigen::Vector3d(0, 1, 0));
            CHECK(mesh.positions.col(265) == Eigen::Vector3d(0, -1, 0));
            CHECK(mesh.normals.col(0) == Eigen::Vector3d(0, 1, 0));
        }
        const bool triangles = std::string(name).find(".gl") != std::string::npos || std::string(name) == "sphere.stl";
        CHECK(mesh.faceCount() == (triangles ? 24 * 2 + 240 * 2 : 288));
    }
    for (const char* name : {"cube.obj", "sphere.obj", "sphere.ply", "sphere.gltf", "sphere.glb", "sphere.off", "sphere.stl"}) {
        INFO(name);
        const std::string out = tmp(std::string("sample_") + name);
        MeshFile::read(dir + name).write(out);
        if (std::string(name) != "sphere.gltf") {
            CHECK(slurp(out) == slurp(dir + name));
            continue;
        }
        // Written elsewhere, the external buffer follows the output's name; all else is the same.
        nlohmann::json a = nlohmann::json::parse(slurp(dir + name)), b = nlohmann::json::parse(slurp(out));
        CHECK(b["buffers"][0]["uri"] == "meshio_sample_sphere.bin");
        a["buffers"][0].erase("uri");
        b["buffers"][0].erase("uri");
        CHECK(a == b);
        CHECK(slurp(tmp("sample_sphere.bin")) == slurp(dir + "sphere.bin"));
    }
    const PolygonMesh cube = freeform::readPolygonMesh(dir + "cube.obj");
    CHECK(cube.vertexCount() == 8);
    CHECK(cube.faceCount() == 6);
}

namespace {

/// The same doubles, bit for bit (== would let -0 equal +0 and refuse NaN).
template <class Matrix>
bool sameBits(const Matrix& a, const Matrix& b)
{
    return a.rows() == b.rows() && a.cols() == b.cols() &&
           (a.size() == 0 || std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0);
}

} // namespace

TEST_CASE("MeshFile::readBytes reads a file from memory as read() reads it from the disk", "[mesh_io][memory]")
{
    const std::string dir = std::string(FREEFORM_SOURCE_DIR) + "/data/meshes/";
    // A folder that does not exist: nothing of the file or its buffers can come from the disk.
    const std::string nowhere = tmp("memory_nowhere") + "/";
    REQUIRE_FALSE(std::filesystem::exists(nowhere));
    for (const char* name : {"cube.obj", "sphere.obj", "sphere.ply", "sphere.gltf", "sphere.glb", "sphere.off", "sphere.stl"}) {
        INFO(name);
        const MeshFile file = MeshFile::read(dir + name);
        CHECK(file.bytes() == slurp(dir + name));
        const bool external = std::string(name) == "sphere.gltf";
        const std::map<std::string, std::string> companions = file.companions();
        if (external) {
            REQUIRE(companions.size() == 1);
            CHECK(companions.at("sphere.bin") == slurp(dir + "sphere.bin")); // its byteLength is the whole file
        } else {
            CHECK(companions.empty());
        }
        MeshFile copy = MeshFile::readBytes(nowhere + name, file.bytes(), companions);
        CHECK(copy.path() == nowhere + name);
        CHECK(copy.format() == file.format());
        CHECK(copy.reader() == file.reader());
        CHECK(sameBits(copy.positions(), file.positions()));
        CHECK(sameBits(copy.normals(), file.normals()));
        CHECK(sameBits(copy.tangents(), file.tangents()));
        CHECK(copy.normalAnchors() == file.normalAnchors());
        CHECK(copy.bytes() == file.bytes());
        CHECK(copy.companions() == companions);
        // Moved alike, both write the same file to the same path (a .gltf's buffer is written
        // beside it, named after it).
        MeshFile moved = MeshFile::read(dir + name);
        moved.positions().colwise() += kShift;
        copy.positions().colwise() += kShift;
        const std::string out = tmp("memory_out") + std::filesystem::path(name).extension().string();
        moved.write(out);
        const std::string fromDisk = slurp(out), binFromDisk = external ? slurp(tmp("memory_out.bin")) : "";
        std::filesystem::remove(out);
        copy.write(out);
        CHECK(slurp(out) == fromDisk);
        if (external) {
            CHECK(slurp(tmp("memory_out.bin")) == binFromDisk);
            CHECK(binFromDisk != slurp(dir + "sphere.bin")); // it did move
        }
    }
}

TEST_CASE("MeshFile::readBytes: a missing companion and bad bytes are errors naming the file", "[mesh_io][memory]")
{
    const std::string dir = std::string(FREEFORM_SOURCE_DIR) + "/data/meshes/";
    // The .gltf's buffer is neither given nor read from beside it on the disk.
    REQUIRE_THROWS_WITH(MeshFile::readBytes(dir + "sphere.gltf", slurp(dir + "sphere.gltf")),
                        Catch::Contains(dir + "sphere.gltf: buffer 0: the uri \"sphere.bin\" names sphere.bin, which is not "
                                        "among the files given with it"));
    // A uri that leaves the folder is refused before any lookup, as on the disk.
    std::string json = slurp(dir + "sphere.gltf");
    const std::size_t at = json.find("\"sphere.bin\"");
    REQUIRE(at != std::string::npos);
    json.replace(at, 12, "\"../sphere.bin\"");
    REQUIRE_THROWS_WITH(MeshFile::readBytes("m.gltf", json, {{"../sphere.bin", slurp(dir + "sphere.bin")}}),
                        Catch::Contains("m.gltf: buffer 0: the uri \"../sphere.bin\" leaves the folder (..)"));
    // A buffer shorter than its byteLength, as a truncated file on the disk.
    REQUIRE_THROWS_WITH(MeshFile::readBytes("m.gltf", slurp(dir + "sphere.gltf"), {{"sphere.bin", "abc"}}),
                        Catch::Contains("m.gltf: buffer 0 holds 3 bytes, its byteLength is"));
    // Truncated binary STL: the same message as the file on the disk, under the given name.
    const std::string stl = slurp(dir + "sphere.stl").substr(0, 200);
    writeText(tmp("memory_truncated.stl"), stl);
    std::string fromDisk;
    try {
        (void)MeshFile::read(tmp("memory_truncated.stl"));
    } catch (const freeform::Error& e) {
        fromDisk = e.what();
    }
    REQUIRE(fromDisk.rfind(tmp("memory_truncated.stl") + ": ", 0) == 0);
    REQUIRE_THROWS_WITH(MeshFile::readBytes("cut.stl", stl),
                        "cut.stl: " + fromDisk.substr(tmp("memory_truncated.stl").size() + 2));
    REQUIRE_THROWS_WITH(MeshFile::readBytes("mesh.xyz123", "v 0 0 0\n"), Catch::Contains("mesh.xyz123: unknown mesh format '.xyz123'"));
}

} // namespace test_mesh_io
