// Render tests (label "render": they need an X display; scripts/test.sh provides Xvfb). They run
// build/bin/freeform-editor --screenshot and look at the pixels:
//   - the teapot flat, Gouraud and Phong: three different images, each matching its stored
//     reference (editor/tests/reference/, 160x120) within a tolerance for Mesa's rounding, and a
//     render with flipped normals that must NOT match (so the comparison can fail);
//   - the silhouette's bounding box equals the teapot's bounding box projected with
//     core/transform.h (an independent computation from the patches, not from the renderer);
//   - a file that cannot be read: exit 1, "error:" on stderr, no PNG.
// FREEFORM_UPDATE_REFERENCES=1 rewrites the references (review them before committing).

#include <catch2/catch.hpp>

#include <freeform/core/transform.h>
#include <freeform/surface/patch_complex.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>

#include "freeform/io/bpt.h"
#include "image_compare.h"
#include "support/editor_process.h"
#include "support/process.h"

namespace test_render {

using namespace freeform;
using freeform::test::compare;
using freeform::test::loadPng;
using freeform::test::matches;

namespace {

namespace fs = std::filesystem;

const std::string kSource = FREEFORM_SOURCE_DIR;
const std::string kTmp = FREEFORM_TEST_TMP;

/// Concatenation through a stream (g++ 12 -O3 warns falsely, -Wrestrict, on some string + chains).
template <typename... Parts>
std::string cat(const Parts&... parts)
{
    std::ostringstream s;
    (s << ... << parts);
    return s.str();
}

/// Runs the editor (support/editor_process.h: LeakSanitizer off for the child, a refused X
/// connection retried).
test::ProcessResult editor(const std::string& arguments) { return test::runEditorBinary(arguments); }

/// The teapot document of the shading tests: teapot.bpt imported, a fixed camera from the front
/// right above (the iso direction, closer than a fit) so that the teapot fills the picture.
std::string teapotDocument()
{
    const std::string doc = kTmp + "/render_teapot.json";
    static bool written = false; // once per run, never a stale file from an earlier build
    if (written) return doc;
    written = true;
    const auto r = editor("'" + kSource + "/data/teapot.bpt' --save '" + doc + ".tmp'");
    INFO(r.err);
    REQUIRE(r.status == 0);
    nlohmann::ordered_json j = nlohmann::ordered_json::parse(test::slurp(doc + ".tmp"));
    // The iso view: back = (1, -1, 1)/sqrt(3), right = (1, 1, 0)/sqrt(2), up = back x right.
    const Eigen::Vector3d back = Eigen::Vector3d(1, -1, 1).normalized(), right = Eigen::Vector3d(1, 1, 0).normalized();
    Eigen::Matrix3d frame;
    frame << right, back.cross(right), back;
    const Eigen::Quaterniond q(frame);
    j["editor"]["camera"] = {{"target", {0.2, 0.0, 1.4}}, {"distance", 9.0}, {"orientation", {q.w(), q.x(), q.y(), q.z()}},
                             {"fovy", 35.0}, {"projection", "perspective"}, {"orbit", "turntable"}};
    test::writeText(doc, j.dump(2));
    return doc;
}

/// The teapot at 160x120, coarsely tessellated (4 x 4 quads per patch) so that the shading modes
/// differ visibly.
std::string teapotShot(const std::string& name, const std::string& extra)
{
    const std::string out = cat(kTmp, "/render_", name, ".png");
    fs::remove(out);
    const auto r = editor(cat("'", teapotDocument(), "' --screenshot '", out, "' --size 160x120 --no-ui --segments 4 ", extra));
    INFO(r.err);
    REQUIRE(r.status == 0);
    REQUIRE(fs::exists(out));
    return out;
}

void checkAgainstReference(const std::string& shot, const std::string& referenceName)
{
    const std::string reference = kSource + "/editor/tests/reference/" + referenceName;
    if (const char* update = std::getenv("FREEFORM_UPDATE_REFERENCES"); update && std::string(update) == "1")
        fs::copy_file(shot, reference, fs::copy_options::overwrite_existing);
    INFO("reference " << reference << " (FREEFORM_UPDATE_REFERENCES=1 writes it)");
    const auto expected = loadPng(reference);
    REQUIRE_FALSE(expected.empty());
    const auto d = compare(loadPng(shot), expected);
    INFO(referenceName << ": mean difference " << d.meanAbs << ", pixels off by more than 32: " << d.badFraction * 100 << "%");
    CHECK(matches(d));
}

} // namespace

TEST_CASE("flat, Gouraud and Phong shading give three different images, each as its reference", "[render]")
{
    const std::string flat = teapotShot("flat", "--shading flat");
    const std::string gouraud = teapotShot("gouraud", "--shading gouraud");
    const std::string phong = teapotShot("phong", "--shading phong");

    checkAgainstReference(flat, "teapot-flat.png");
    checkAgainstReference(gouraud, "teapot-gouraud.png");
    checkAgainstReference(phong, "teapot-phong.png");

    // Pairwise different: many pixels change, by more than the tolerance allows.
    const auto f = loadPng(flat), g = loadPng(gouraud), p = loadPng(phong);
    for (const auto& [a, b, what] : {std::tuple{&f, &g, "flat/Gouraud"}, std::tuple{&g, &p, "Gouraud/Phong"},
                                     std::tuple{&f, &p, "flat/Phong"}}) {
        const auto d = compare(*a, *b);
        INFO(what << ": " << d.changedPixels << " pixels differ by more than 8 levels, mean " << d.meanAbs
                  << ", off by more than 32: " << d.badFraction * 100 << "%");
        CHECK(d.changedPixels > 100);
        // The reference check tells the modes apart: one mode's image does not pass as another's.
        CHECK_FALSE(matches(d));
    }
}

TEST_CASE("the reference comparison fails for wrong shading (normals flipped)", "[render]")
{
    for (const std::string mode : {"flat", "gouraud", "phong"}) {
        const std::string shot = teapotShot("flipped_" + mode, "--shading " + mode + " --flip-normals");
        const auto d = compare(loadPng(shot), loadPng(kSource + "/editor/tests/reference/teapot-" + mode + ".png"));
        INFO(mode << " with flipped normals: mean difference " << d.meanAbs << ", off by more than 32: " << d.badFraction * 100 << "%");
        CHECK_FALSE(matches(d));
    }
}

TEST_CASE("Blinn-Phong and Phong specular differ", "[render]")
{
    const auto phong = loadPng(teapotShot("spec_phong", "--shading phong --lighting phong"));
    const auto blinn = loadPng(teapotShot("spec_blinn", "--shading phong --lighting blinn"));
    CHECK(compare(phong, blinn).changedPixels > 20);
}

TEST_CASE("the silhouette matches the teapot's bounding box projected with transform.h", "[render]")
{
    // A document with the teapot, a fixed orthographic front camera, black background, no grid.
    const std::string doc = kTmp + "/silhouette.json";
    {
        const auto r = editor("'" + kSource + "/data/teapot.bpt' --save '" + doc + "'");
        INFO(r.err);
        REQUIRE(r.status == 0);
    }
    nlohmann::ordered_json j = nlohmann::ordered_json::parse(test::slurp(doc));
    const double s = std::sqrt(0.5);
    // Front view: camera right = +x, up = +z, looking along +y: the rotation by 90 degrees about x.
    j["editor"]["camera"] = {{"target", {0.1, 0.0, 1.5}}, {"distance", 10.0}, {"orientation", {s, s, 0.0, 0.0}},
                             {"fovy", 40.0}, {"projection", "orthographic"}, {"orbit", "turntable"}};
    j["editor"]["display"]["grid"] = false;
    j["editor"]["display"]["axes"] = false;
    j["editor"]["display"]["background"] = {0.0, 0.0, 0.0};
    j["editor"]["display"]["samples"] = 0;
    test::writeText(doc, j.dump(2));

    const int width = 320, height = 240;
    const std::string shot = kTmp + "/silhouette.png";
    fs::remove(shot);
    const auto r = editor("'" + doc + "' --screenshot '" + shot + "' --size 320x240 --no-ui --segments 48");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const auto image = loadPng(shot);
    REQUIRE(image.width == width);

    int minX = width, maxX = -1, minY = height, maxY = -1;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const unsigned char* p = image.at(x, y);
            if (std::max({p[0], p[1], p[2]}) > 3) {
                minX = std::min(minX, x), maxX = std::max(maxX, x);
                minY = std::min(minY, y), maxY = std::max(maxY, y);
            }
        }
    REQUIRE(maxX >= 0);

    // The same camera built by hand: eye = target - 10 y, orthographic with half-height
    // 10 tan(20 degrees), near/far wide enough; then every surface point projected to a pixel.
    const Eigen::Vector3d target(0.1, 0, 1.5), eye = target - 10.0 * Eigen::Vector3d::UnitY();
    const double h = 10.0 * std::tan(20.0 * 3.14159265358979323846 / 180.0), a = double(width) / height;
    const Eigen::Matrix4d full = viewport<double>(0, 0, width, height) * orthographic<double>(-a * h, a * h, -h, h, 1, 20) *
                                 lookAt<double>(eye, target, Eigen::Vector3d::UnitZ());
    double lo[2] = {1e9, 1e9}, hi[2] = {-1e9, -1e9};
    for (const Patch& patch : readBpt(kSource + "/data/teapot.bpt").patches)
        for (int i = 0; i <= 60; ++i)
            for (int k = 0; k <= 60; ++k) {
                const Eigen::Vector3d w = transformPoint<double>(full, patch.evaluate(i / 60.0, k / 60.0));
                for (int c = 0; c < 2; ++c) lo[c] = std::min(lo[c], w[c]), hi[c] = std::max(hi[c], w[c]);
            }
    // Pixel (x, row) is covered when its centre (x + 1/2, height - row - 1/2) is inside.
    const double expectMinX = std::ceil(lo[0] - 0.5), expectMaxX = std::floor(hi[0] - 0.5);
    const double expectMinRow = height - 1 - std::floor(hi[1] - 0.5), expectMaxRow = height - 1 - std::ceil(lo[1] - 0.5);
    INFO("rendered x " << minX << ".." << maxX << ", rows " << minY << ".." << maxY << "; projected x " << expectMinX << ".."
                       << expectMaxX << ", rows " << expectMinRow << ".." << expectMaxRow);
    CHECK(std::abs(minX - expectMinX) <= 1);
    CHECK(std::abs(maxX - expectMaxX) <= 1);
    CHECK(std::abs(minY - expectMinRow) <= 1);
    CHECK(std::abs(maxY - expectMaxRow) <= 1);
}

TEST_CASE("a file that cannot be read gives exit 1, an error line and no PNG", "[render]")
{
    const std::string shot = kTmp + "/corrupt.png";
    struct Case {
        const char* name;
        const char* text;
    };
    for (const Case& c : {Case{"corrupt.json", "{\"format\": \"freeform\", \"version\": 1, \"objects\": [ {"},
                          Case{"wrong.json", "{\"format\": \"freeform\", \"version\": 1, \"objects\": [{\"name\": \"c\", \"type\": \"bezier_curve\", \"points\": [[0, 0], [1]]}]}"},
                          Case{"badcamera.json", "{\"format\": \"freeform\", \"version\": 1, \"objects\": [], \"editor\": {\"camera\": {\"distance\": -1}}}"},
                          Case{"corrupt.bpt", "2\n3 3\n0 0 0\n"}, Case{"corrupt.obj", "v 0 0 0\nv 1 0\nf 1 2 3\n"}}) {
        const std::string input = kTmp + "/" + c.name;
        test::writeText(input, c.text);
        fs::remove(shot);
        const auto r = editor("'" + input + "' --screenshot '" + shot + "'");
        INFO(c.name << ": " << r.err);
        CHECK(r.status == 1);
        CHECK(r.err.rfind("error: ", 0) == 0);
        CHECK(r.out.empty());
        CHECK_FALSE(fs::exists(shot));
    }
    fs::remove(shot);
    const auto missing = editor("'" + kTmp + "/does-not-exist.json' --screenshot '" + shot + "'");
    CHECK(missing.status == 1);
    CHECK_FALSE(fs::exists(shot));
}

TEST_CASE("the demo scene renders with the panels", "[render]")
{
    const std::string shot = kTmp + "/demo-ui.png";
    fs::remove(shot);
    const auto r = editor("'" + kSource + "/examples/data/demo-scene.json' --screenshot '" + shot + "' --size 640x400");
    INFO(r.err);
    REQUIRE(r.status == 0);
    const auto image = loadPng(shot);
    REQUIRE(image.width == 640);
    REQUIRE(image.height == 400);
}

} // namespace test_render
