// Hostile input (docs/mesh-io.md, "Hostile input"): each case here failed on the readers before
// they were hardened (issue 16) — out-of-bounds reads and writes, stack overflows on deep nesting,
// header counts that allocate gigabytes, silent acceptance of garbage — and must now be a
// freeform::Error that names the file and what is wrong, before any output is touched. The inputs
// the fuzzers found live in tests/regressions/ and are replayed at the end.

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "freeform/core/error.h"
#include "freeform/core/warning.h"
#include "freeform/io/bpt.h"
#include "freeform/io/document.h"
#include "freeform/io/geometry_data.h"
#include "freeform/io/json_check.h"
#include "freeform/io/mesh_io.h"
#include "freeform/io/obj_freeform.h"
#include "freeform/subdivision/subdivision_surface.h"
#include "freeform/surface/bezier_surface.h"
#include "freeform/surface/patch_complex.h"
#include "freeform/io/deform_file.h"
#include "freeform/volume/lattice.h"
#include "support/bytes.h"
#include "support/process.h"

namespace test_hardening {

using freeform::Error;
using freeform::MeshFile;
using freeform::ScopedWarningHandler;
using freeform::setWarningHandler;
using freeform::warn;
using freeform::WarningHandler;
using freeform::test::putBytes;
using freeform::test::slurp;
using freeform::test::writeText;
using Catch::Matchers::Contains;
using Catch::Matchers::Equals;
using Catch::Matchers::StartsWith;
using Catch::Matchers::WithinRel;
namespace fs = std::filesystem;

namespace {

std::string tmp(const std::string& name)
{
    const std::string dir = std::string(FREEFORM_TEST_TMP) + "/hardening";
    fs::create_directories(dir);
    return dir + "/" + name;
}

/// The message of the Error that reading `content` as file `name` throws (FAIL when none).
std::string readError(const std::string& name, const std::string& content)
{
    const std::string path = tmp(name);
    writeText(path, content);
    try {
        (void)MeshFile::read(path);
    } catch (const Error& e) {
        return e.what();
    }
    FAIL("reading " << name << " did not throw");
    return {};
}

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAsan = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAsan = true;
#else
constexpr bool kAsan = false;
#endif
#else
constexpr bool kAsan = false;
#endif

/// Runs f in a child process whose address space may grow by at most `megabytes` beyond what the
/// test process uses now; true when f returned normally and the child exited 0 (an allocation
/// beyond the cap throws bad_alloc in the child, which exits 3).
template <typename F>
bool withinMemory(std::size_t megabytes, F&& f)
{
    std::size_t pages = 0;
    {
        std::ifstream statm("/proc/self/statm");
        statm >> pages;
    }
    const rlim_t now = static_cast<rlim_t>(pages) * static_cast<rlim_t>(sysconf(_SC_PAGESIZE));
    const pid_t child = fork();
    if (child == 0) {
        rlimit limit{now + megabytes * 1024 * 1024, now + megabytes * 1024 * 1024};
        setrlimit(RLIMIT_AS, &limit);
        try {
            f();
        } catch (const std::bad_alloc&) {
            _exit(3);
        } catch (...) {
            _exit(4);
        }
        _exit(0);
    }
    int status = 0;
    waitpid(child, &status, 0);
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

// ---- a small glTF built by hand: one triangle, positions at bytes 0..35 of a data: buffer

std::string base64(const std::string& bytes)
{
    static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    std::size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                           static_cast<unsigned char>(bytes[i + 2]);
        for (int k = 3; k >= 0; --k) out.push_back(t[(v >> (6 * k)) & 63]);
    }
    if (i + 1 == bytes.size()) {
        const unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
        out += std::string{t[(v >> 18) & 63], t[(v >> 12) & 63], '=', '='};
    } else if (i + 2 == bytes.size()) {
        const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) | (static_cast<unsigned char>(bytes[i + 1]) << 8);
        out += std::string{t[(v >> 18) & 63], t[(v >> 12) & 63], t[(v >> 6) & 63], '='};
    }
    return out;
}

std::string triangleBuffer()
{
    std::string b;
    for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) putBytes(b, v);
    return b;
}

/// A glTF text with the accessor and bufferView members given (JSON fragments, may be empty).
std::string gltf(const std::string& accessorExtra, const std::string& viewExtra, const std::string& bufferUri = "")
{
    const std::string buffer = triangleBuffer();
    const std::string uri = bufferUri.empty() ? "data:application/octet-stream;base64," + base64(buffer) : bufferUri;
    return std::string("{\"asset\":{\"version\":\"2.0\"},\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],") +
           "\"buffers\":[{\"uri\":\"" + uri + "\",\"byteLength\":36}]," +
           "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36" + viewExtra + "}]," +
           "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\"" + accessorExtra + "}]}";
}

std::string nested(int depth, const std::string& inner = "1")
{
    return std::string(static_cast<std::size_t>(depth), '[') + inner + std::string(static_cast<std::size_t>(depth), ']');
}

} // namespace

// ------------------------------------------------------------------ 1. memory safety

TEST_CASE("glTF offsets, strides and counts that would wrap the bounds check are refused", "[hardening][gltf]")
{
    // The hand-made triangle itself reads (so the cases below fail for the member they change).
    writeText(tmp("ok.gltf"), gltf("", ""));
    CHECK(MeshFile::read(tmp("ok.gltf")).positions().cols() == 3);

    CHECK_THROWS_WITH(MeshFile::read((writeText(tmp("a.gltf"), gltf(",\"byteOffset\":-12", "")), tmp("a.gltf"))),
                      Contains("a.gltf") && Contains("byteOffset"));
    CHECK_THROWS_WITH(MeshFile::read((writeText(tmp("b.gltf"), gltf(",\"byteOffset\":18446744073709551604", "")), tmp("b.gltf"))),
                      Contains("b.gltf") && Contains("byteOffset"));
    CHECK_THROWS_WITH(MeshFile::read((writeText(tmp("c.gltf"), gltf("", ",\"byteOffset\":-36")), tmp("c.gltf"))),
                      Contains("c.gltf") && Contains("byteOffset"));
    CHECK_THROWS_WITH(MeshFile::read((writeText(tmp("d.gltf"), gltf("", ",\"byteStride\":4294967292")), tmp("d.gltf"))),
                      Contains("d.gltf") && Contains("byteStride"));
    CHECK_THROWS_WITH(MeshFile::read((writeText(tmp("e.gltf"), gltf("", ",\"byteStride\":9223372036854775804")), tmp("e.gltf"))),
                      Contains("e.gltf") && Contains("byteStride"));
    CHECK_THROWS_WITH(MeshFile::read((writeText(tmp("f.gltf"), gltf(",\"byteOffset\":4611686018427387904", "")), tmp("f.gltf"))),
                      Contains("f.gltf"));
    // A stride of 0 would read 20 million copies of the same 12 bytes (3 GB of vertices).
    std::string zero = gltf("", ",\"byteStride\":0");
    zero.replace(zero.find("\"count\":3"), 9, "\"count\":20000000");
    CHECK_THROWS_WITH(MeshFile::read((writeText(tmp("g.gltf"), zero), tmp("g.gltf"))), Contains("g.gltf") && Contains("byteStride"));
    // A float where an index belongs, and an index past the int range.
    std::string flt = gltf("", "");
    flt.replace(flt.find("\"POSITION\":0"), 12, "\"POSITION\":1e300");
    CHECK_THROWS_WITH(MeshFile::read((writeText(tmp("h.gltf"), flt), tmp("h.gltf"))), Contains("h.gltf") && Contains("POSITION"));
}

TEST_CASE("A failed read never replaces an existing output", "[hardening][gltf]")
{
    const std::string out = tmp("kept.gltf");
    writeText(out, "precious");
    writeText(tmp("bad.gltf"), gltf(",\"byteOffset\":-12", ""));
    const auto convert = [&] { MeshFile::read(tmp("bad.gltf")).write(out); };
    CHECK_THROWS_AS(convert(), Error);
    CHECK(slurp(out) == "precious");
}

TEST_CASE("JSON nested tens of thousands deep is refused before any recursion", "[hardening][json]")
{
    const std::string deep = nested(50000);
    CHECK_THROWS_WITH(freeform::checkJsonText(deep, "deep.json"), Contains("deep.json") && Contains("nested deeper than"));
    CHECK_NOTHROW(freeform::checkJsonText(nested(freeform::kMaxJsonDepth), "ok.json"));
    CHECK_THROWS_WITH(freeform::checkJsonText(nested(freeform::kMaxJsonDepth + 1), "x.json"), Contains("nested deeper than 256"));

    // The document's editor member, a lattice field.
    const std::string doc = "{\"format\":\"freeform\",\"version\":1,\"objects\":[],\"editor\":{\"a\":" + nested(50000) + "}}";
    CHECK_THROWS_WITH(freeform::parseDocument(doc, "doc.json"), Contains("doc.json") && Contains("nested deeper"));
    const std::string lattice = "{\"format\":\"freeform\",\"version\":1,\"objects\":[{\"name\":\"l\",\"type\":\"lattice\",\"degree\":" +
                                nested(40000, "1,1,1") + "}]}";
    CHECK_THROWS_WITH(freeform::parseDocument(lattice, "lat.json"), Contains("nested deeper"));

    // A glTF extras member (the JSON span locator recursed on depth).
    std::string g = gltf("", "");
    g.insert(g.size() - 1, ",\"extras\":" + nested(60000));
    writeText(tmp("deep.gltf"), g);
    CHECK_THROWS_WITH(MeshFile::read(tmp("deep.gltf")), Contains("deep.gltf") && Contains("nested deeper"));
}

TEST_CASE("The JSON gate says where: the path to the value nested too deep or the object repeating a key", "[hardening][json]")
{
    // Hand-written locations: the path a reader would follow, its first 8 components only.
    const std::string deepDoc = "{\"format\":\"freeform\",\"version\":1,\"objects\":[{\"name\":\"c\"},{\"name\":\"d\",\"editor\":{\"m\":" +
                                nested(300) + "}}]}";
    CHECK_THROWS_WITH(freeform::checkJsonText(deepDoc, "d.json"),
                      Contains("d.json: values are nested deeper than 256 levels (at objects[1].editor.m[0][0][0][0]...)"));
    CHECK_THROWS_WITH(freeform::checkJsonText("[1, [2, {\"x\": {\"k\": 1, \"k\": 2}}]]", "k.json"),
                      Contains("k.json: the key \"k\" appears twice in one object (at [1][1].x)"));
    // At the top level there is no path to give.
    CHECK_THROWS_WITH(freeform::checkJsonText("{\"k\": 1, \"k\": 2}", "top.json"), Equals("top.json: the key \"k\" appears twice in one object"));
}

TEST_CASE("formatDocument gates editor members held as text: an error naming the object, not a stack overflow", "[hardening][json]")
{
    // A Document built in memory (the editor's tools, the Python bindings) carries each editor
    // member as text; nlohmann's dump of a tree 100,000 deep recursed past the stack (SIGSEGV).
    freeform::Document doc;
    freeform::DocumentObject o;
    o.name = "curve one";
    o.data = freeform::BezierCurveData{Eigen::MatrixXd::Identity(2, 2)};
    o.editor = "{\"a\":" + nested(100000) + "}";
    doc.objects.push_back(o);
    CHECK_THROWS_WITH(freeform::formatDocument(doc), Contains("object \"curve one\".editor") && Contains("nested deeper than 256"));
    doc.objects[0].editor = R"({"visible": false, "visibl\u0065": true})";
    CHECK_THROWS_WITH(freeform::formatDocument(doc), Contains("object \"curve one\".editor") && Contains("\"visible\" appears twice"));
    doc.objects[0].editor = R"({"visible": false})";
    doc.editor = "{\"display\": " + nested(100000) + "}";
    CHECK_THROWS_WITH(freeform::formatDocument(doc), Contains("editor: values are nested deeper than 256 levels (at display"));
    doc.editor.clear();
    // A valid one still writes and reads back.
    CHECK(freeform::parseDocument(freeform::formatDocument(doc), "back.json").object("curve one").editor == R"({"visible":false})");
}

TEST_CASE("JSON keys: duplicates are refused, escaped keys are the same key", "[hardening][json]")
{
    CHECK_THROWS_WITH(freeform::parseDocument("{\"format\":\"freeform\",\"version\":1,\"version\":1,\"objects\":[]}", "dup.json"),
                      Contains("dup.json") && Contains("\"version\" appears twice"));
    CHECK_THROWS_WITH(freeform::checkJsonText("{\"a\":1,\"\\u0061\":2}", "esc.json"), Contains("\"a\" appears twice"));
    CHECK_NOTHROW(freeform::checkJsonText("[{\"a\":1},{\"a\":2}]", "two.json"));

    // A glTF whose keys are written with escapes: read the same, and when positions move the
    // accessor's min/max (an escaped key too) are rewritten.
    std::string g = gltf(",\"min\":[0,0,0],\"m\\u0061x\":[1,1,0]", "");
    g.replace(g.find("\"accessors\""), 11, "\"\\u0061ccessors\"");
    writeText(tmp("esc.gltf"), g);
    MeshFile file = MeshFile::read(tmp("esc.gltf"));
    REQUIRE(file.positions().cols() == 3);
    file.positions().row(0).array() += 2.0;
    file.write(tmp("esc_out.gltf"));
    const std::string written = slurp(tmp("esc_out.gltf"));
    CHECK_THAT(written, Contains("[2, 0, 0]"));
    CHECK_THAT(written, Contains("[3, 1, 0]"));
}

TEST_CASE("limitNormal with degrees that sum past the binomial table", "[hardening][surface]")
{
    // A flat quarter disc of degree (40, 40) whose edge u = 0 collapses to the origin: the normal
    // there comes from limitNormal (orders up to m + n - 1 = 79) and must be the plane's, +-z.
    const int m = 40, n = 40;
    freeform::BezierSurface<double, 3>::Points points(3, (m + 1) * (n + 1));
    for (int i = 0; i <= m; ++i)
        for (int j = 0; j <= n; ++j) {
            const double r = double(i) / m, a = std::numbers::pi / 2 * double(j) / n;
            points.col(i * (n + 1) + j) = Eigen::Vector3d(r * std::cos(a), r * std::sin(a), 0.0);
        }
    const freeform::BezierSurface<double, 3> s(m, n, points);
    for (double v : {0.1, 0.5, 0.9}) {
        const Eigen::Vector3d normal = s.normal(0.0, v);
        CHECK(std::abs(std::abs(normal.z()) - 1.0) < 1e-9);
        CHECK(std::abs(normal.x()) + std::abs(normal.y()) < 1e-9);
    }
}

TEST_CASE("glTF buffer URIs resolve only inside the file's folder", "[hardening][gltf]")
{
    const std::string outside = tmp("outside.bin");
    writeText(outside, triangleBuffer());
    fs::create_directories(tmp("inner"));
    const auto attempt = [&](const std::string& uri) {
        writeText(tmp("inner/u.gltf"), gltf("", "", uri));
        try {
            (void)MeshFile::read(tmp("inner/u.gltf"));
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    CHECK_THAT(attempt(outside), Contains("absolute path") && Contains("own folder"));
    CHECK_THAT(attempt("../outside.bin"), Contains("leaves the folder"));
    CHECK_THAT(attempt("/dev/zero"), Contains("absolute path"));
    CHECK_THAT(attempt("file:///dev/zero"), Contains("scheme"));
    writeText(tmp("inner/in.bin"), triangleBuffer() + std::string(1000, 'x')); // longer than byteLength
    CHECK(attempt("in.bin") == "accepted");
    std::error_code ec;
    fs::remove(tmp("inner/zero.bin"), ec);
    fs::create_symlink("/dev/zero", tmp("inner/zero.bin"), ec);
    if (!ec) CHECK_THAT(attempt("zero.bin"), Contains("not a regular file"));
}

// ------------------------------------------------------------------ 2. resource bombs

TEST_CASE("Header counts beyond what the file can hold are refused before allocating", "[hardening][bombs]")
{
    const std::string off = "OFF\n500000000 0 0\n"; // 19 bytes
    CHECK_THAT(readError("bomb.off", off), Contains("bomb.off") && Contains("500000000 vertices"));
    std::string ply = "ply\nformat ascii 1.0\nelement vertex 300000000\nproperty float x\nproperty float y\nproperty float z\n"
                      "property float nx\nproperty float ny\nproperty float nz\nend_header\n0 0 0 0 0 1\n";
    CHECK_THAT(readError("bomb.ply", ply), Contains("bomb.ply") && Contains("300000000 'vertex' elements"));
    std::string bin = "ply\nformat binary_little_endian 1.0\nelement vertex 2147483647\nproperty float x\nproperty float y\n"
                      "property float z\nend_header\n";
    CHECK_THAT(readError("bomb_bin.ply", bin), Contains("2147483647 'vertex' elements"));
    // A list count that the rest of the file cannot hold.
    std::string list = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                       "element face 1\nproperty list uint int vertex_indices\nend_header\n";
    for (int i = 0; i < 9; ++i) putBytes(list, float(i % 2));
    putBytes(list, std::uint32_t{4000000000u});
    CHECK_THAT(readError("bomb_list.ply", list), Contains("list count of 4000000000"));

    if (kAsan) {
        WARN("memory caps skipped under AddressSanitizer (it reserves terabytes of address space)");
        return;
    }
    for (const auto& [name, text] : {std::pair{std::string("cap.off"), off}, std::pair{std::string("cap.ply"), ply},
                                     std::pair{std::string("cap_bin.ply"), bin}, std::pair{std::string("cap_list.ply"), list}}) {
        writeText(tmp(name), text);
        const std::string path = tmp(name);
        INFO(name);
        CHECK(withinMemory(50, [&] {
            try {
                (void)MeshFile::read(path);
            } catch (const Error&) {
            }
        }));
    }
}

TEST_CASE("Property-less PLY elements with huge counts take no time", "[hardening][bombs]")
{
    const std::string ply = "ply\nformat ascii 1.0\nelement junk 2147483647\nelement vertex 3\nproperty float x\nproperty float y\n"
                            "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                            "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    writeText(tmp("junk.ply"), ply);
    CHECK(MeshFile::read(tmp("junk.ply")).positions().cols() == 3);
}

// ------------------------------------------------------------------ 3. silent acceptance

TEST_CASE("Not a text mesh: a JPEG, random bytes, UTF-16 named .obj", "[hardening][obj]")
{
    CHECK_THAT(readError("photo.obj", std::string("\xFF\xD8\xFF\xE0\0\x10JFIF\0", 11)), Contains("photo.obj"));
    CHECK_THAT(readError("utf16.obj", std::string("\xFF\xFEv\0 \0\x31\0", 8)), Contains("UTF-16"));
    CHECK_THAT(readError("noise.obj", "\x93\xA7\x01\x7F garbage\n"), Contains("noise.obj:1") && Contains("not an OBJ statement"));
}

TEST_CASE("One validation path: what readPolygonMesh refuses, MeshFile::read refuses", "[hardening][validation]")
{
    const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    // NaN texture coordinates (OBJ).
    CHECK_THAT(readError("nan_uv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt nan 0\nf 1/1 2/1 3/1\n"), Contains("nan_uv.obj"));
    // inf and out-of-range colours.
    CHECK_THAT(readError("inf_color.ply", head + "property float red\nproperty float green\nproperty float blue\nend_header\n"
                                                 "0 0 0 inf 0 0\n1 0 0 0 0 0\n0 1 0 0 0 0\n"),
               Contains("colour"));
    CHECK_THAT(readError("big_color.off", "COFF\n3 1 0\n0 0 0 900 0 0 255\n1 0 0 0 0 0 255\n0 1 0 0 0 0 255\n3 0 1 2\n"),
               Contains("colour"));
    // A uchar list count of 1000 and an ASCII count of 1e300 (an undefined cast before).
    CHECK_THAT(readError("uchar.ply", head + "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                             "0 0 0\n1 0 0\n0 1 0\n1000 0 1 2\n"),
               Contains("out of range for its type uchar"));
    CHECK_THAT(readError("huge.ply", head + "element face 1\nproperty list int int vertex_indices\nend_header\n"
                                            "0 0 0\n1 0 0\n0 1 0\n1e300 0 1 2\n"),
               Contains("huge.ply:") && Contains("out of range"));
    // Index accessors marked normalized.
    std::string g = gltf("", "");
    g.replace(g.find("\"attributes\":{\"POSITION\":0}"), 27, "\"attributes\":{\"POSITION\":0},\"indices\":1");
    std::string idx;
    putBytes(idx, std::uint16_t{0});
    putBytes(idx, std::uint16_t{1});
    putBytes(idx, std::uint16_t{2});
    g.replace(g.find("\"accessors\":["), 13,
              "\"accessors\":[{\"bufferView\":0,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\",\"normalized\":true},");
    // accessor 0 is now the index accessor over the position bytes; POSITION is accessor 1.
    g.replace(g.find("\"POSITION\":0"), 12, "\"POSITION\":1");
    g.replace(g.find("\"indices\":1"), 11, "\"indices\":0");
    CHECK_THAT(readError("norm.gltf", g), Contains("normalized"));
}

// ------------------------------------------------------------------ 4. real files from the wild

TEST_CASE("A PLY header line written by Blender 2.47 is kept as a comment", "[hardening][ply]")
{
    const std::string ply = "ply\nformat ascii 1.0\nCreated by Blender3D 247 - www.blender.org, source file: 'cube.blend'\n"
                            "element vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
                            "property list uchar uint vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    writeText(tmp("blender.ply"), ply);
    // The reader says so through the caller's warning handler (freeform/core/warning.h), once; the
    // library prints nothing itself.
    std::vector<std::string> warnings;
    const MeshFile file = [&warnings] {
        const ScopedWarningHandler capture([&warnings](const std::string& m) { warnings.push_back(m); });
        return MeshFile::read(tmp("blender.ply"));
    }();
    REQUIRE(warnings.size() == 1);
    CHECK_THAT(warnings[0], Contains("blender.ply") && Contains("unknown header line 'Created' kept as a comment"));
    CHECK(file.positions().cols() == 3);
    file.write(tmp("blender_out.ply"));
    CHECK(slurp(tmp("blender_out.ply")) == ply);
}

TEST_CASE("The leniency table of docs/mesh-io.md: OFF variants, OBJ statements passed through, glTF extensions", "[hardening][leniency]")
{
    // OFF variants (Geomview's prefixes in the order ST C N): read with the hand values below and
    // written back byte for byte; other dimensions are refused by name.
    struct Variant {
        const char* name;
        const char* vertices;
        bool normals, texcoords;
    };
    const Variant variants[] = {
        {"NOFF", "0 0 0 0 0 1\n2 0 0 0 0 1\n0 3 0 0 0 1\n", true, false},
        {"CNOFF", "0 0 0 0 0 1 1 0 0 1\n2 0 0 0 0 1 0 1 0 1\n0 3 0 0 0 1 0 0 1 1\n", true, false},
        {"STOFF", "0 0 0 0.25 0.5\n2 0 0 1 0.5\n0 3 0 0.25 1\n", false, true},
        {"STCOFF", "0 0 0 255 0 0 0.25 0.5\n2 0 0 0 255 0 1 0.5\n0 3 0 0 0 255 0.25 1\n", false, true},
    };
    for (const Variant& v : variants) {
        INFO(v.name);
        const std::string text = std::string(v.name) + "\n# a comment after the keyword\n3 1 0\n" + v.vertices + "# and between\n3 0 1 2\n";
        const std::string name = std::string("variant_") + v.name + ".off";
        writeText(tmp(name), text);
        MeshFile file = MeshFile::read(tmp(name));
        REQUIRE(file.positions().cols() == 3);
        CHECK(file.positions().col(1) == Eigen::Vector3d(2, 0, 0));
        CHECK(file.positions().col(2) == Eigen::Vector3d(0, 3, 0));
        if (v.normals) {
            REQUIRE(file.normals().cols() == 3);
            CHECK(file.normals().col(2) == Eigen::Vector3d(0, 0, 1));
        }
        if (v.texcoords) {
            const freeform::PolygonMesh mesh = file.toPolygonMesh();
            REQUIRE(mesh.texcoords.cols() == 3);
            CHECK(mesh.texcoords.col(1) == Eigen::Vector2d(1, 0.5));
        }
        file.write(tmp("back_" + name));
        CHECK(slurp(tmp("back_" + name)) == text);
    }
    CHECK_THAT(readError("four.off", "4OFF\n1 0 0\n0 0 0 0\n"), Contains("four.off") && Contains("4OFF"));
    CHECK_THAT(readError("ndim.off", "nOFF\n4\n1 0 0\n0 0 0 0\n"), Contains("ndim.off") && Contains("nOFF"));

    // OBJ statements the reader does not use are passed through unchanged.
    const std::string obj = "mtllib m.mtl\no thing\ng part\ns 1\nusemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvp 0.5\n"
                            "cstype bezier\ndeg 1\nl 1 2\np 3\nf 1 2 3\nxvendor_ext 1 2 3\n";
    writeText(tmp("pass.obj"), obj);
    MeshFile o = MeshFile::read(tmp("pass.obj"));
    CHECK(o.positions().cols() == 3);
    o.positions()(2, 1) = 0.5;
    o.write(tmp("pass_back.obj"));
    std::string expected = obj;
    expected.replace(expected.find("v 1 0 0"), 7, "v 1 0 0.5");
    CHECK(slurp(tmp("pass_back.obj")) == expected);

    // glTF: unknown extensions are kept; extensions that change the geometry, if required, are refused by name.
    for (const char* ext : {"KHR_draco_mesh_compression", "EXT_meshopt_compression", "KHR_mesh_quantization"}) {
        INFO(ext);
        std::string g = gltf("", "");
        g.insert(g.size() - 1, std::string(",\"extensionsUsed\":[\"") + ext + "\"],\"extensionsRequired\":[\"" + ext + "\"]");
        CHECK_THAT(readError("ext.gltf", g), Contains("ext.gltf") && Contains(ext));
    }
    std::string g = gltf("", "");
    g.insert(g.size() - 1, ",\"extensionsUsed\":[\"VENDOR_thing\"],\"extensions\":{\"VENDOR_thing\":{\"x\":1}}");
    writeText(tmp("vendor.gltf"), g);
    MeshFile vendor = MeshFile::read(tmp("vendor.gltf"));
    CHECK(vendor.positions().cols() == 3);
    vendor.write(tmp("vendor_back.gltf"));
    CHECK_THAT(slurp(tmp("vendor_back.gltf")), Contains("VENDOR_thing") && Contains("\"x\""));
}

// ------------------------------------------------------------------ CLI: one error line, no JSON, no signal

TEST_CASE("The CLI on hostile meshes: exit 1, one error line naming the file, nothing on stdout", "[hardening][cli]")
{
    writeText(tmp("cli_bomb.off"), "OFF\n500000000 0 0\n");
    writeText(tmp("cli_deep.gltf"), [] {
        std::string g = gltf("", "");
        g.insert(g.size() - 1, ",\"extras\":" + nested(60000));
        return g;
    }());
    writeText(tmp("cli_stride.gltf"), gltf("", ",\"byteStride\":4294967292"));
    for (const char* name : {"cli_bomb.off", "cli_deep.gltf", "cli_stride.gltf"}) {
        INFO(name);
        const auto r = freeform::test::cli("info '" + tmp(name) + "'");
        CHECK(r.status == 1);
        CHECK(r.out.empty());
        CHECK_THAT(r.err, Contains("error:") && Contains(name));
    }
    // A points file of `freeform interpolate` nested 100,000 deep; the output must not appear.
    writeText(tmp("cli_deep_points.json"), "{\"points\": " + nested(100000) + "}");
    std::error_code ec;
    fs::remove(tmp("cli_deep_out.json"), ec);
    const auto r = freeform::test::cli("interpolate '" + tmp("cli_deep_points.json") + "' -o '" + tmp("cli_deep_out.json") + "'");
    CHECK(r.status == 1);
    CHECK(r.out.empty());
    CHECK_THAT(r.err, Contains("error:") && Contains("cli_deep_points.json") && Contains("nested deeper than 256"));
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK_FALSE(fs::exists(tmp("cli_deep_out.json")));
}

TEST_CASE("info and ffd say which path a mesh took: Assimp (not lossless) or the lossless readers", "[hardening][cli][assimp]")
{
    const std::string box = "/usr/share/assimp/models/FBX/box.fbx";
    if (!fs::exists(box)) {
        WARN("assimp-testmodels is not installed: the Assimp path of info and ffd was not tried");
        return;
    }
    const std::string cube = std::string(FREEFORM_SOURCE_DIR) + "/data/meshes/cube.obj";
    // info: "reader" first, only when the file went through Assimp (docs/cli.md).
    const auto viaAssimp = freeform::test::cli("info '" + box + "'");
    REQUIRE(viaAssimp.status == 0);
    const nlohmann::ordered_json a = nlohmann::ordered_json::parse(viaAssimp.out);
    CHECK(a.begin().key() == "reader");
    CHECK(a["reader"] == "assimp (not lossless)");
    const auto lossless = freeform::test::cli("info '" + cube + "'");
    REQUIRE(lossless.status == 0);
    CHECK_FALSE(nlohmann::json::parse(lossless.out).contains("reader"));
    // ffd: "reader" always.
    REQUIRE(freeform::test::cli("lattice --fit '" + box + "' -o '" + tmp("box_lattice.json") + "'").status == 0);
    const auto deformed = freeform::test::cli("ffd '" + box + "' --lattice '" + tmp("box_lattice.json") + "' -o '" + tmp("box_out.ply") + "'");
    INFO(deformed.err);
    REQUIRE(deformed.status == 0);
    CHECK(nlohmann::json::parse(deformed.out)["reader"] == "assimp (not lossless)");
    REQUIRE(freeform::test::cli("lattice --fit '" + cube + "' -o '" + tmp("cube_lattice.json") + "'").status == 0);
    const auto plain = freeform::test::cli("ffd '" + cube + "' --lattice '" + tmp("cube_lattice.json") + "' -o '" + tmp("cube_out.obj") + "'");
    REQUIRE(plain.status == 0);
    CHECK(nlohmann::json::parse(plain.out)["reader"] == "freeform (lossless)");
}

// ------------------------------------------------------------------ fuzz findings

TEST_CASE("Every input the fuzzers found reads to an Error or a mesh, never a crash", "[hardening][regressions]")
{
    const fs::path dir = fs::path(FREEFORM_SOURCE_DIR) / "tests" / "regressions";
    int count = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        if (name == "README.md") continue;
        ++count;
        INFO(name);
        // The file name says the reader: TARGET-anything.EXT (fuzz/README.md).
        const std::string target = name.substr(0, name.find('-'));
        const std::string text = slurp(entry.path().string());
        try {
            if (target == "document") (void)freeform::formatDocument(freeform::parseDocument(text, name));
            else if (target == "bpt") (void)freeform::formatBpt(freeform::parseBpt(text, name));
            else if (target == "objfreeform") (void)freeform::formatObjFreeform(freeform::parseObjFreeform(text, name));
            else if (target == "cage") {
                const freeform::SubdivisionCage cage = freeform::readCage(entry.path().string());
                const freeform::SubdivisionSurface surface(cage, freeform::defaultScheme(cage.mesh));
                (void)surface;
            }
            else {
                const MeshFile file = MeshFile::read(entry.path().string());
                file.write(tmp("regression_out." + entry.path().extension().string().substr(1)));
            }
        } catch (const Error&) {
        }
    }
    CHECK(count >= 3); // the three findings of issue 16 (tests/regressions/README.md); more may follow
}

// ------------------------------------------------------------------ subdivision cages from the wild

namespace {

/// Runs f with the process's stdout (fd 1) captured; returns what was printed there.
template <typename F>
std::string capturedStdout(F&& f)
{
    std::fflush(stdout);
    const std::string file = tmp("stdout.txt");
    const int saved = dup(1);
    FILE* sink = std::fopen(file.c_str(), "w");
    dup2(fileno(sink), 1);
    try {
        f();
    } catch (...) {
    }
    std::fflush(stdout);
    dup2(saved, 1);
    close(saved);
    std::fclose(sink);
    return slurp(file);
}

std::string squareCage(const std::string& tags)
{
    // A 3 x 3 grid of quads (16 vertices), 0-based index of vertex (i, j) = 4 j + i.
    std::string obj;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) obj += "v " + std::to_string(i) + " " + std::to_string(j) + " 0\n";
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            const int a = 4 * j + i + 1;
            obj += "f " + std::to_string(a) + " " + std::to_string(a + 1) + " " + std::to_string(a + 5) + " " + std::to_string(a + 4) + "\n";
        }
    return obj + tags;
}

} // namespace

TEST_CASE("OpenSubdiv's shape tags: read where OpenSubdiv acts on them, refused by name otherwise", "[hardening][subdivision]")
{
    const auto cage = [&](const std::string& name, const std::string& tags) {
        writeText(tmp(name), squareCage(tags));
        return freeform::readCage(tmp(name));
    };
    const freeform::SubdivisionCage holes = cage("hole.obj", "t hole 1/0/0 4\n");
    REQUIRE(holes.holes == std::vector<int>{4});
    const freeform::SubdivisionSurface withHole(holes, freeform::SubdivisionScheme::Catmark);
    CHECK_FALSE(withHole.hasLimitSurface(4));
    CHECK(withHole.hasLimitSurface(0));

    // interpolateboundary 0 = none: the boundary faces lose their limit surface, the centre keeps it.
    const freeform::SubdivisionCage none = cage("ib.obj", "t interpolateboundary 1/0/0 0\n");
    REQUIRE(none.boundary == freeform::BoundaryInterpolation::None);
    const freeform::SubdivisionSurface framed(none, freeform::SubdivisionScheme::Catmark);
    CHECK(framed.boundary() == freeform::BoundaryInterpolation::None);
    CHECK_FALSE(framed.hasLimitSurface(0));
    CHECK(framed.hasLimitSurface(4));
    CHECK_THROWS_WITH(freeform::SubdivisionSurface(none, freeform::SubdivisionScheme::Catmark, freeform::BoundaryInterpolation::EdgeAndCorner),
                      Contains("interpolateboundary"));

    CHECK(cage("chaikin.obj", "t creasemethod 0/0/1 chaikin\n").chaikin);
    CHECK(cage("smooth.obj", "t smoothtriangles 0/0/1 smooth\n").smoothTriangles);
    CHECK_THROWS_WITH(cage("fvp.obj", "t facevaryingpropagatecorners 1/0/0 1\n"), Contains("fvp.obj:26") && Contains("facevaryingpropagatecorners"));
    CHECK_THROWS_WITH(cage("bad_ib.obj", "t interpolateboundary 1/0/0 7\n"), Contains("bad_ib.obj:26"));
    CHECK_THROWS_WITH(cage("bad_hole.obj", "t hole 1/0/0 9\n"), Contains("hole face 9"));
    CHECK_THROWS_WITH(cage("bomb_tag.obj", "t crease 999999/1 0 1 2\n"), Contains("more values than the line holds"));
}

TEST_CASE("OpenSubdiv never prints on stdout", "[hardening][subdivision]")
{
    // A crease tag on an edge the cage does not have is refused before OpenSubdiv sees it (Debian's
    // 3.5.0 reads uninitialised memory there), and OpenSubdiv's own messages go to stderr.
    writeText(tmp("nocrease.obj"), squareCage("t crease 2/1 0 5 10\n"));
    std::string out = capturedStdout([&] {
        const freeform::SubdivisionCage c = freeform::readCage(tmp("nocrease.obj"));
        CHECK_THROWS_WITH(freeform::SubdivisionSurface(c, freeform::SubdivisionScheme::Catmark), Contains("no such edge"));
    });
    CHECK(out.empty());

    // A vertex of valence 70,000 (a triangle fan): OpenSubdiv complains; not on stdout.
    freeform::SubdivisionCage fan;
    const int n = 70000;
    fan.mesh.positions.resize(3, n + 1);
    fan.mesh.positions.col(0).setZero();
    for (int i = 0; i < n; ++i) {
        const double a = 2 * std::numbers::pi * i / n;
        fan.mesh.positions.col(i + 1) = Eigen::Vector3d(std::cos(a), std::sin(a), 0);
    }
    for (int i = 0; i < n; ++i) {
        const int f[3] = {0, i + 1, (i + 1) % n + 1};
        fan.mesh.addFace(f, f + 3);
    }
    out = capturedStdout([&] { freeform::SubdivisionSurface s(fan, freeform::SubdivisionScheme::Loop); });
    CHECK(out.empty());
}

TEST_CASE("Results that overflow are an error, never null with exit 0", "[hardening][cli]")
{
    writeText(tmp("huge.json"), "{\"format\":\"freeform\",\"version\":1,\"objects\":[{\"name\":\"c\",\"type\":\"bezier_curve\","
                                "\"points\":[[0,0],[1e308,1e308],[-1e308,-1e308],[1e308,0]]}]}");
    const auto r = freeform::test::cli("eval '" + tmp("huge.json") + "' --object c --at 0.5 --derivatives 2");
    CHECK(r.status == 1);
    CHECK(r.out.empty());
    CHECK_THAT(r.err, Contains("not finite"));
}

TEST_CASE("continuity of tiny intervals and a lattice det past double range exit 1 naming the field", "[hardening][cli]")
{
    // Spline derivatives in the global parameter scale by 1/h^k on an interval of length h: with
    // h = 1e-110 the jumps of order 3 are of order 1e330 > DBL_MAX (about 1.8e308).
    const std::string spline = "{\"format\":\"freeform\",\"version\":1,\"objects\":[{\"name\":\"s\",\"type\":\"bezier_spline\","
                               "\"degree\":3,\"closed\":false,\"points\":[[0,0],[1,2],[3,2],[4,0],[5,-2],[7,-2],[8,0]],\"intervals\":";
    writeText(tmp("tiny.json"), spline + "[1e-110,2e-110]}]}");
    const auto r = freeform::test::cli("continuity '" + tmp("tiny.json") + "' --object s");
    CHECK(r.status == 1);
    CHECK(r.out.empty());
    CHECK_THAT(r.err, StartsWith("error: ") && Contains("jumps") && Contains("not finite"));
    // The same points on intervals [1, 2] (docs/format.md's example) are fine.
    writeText(tmp("unit.json"), spline + "[1,2]}]}");
    CHECK(freeform::test::cli("continuity '" + tmp("unit.json") + "' --object s").status == 0);

    // A trilinear lattice on the unit box whose points are the rest points scaled by c is p -> c p:
    // J = c I, det J = c^3. c = 1e110: det 1e330 overflows (the point, 0.5 c, and the partials, c,
    // do not); c = 1e100: det 1e300 is printed.
    auto lattice = [](const std::string& c) {
        std::string points;
        for (int i = 0; i < 2; ++i)
            for (int j = 0; j < 2; ++j)
                for (int k = 0; k < 2; ++k)
                    points += std::string(points.empty() ? "" : ",") + "[" + (i ? c : "0") + "," + (j ? c : "0") + "," + (k ? c : "0") + "]";
        return "{\"format\":\"freeform\",\"version\":1,\"objects\":[{\"name\":\"L\",\"type\":\"lattice\",\"degree\":[1,1,1],"
               "\"origin\":[0,0,0],\"axes\":[[1,0,0],[0,1,0],[0,0,1]],\"points\":[" + points + "]}]}";
    };
    writeText(tmp("det_huge.json"), lattice("1e110"));
    const auto d = freeform::test::cli("eval '" + tmp("det_huge.json") + "' --object L --at 0.5,0.5,0.5 --derivatives 1");
    CHECK(d.status == 1);
    CHECK(d.out.empty());
    CHECK_THAT(d.err, StartsWith("error: ") && Contains("det") && Contains("not finite"));
    // Without derivatives there is no det, and the point 0.5 c is finite.
    CHECK(freeform::test::cli("eval '" + tmp("det_huge.json") + "' --object L --at 0.5,0.5,0.5").status == 0);
    writeText(tmp("det_big.json"), lattice("1e100"));
    const auto ok = freeform::test::cli("eval '" + tmp("det_big.json") + "' --object L --at 0.5,0.5,0.5 --derivatives 1");
    REQUIRE(ok.status == 0);
    const double det = nlohmann::json::parse(ok.out)["derivatives"][0]["det"].get<double>();
    CHECK_THAT(det, WithinRel(1e300, 1e-12));
}

TEST_CASE("An empty mesh deforms to nothing; a face that repeats a vertex is named by its file", "[hardening][ffd]")
{
    freeform::LatticeData data;
    data.degree = {1, 1, 1};
    data.points.resize(3, 8);
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
            for (int k = 0; k < 2; ++k) data.points.col(i * 4 + j * 2 + k) = Eigen::Vector3d(i, j, k) * 1.5;
    const freeform::Lattice lattice = freeform::latticeFromData(data);

    writeText(tmp("empty.obj"), "# nothing but a comment\n");
    MeshFile empty = MeshFile::read(tmp("empty.obj"));
    CHECK_NOTHROW(freeform::deformMeshFile(lattice, empty));

    // info on a face that repeats a vertex: the topology's message now names the file too.
    writeText(tmp("repeat.obj"), "v 0.1 0.1 0.1\nv 0.5 0.1 0.1\nv 0.1 0.5 0.1\nf 1 1 2 3\n");
    const auto r = freeform::test::cli("info '" + tmp("repeat.obj") + "'");
    CHECK(r.status == 1);
    CHECK(r.out.empty());
    CHECK_THAT(r.err, Contains("repeat.obj") && Contains("twice"));
}

TEST_CASE("Integer PLY coordinates stay integers when written back", "[hardening][ply]")
{
    const std::string ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty int x\nproperty int y\nproperty int z\n"
                            "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n10 0 0\n0 10 0\n3 0 1 2\n";
    writeText(tmp("int.ply"), ply);
    MeshFile file = MeshFile::read(tmp("int.ply"));
    file.positions()(0, 1) = 12.6; // rounds to 13
    file.write(tmp("int_out.ply"));
    const std::string out = slurp(tmp("int_out.ply"));
    CHECK_THAT(out, Contains("\n13 0 0\n"));
    CHECK(MeshFile::read(tmp("int_out.ply")).positions()(0, 1) == 13.0);
    file.positions()(0, 1) = 3e9; // beyond int
    CHECK_THROWS_AS(file.write(tmp("int_out2.ply")), Error);
}

TEST_CASE("The warning handler: set, replaced, scoped, and nothing without one", "[hardening][warning]")
{
    std::vector<std::string> a, b;
    const WarningHandler before = setWarningHandler({});
    warn("dropped: no handler"); // nothing to call, nothing printed
    CHECK(!setWarningHandler([&a](const std::string& m) { a.push_back(m); }));
    warn("one");
    {
        const ScopedWarningHandler scoped([&b](const std::string& m) { b.push_back(m); });
        warn("two");
    }
    warn("three");
    CHECK(a == std::vector<std::string>{"one", "three"});
    CHECK(b == std::vector<std::string>{"two"});
    const WarningHandler mine = setWarningHandler(before);
    REQUIRE(mine);
    mine("four"); // the returned handler is the one that was set
    CHECK(a.back() == "four");
}

} // namespace test_hardening
