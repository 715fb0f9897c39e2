// The promises of docs/editor.md that had no test (issue 12; label "render": they need an X
// display). Each runs build/bin/freeform-editor and checks what it wrote against values computed
// here, independently of the editor:
//   - a file dropped on the window (the replay's "drop" event calls the very function the window's
//     GLFW drop callback calls): a mesh is imported, a document opens, a corrupt file shows its
//     error and leaves the document as it was, byte for byte;
//   - File > Export tessellation as OBJ (Ctrl+E, the path typed, Enter): the file read back by a
//     reader written here equals the library's tessellateObject of every visible surface at the
//     document's tolerance, followed by the mesh file's own vertices (its quads split as fans):
//     the same counts, the same triangles, positions to 1e-12; a hidden object is left out;
//   - the F2 frame-statistics overlay: shown after F2 (its text through --state), gone after a
//     second F2; the triangle count it shows equals 2 n^2 per visible patch tessellated uniformly in
//     n x n cells, counted by hand;
//   - the lattice panel's strength slider set to W = 0.5 as a user does it (Ctrl+click, typing,
//     Enter): `ffd.strength` is saved as 0.5, and the deformed mesh exported through the panel is
//     p + W (D(p) - p) with D(p) the mesh `freeform ffd` writes for the saved lattice (1e-12);
//   - reflection lines: in an orthographic view a plane is one colour, dark where the formula of
//     docs/editor.md puts it on a stripe and light between stripes; on a half cylinder facing the
//     view the stripes are straight and equally spaced, 23 across the scanline through its middle,
//     each pixel dark or light as the formula computed here says;
//   - the "First steps" C0 patch pair (examples/data/c0-patches.json) with reflection lines, seen
//     from above: every pixel dark or light as the formula says with the hand-derived normals of
//     the two height fields, so the stripes break at the shared edge;
//   - the wireframe overlay: on a uniformly tessellated plane, the triangle edges cross a row of
//     pixels exactly at the cell boundaries and cell middles computed from the corners;
//   - `--frames N`: exit 0, nothing on stderr, stdout exactly the documented keys (N frames, the
//     hand-counted triangles, min <= median, mean <= max).

#include <catch2/catch.hpp>

#include <freeform/document/model.h>
#include <freeform/document/operations.h>
#include <freeform/mesh/polygon_mesh.h>

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "image_compare.h"
#include "interaction/replay.h"
#include "scene/scene.h"
#include "support/process.h"
#include "support/replay_session.h"

namespace test_render_promises {

using namespace freeform;
using namespace freeform::editor;
using namespace freeform::editor::replay_test;
using Json = nlohmann::ordered_json;

namespace {

namespace fs = std::filesystem;

std::string sphereObj() { return cat(FREEFORM_SOURCE_DIR, "/data/meshes/sphere.obj"); }

Json points(const std::vector<Eigen::Vector3d>& ps)
{
    Json out = Json::array();
    for (const auto& p : ps) out.push_back({p.x(), p.y(), p.z()});
    return out;
}

/// A bilinear patch (bezier_surface of degree 1 x 1) with corners c -+ a t -+ b z, its normal
/// t x z (rows along t).
Json plane(const std::string& name, const Eigen::Vector3d& c, const Eigen::Vector3d& t, double a, double b)
{
    const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
    return {{"name", name},
            {"type", "bezier_surface"},
            {"degree", {1, 1}},
            {"points", {points({c - a * t - b * z, c - a * t + b * z}), points({c + a * t - b * z, c + a * t + b * z})}}};
}

/// A bicubic patch over [x0, x0 + 2] x [-1, 1] with a bump (not planar, so that tessellation
/// to a tolerance has work to do).
Json bumpPatch(const std::string& name, double x0)
{
    Json rows = Json::array();
    for (int i = 0; i < 4; ++i) {
        std::vector<Eigen::Vector3d> row;
        for (int j = 0; j < 4; ++j) row.emplace_back(x0 + 2.0 * i / 3, -1 + 2.0 * j / 3, (i % 3 && j % 3) ? 1.2 : 0.1 * i);
        rows.push_back(points(row));
    }
    return {{"name", name}, {"type", "bezier_surface"}, {"degree", {3, 3}}, {"points", rows}};
}

Json document(const Json& objects, const Json& editor)
{
    return {{"format", "freeform"}, {"version", 1}, {"objects", objects}, {"editor", editor}};
}

std::string writeDoc(const std::string& name, const Json& doc)
{
    const std::string path = cat(kTmp, "/promises_", name, ".json");
    test::writeText(path, doc.dump(1));
    return path;
}

/// The front view (the camera at -y looking along +y, +z up): eye x = world x, eye z = -world y.
Json frontCamera(double distance, const std::string& projection)
{
    const Eigen::Quaterniond q(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()));
    return {{"target", {0.0, 0.0, 0.0}}, {"distance", distance}, {"orientation", {q.w(), q.x(), q.y(), q.z()}},
            {"fovy", 35.0}, {"projection", projection}, {"orbit", "turntable"}};
}

struct Run {
    test::ProcessResult process;
    Json state;
    std::string saved; // the --save output ("" when none)
};

/// Replays `events` on `doc` with --state (and --save, --screenshot when asked).
Run replayRun(const std::string& doc, const std::string& name, const Json& events, bool save = true, const std::string& png = "")
{
    const std::string file = cat(kTmp, "/promises_", name, ".events.json"), state = cat(kTmp, "/promises_", name, ".state.json"),
                      out = cat(kTmp, "/promises_", name, ".out.json");
    test::writeText(file, Json{{"events", events}}.dump(1));
    fs::remove(state);
    fs::remove(out);
    std::string args = cat("'", doc, "' --replay '", file, "' --state '", state, "' --size ", kW, "x", kH);
    if (save) args += cat(" --save '", out, "'");
    if (!png.empty()) args += cat(" --screenshot '", png, "'");
    Run r;
    r.process = runEditor(args, "FREEFORM_NO_ZENITY=1");
    INFO(r.process.err);
    REQUIRE(r.process.status == 0);
    REQUIRE(fs::exists(state));
    r.state = Json::parse(test::slurp(state));
    if (save) {
        REQUIRE(fs::exists(out));
        r.saved = test::slurp(out);
    }
    return r;
}

Json drop(const std::vector<std::string>& paths) { return {{"type", "drop"}, {"paths", paths}}; }
Json text(const std::string& t) { return {{"type", "text"}, {"text", t}}; }

/// A minimal OBJ reader (v and f lines; f takes the position index of each corner, 1-based or
/// negative), written here so that the check does not go through the library's reader.
struct Obj {
    std::vector<Eigen::Vector3d> v;
    std::vector<std::vector<int>> f;
};

Obj readObj(const std::string& path)
{
    Obj o;
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);) {
        std::istringstream s(line);
        std::string tag;
        s >> tag;
        if (tag == "v") {
            Eigen::Vector3d p;
            s >> p.x() >> p.y() >> p.z();
            o.v.push_back(p);
        } else if (tag == "f") {
            std::vector<int> face;
            for (std::string corner; s >> corner;) {
                const int i = std::stoi(corner.substr(0, corner.find('/')));
                face.push_back(i > 0 ? i - 1 : static_cast<int>(o.v.size()) + i);
            }
            o.f.push_back(face);
        }
    }
    return o;
}

/// The "key: value" lines of a --frames output.
std::vector<std::pair<std::string, std::string>> keyLines(const std::string& out)
{
    std::vector<std::pair<std::string, std::string>> lines;
    std::istringstream s(out);
    for (std::string line; std::getline(s, line);) {
        const auto colon = line.find(": ");
        lines.emplace_back(colon == std::string::npos ? line : line.substr(0, colon), colon == std::string::npos ? "" : line.substr(colon + 2));
    }
    return lines;
}

/// The centre of a --state widget rectangle [x, y, width, height].
Eigen::Vector2d centre(const Json& rect)
{
    return {rect[0].get<double>() + 0.5 * rect[2].get<double>(), rect[1].get<double>() + 0.5 * rect[3].get<double>()};
}

void clickAt(Json& events, const Eigen::Vector2d& p, const std::vector<std::string>& mods = {})
{
    Json m = move(p), down = press(p), up = release(p);
    if (!mods.empty()) m["mods"] = down["mods"] = up["mods"] = mods;
    events.push_back(m);
    events.push_back(down);
    events.push_back(up);
    events.push_back(frames(1));
}

} // namespace

// ------------------------------------------------------------------------------------ file drop

TEST_CASE("a file dropped on the window: a mesh is imported, a document opens, a corrupt file shows its error", "[render][replay][drop]")
{
    const Json a = document(Json::array({bumpPatch("a", -1)}), {{"camera", frontCamera(8, "perspective")}});
    const Json b = document(Json::array({bumpPatch("b1", -3), bumpPatch("b2", 1)}), {{"camera", frontCamera(9, "perspective")}});
    const std::string docA = writeDoc("drop_a", a), docB = writeDoc("drop_b", b);
    const std::string corrupt = cat(kTmp, "/promises_drop_corrupt.json"), corruptMesh = cat(kTmp, "/promises_drop_corrupt.obj");
    test::writeText(corrupt, "{\"format\": \"freeform\", \"version\": 1, \"objects\": [{\"name\": \"x\", \"type\": \"bezier_curve\"");
    test::writeText(corruptMesh, "v 0 0 0\nv 1 0 0\nf 1 2 7\n");

    // The document as a session without events saves it: what "untouched" means.
    const Run plain = replayRun(docA, "drop_plain", Json::array({frames(1)}));
    const Json plainJson = Json::parse(plain.saved);
    REQUIRE(plainJson["objects"].size() == 1);

    SECTION("a mesh is imported (recorded by path in editor.meshes), the document's objects stay")
    {
        const Run r = replayRun(docA, "drop_mesh", Json::array({drop({sphereObj()}), frames(2)}));
        CHECK(r.state["error"] == "");
        CHECK(r.state["objects"] == 2); // the patch and the mesh
        CHECK(r.state["modified"] == true);
        const Json saved = Json::parse(r.saved);
        CHECK(saved["objects"] == plainJson["objects"]);
        REQUIRE(saved["editor"]["meshes"].size() == 1);
        CHECK(fs::path(saved["editor"]["meshes"][0]["path"].get<std::string>()).filename() == "sphere.obj");
    }
    SECTION("two files dropped at once are both imported")
    {
        const std::string bpt = cat(FREEFORM_SOURCE_DIR, "/data/teapot.bpt");
        const Run r = replayRun(docA, "drop_two", Json::array({drop({sphereObj(), bpt}), frames(2)}));
        CHECK(r.state["error"] == "");
        // 1 + the mesh + the 32 patches of teapot.bpt (bezier_surface objects).
        CHECK(r.state["objects"] == 34);
    }
    SECTION("a .json document opens: the scene becomes that file's")
    {
        const Run r = replayRun(docA, "drop_doc", Json::array({drop({docB}), frames(2)}));
        CHECK(r.state["error"] == "");
        CHECK(r.state["objects"] == 2);
        CHECK(r.state["modified"] == false);
        const Json saved = Json::parse(r.saved);
        REQUIRE(saved["objects"].size() == 2);
        CHECK(saved["objects"][0]["name"] == "b1");
        CHECK(saved["objects"][1]["name"] == "b2");
        CHECK(saved["objects"][0]["points"] == b["objects"][0]["points"]);
        CHECK(saved["objects"][1]["points"] == b["objects"][1]["points"]);
    }
    SECTION("a document dropped over unsaved changes asks first")
    {
        const Run r = replayRun(docA, "drop_doc_unsaved", Json::array({drop({sphereObj()}), frames(1), drop({docB}), frames(2)}), false);
        CHECK(r.state["unsaved_dialog"] == true);
        CHECK(r.state["objects"] == 2); // still A's patch and the mesh
    }
    SECTION("a corrupt document shows the error naming the file; the document is untouched")
    {
        const Run r = replayRun(docA, "drop_corrupt", Json::array({drop({corrupt}), frames(2)}));
        const std::string error = r.state["error"];
        INFO(error);
        CHECK(error.find("promises_drop_corrupt.json") != std::string::npos);
        CHECK(r.state["modified"] == false);
        CHECK(r.saved == plain.saved);
    }
    SECTION("a mesh the reader accepts with a warning: imported, the warning in the status line")
    {
        // A PLY header line Blender 2.47 wrote, kept as a comment (docs/mesh-io.md): the library's
        // warning (freeform/core/warning.h) goes to the status line beside the import's notice;
        // the editor prints nothing for it.
        const std::string blender = cat(kTmp, "/promises_drop_blender.ply");
        test::writeText(blender, "ply\nformat ascii 1.0\nCreated by Blender3D 247 - www.blender.org\nelement vertex 3\n"
                                 "property float x\nproperty float y\nproperty float z\nelement face 1\n"
                                 "property list uchar uint vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
        const Run r = replayRun(docA, "drop_blender", Json::array({drop({blender}), frames(2)}));
        CHECK(r.state["error"] == "");
        CHECK(r.state["objects"] == 2);
        const std::string notice = r.state["notice"];
        INFO(notice);
        CHECK(notice.rfind("imported promises_drop_blender.ply", 0) == 0);
        CHECK(notice.find("; warning: ") != std::string::npos);
        CHECK(notice.find("unknown header line 'Created' kept as a comment") != std::string::npos);
        CHECK(r.process.err.find("warning") == std::string::npos);
    }
    SECTION("a corrupt mesh shows the error naming the file; the document is untouched")
    {
        const Run r = replayRun(docA, "drop_corrupt_mesh", Json::array({drop({corruptMesh}), frames(2)}));
        const std::string error = r.state["error"];
        INFO(error);
        CHECK(error.find("promises_drop_corrupt.obj") != std::string::npos);
        CHECK(r.state["objects"] == 1);
        CHECK(r.saved == plain.saved);
    }
}

TEST_CASE("the replay's drop event: a bad one is refused with its index and field", "[render][replay][drop]")
{
    CHECK_THROWS_WITH(parseReplay(R"({"events": [{"type": "drop"}]})"), Catch::Contains("events[0]") && Catch::Contains("paths"));
    CHECK_THROWS_WITH(parseReplay(R"({"events": [{"type": "drop", "paths": []}]})"), Catch::Contains("events[0].paths"));
    CHECK_THROWS_WITH(parseReplay(R"({"events": [{"type": "drop", "paths": [1]}]})"), Catch::Contains("events[0].paths"));
    CHECK_THROWS_WITH(parseReplay(R"({"events": [{"type": "drop", "paths": ["a"], "x": 1}]})"), Catch::Contains("events[0].x"));
    const auto events = parseReplay(R"({"events": [{"type": "drop", "paths": ["a.obj", "b.json"]}]})");
    REQUIRE(events.size() == 1);
    CHECK(events[0].type == ReplayEvent::Type::Drop);
    CHECK(events[0].paths == std::vector<std::string>{"a.obj", "b.json"});
}

// --------------------------------------------------------------------- Export tessellation as OBJ

TEST_CASE("File > Export tessellation as OBJ writes every visible surface and mesh at the document's tolerance", "[render][replay][export]")
{
    constexpr double kTolerance = 0.004;
    Json hidden = bumpPatch("hidden", 3);
    hidden["editor"] = {{"visible", false}};
    const Json objects = Json::array({bumpPatch("left", -2), bumpPatch("right", 0), hidden});
    const std::string doc =
        writeDoc("export", document(objects, {{"camera", frontCamera(9, "perspective")},
                                              {"display", {{"tolerance", kTolerance}}},
                                              {"meshes", Json::array({{{"name", "sphere"}, {"path", sphereObj()}}})}}));
    const std::string obj = cat(kTmp, "/promises_export.obj");
    fs::remove(obj);
    // Ctrl+E opens the path dialog (FREEFORM_NO_ZENITY=1: the typed path) with "scene.obj" selected:
    // type over it, Enter.
    const Json events = Json::array({key("E", {"ctrl"}), frames(2), key("A", {"ctrl"}), text(obj), key("Enter"), frames(2)});
    const Run r = replayRun(doc, "export", events, false);
    CHECK(r.state["error"] == "");
    CHECK(r.state["path_dialog"] == false);
    REQUIRE(fs::exists(obj));
    const Obj written = readObj(obj);

    // The reference: the library's tessellation of each visible surface at the tolerance, then the
    // mesh file's own vertices and faces (read by the same reader written here: Z up, no turn).
    const TypedDocument typed = TypedDocument::read(doc);
    ObjectTessellation options;
    options.tolerance = kTolerance;
    std::vector<Eigen::Vector3d> v;
    std::vector<std::vector<int>> f;
    for (const char* name : {"left", "right"}) {
        const auto mesh = tessellateObject(typed.object(name), options);
        REQUIRE(mesh);
        REQUIRE(mesh->isTriangleMesh());
        const int offset = static_cast<int>(v.size());
        for (int i = 0; i < mesh->vertexCount(); ++i) v.emplace_back(mesh->positions.col(i));
        for (int k = 0; k < mesh->faceCount(); ++k) f.push_back({offset + mesh->face(k)[0], offset + mesh->face(k)[1], offset + mesh->face(k)[2]});
    }
    const int surfaceVertices = static_cast<int>(v.size());
    const Obj sphere = readObj(sphereObj());
    for (const auto& p : sphere.v) v.push_back(p);
    // The mesh's polygons (sphere.obj has 240 quads) as fans of triangles: (a, b, c, d) ->
    // (a, b, c), (a, c, d).
    int polygons = 0;
    for (const auto& face : sphere.f) {
        polygons += face.size() > 3;
        for (std::size_t k = 1; k + 1 < face.size(); ++k)
            f.push_back({face[0] + surfaceVertices, face[k] + surfaceVertices, face[k + 1] + surfaceVertices});
    }
    REQUIRE(polygons == 240);
    INFO("written " << written.v.size() << " vertices, " << written.f.size() << " faces; reference " << v.size() << ", " << f.size());
    REQUIRE(written.v.size() == v.size());
    REQUIRE(written.f.size() == f.size());
    double worst = 0;
    for (std::size_t i = 0; i < v.size(); ++i) worst = std::max(worst, (written.v[i] - v[i]).norm());
    CHECK(worst <= 1e-12);
    int differentFaces = 0;
    for (std::size_t k = 0; k < f.size(); ++k) differentFaces += written.f[k] != f[k];
    CHECK(differentFaces == 0);
    // The tolerance mattered: the two bumps are refined beyond one quad each.
    CHECK(surfaceVertices > 100);
}

// ------------------------------------------------------------------------- F2 frame statistics

TEST_CASE("F2 shows the frame statistics overlay with the number of triangles drawn; F2 again hides it", "[render][replay][stats]")
{
    // Two visible bicubic patches tessellated uniformly in 5 x 5 and 7 x 7 cells, and a hidden one:
    // 2 (25 + 49) = 148 triangles drawn, counted by hand.
    Json left = bumpPatch("left", -2), right = bumpPatch("right", 0), hidden = bumpPatch("hidden", 3);
    left["editor"] = {{"tessellation", {{"mode", "uniform"}, {"segments", 5}}}};
    right["editor"] = {{"tessellation", {{"mode", "uniform"}, {"segments", 7}}}};
    hidden["editor"] = {{"visible", false}, {"tessellation", {{"mode", "uniform"}, {"segments", 3}}}};
    const std::string doc = writeDoc("stats", document(Json::array({left, right, hidden}), {{"camera", frontCamera(9, "perspective")},
                                                                                             {"display", {{"grid", false}, {"axes", false}}}}));
    const Run before = replayRun(doc, "stats_off", Json::array({frames(2)}), false);
    CHECK(before.state["stats"].is_null());

    const Run shown = replayRun(doc, "stats_on", Json::array({key("F2"), frames(3)}), false);
    REQUIRE(shown.state["stats"].is_string());
    const std::string overlay = shown.state["stats"];
    INFO(overlay);
    double frameMs = -1, updateMs = -1;
    long triangles = -1;
    REQUIRE(std::sscanf(overlay.c_str(), "frame %lf ms   update %lf ms   %ld triangles", &frameMs, &updateMs, &triangles) == 3);
    CHECK(triangles == 2 * (5 * 5 + 7 * 7));
    CHECK(frameMs > 0);
    CHECK(updateMs >= 0);

    const Run hiddenAgain = replayRun(doc, "stats_toggle", Json::array({key("F2"), frames(2), key("F2"), frames(2)}), false);
    CHECK(hiddenAgain.state["stats"].is_null());
}

// --------------------------------------------------------------------------- strength slider

TEST_CASE("the lattice panel's strength slider set to 0.5: ffd.strength is saved and the export is p + W (D(p) - p)", "[render][replay][ffd]")
{
    const std::string mesh = sphereObj();
    Json camera = frontRightCamera(Eigen::Vector3d::Zero(), 7);
    const std::string doc = writeDoc("strength", document(Json::array(), {{"camera", camera},
                                                                          {"meshes", Json::array({{{"name", "sphere"}, {"path", mesh}}})}}));
    const Scene scene = Scene::load(doc);
    const std::string exported = cat(kTmp, "/promises_strength.obj"), reference = cat(kTmp, "/promises_strength_full.obj");

    // Phase 1: select the sphere, fit a lattice (L), drag its corner (1, 1, 1): where is the slider?
    Json events = Json::array();
    clickAt(events, worldToPixel(scene, kW, kH, Eigen::Vector3d::Zero()));
    events.push_back(key("L"));
    events.push_back(frames(2));
    const Run fitted = replayRun(doc, "strength_fit", events);
    const Json fittedJson = Json::parse(fitted.saved);
    Json lattice;
    for (const Json& o : fittedJson["objects"])
        if (o["type"] == "lattice") lattice = o;
    REQUIRE(lattice["points"].size() == 64);
    const Json& p63 = lattice["points"][63];
    const Eigen::Vector2d corner = worldToPixel(scene, kW, kH, Eigen::Vector3d(p63[0].get<double>(), p63[1].get<double>(), p63[2].get<double>()));
    drag(events, corner, corner + Eigen::Vector2d(43, -34));
    events.push_back(key("Escape")); // the point deselected, the lattice stays selected
    events.push_back(frames(2));
    // Properties scrolled to its end (the wheel over it, just under its title bar: off its
    // scrolling child windows), where the lattice panel's rows are.
    const Json& properties = fitted.state["panels"]["Properties"];
    const double wheelX = centre(properties).x(), wheelY = properties[1].get<double>() + 35;
    events.push_back({{"type", "scroll"}, {"dy", -30}, {"x", wheelX}, {"y", wheelY}});
    events.push_back(frames(2));
    const Run dragged = replayRun(doc, "strength_drag", events);
    const Json widgets = dragged.state["widgets"];
    for (const char* name : {"strength", "export path", "export deformed"}) {
        INFO(name);
        REQUIRE(widgets.contains(name)); // drawn and not scrolled out of view
    }

    // Phase 2: Ctrl+click on the slider (it becomes a text field, its text selected), type 0.5,
    // Enter; type the export path, press "export deformed".
    clickAt(events, centre(widgets["strength"]), {"ctrl"});
    events.push_back(text("0.5"));
    events.push_back(key("Enter"));
    events.push_back(frames(2));
    fs::remove(exported);
    clickAt(events, centre(widgets["export path"]));
    events.push_back(key("A", {"ctrl"}));
    events.push_back(text(exported));
    events.push_back(key("Enter"));
    clickAt(events, centre(widgets["export deformed"]));
    const Run done = replayRun(doc, "strength_export", events);
    CHECK(done.state["error"] == "");
    CHECK(done.state["widgets"] == widgets); // the rows stayed where they were clicked
    const Json doneJson = Json::parse(done.saved);
    Json savedLattice;
    for (const Json& o : doneJson["objects"])
        if (o["type"] == "lattice") savedLattice = o;
    CHECK(savedLattice["editor"]["ffd"]["strength"] == 0.5);
    REQUIRE(fs::exists(exported));

    // D(p): the saved lattice applied by the command-line tool (the library's deform, W = 1).
    Json alone = savedLattice;
    alone.erase("editor");
    const std::string latticeFile = cat(kTmp, "/promises_strength_lattice.json");
    test::writeText(latticeFile, document(Json::array({alone}), Json::object()).dump(1));
    fs::remove(reference);
    const auto r = test::cli(cat("ffd '", mesh, "' --lattice '", latticeFile, "' -o '", reference, "'"));
    INFO(r.err);
    REQUIRE(r.status == 0);

    const Obj p = readObj(mesh), full = readObj(reference), half = readObj(exported);
    REQUIRE(p.v.size() == 266);
    REQUIRE(full.v.size() == p.v.size());
    REQUIRE(half.v.size() == p.v.size());
    double worst = 0, moved = 0;
    for (std::size_t i = 0; i < p.v.size(); ++i) {
        worst = std::max(worst, (half.v[i] - (p.v[i] + 0.5 * (full.v[i] - p.v[i]))).norm());
        moved = std::max(moved, (full.v[i] - p.v[i]).norm());
    }
    INFO("worst " << worst << ", largest move at W = 1: " << moved);
    CHECK(worst <= 1e-12);
    CHECK(moved > 0.01); // the drag did deform the mesh, so W matters (at W = 1 the export would be off by moved / 2)
    CHECK(half.f == p.f);
}

// ---------------------------------------------------------------------------- reflection lines

namespace {

/// The reflection-line colour docs/editor.md promises for an eye-space unit normal n in an
/// orthographic view (v = (0, 0, 1)): r = 2 (n.v) n - v, m = r + (0, 0, 1), phase = stripes * m.x / |m|;
/// dark (on a stripe) where the phase is within 1/4 of an integer. Returns the distance of the
/// phase to the nearest integer.
double phaseDistance(const Eigen::Vector3d& n, double stripes)
{
    const Eigen::Vector3d v(0, 0, 1);
    const Eigen::Vector3d r = 2 * n.dot(v) * n - v;
    const Eigen::Vector3d m = r + v;
    const double phase = stripes * m.x() / m.norm();
    return std::abs(phase - std::round(phase));
}

bool isDark(const unsigned char* c) { return c[0] < 40 && c[1] < 40 && c[2] < 40; }
bool isLight(const unsigned char* c) { return c[0] > 215 && c[1] > 215 && c[2] > 215; }

std::string reflectionShot(const std::string& name, const Json& objects, const std::string& extra = "")
{
    const Json editor = {{"camera", frontCamera(5, "orthographic")},
                         {"display", {{"analysis", "reflection_lines"}, {"grid", false}, {"axes", false}, {"background", {0.5, 0.5, 0.5}}}}};
    const std::string doc = writeDoc(name, document(objects, editor)), png = cat(kTmp, "/promises_", name, ".png");
    fs::remove(png);
    const auto r = runEditor(cat("'", doc, "' --screenshot '", png, "' --no-ui --size ", kW, "x", kH, " ", extra));
    INFO(r.err);
    REQUIRE(r.status == 0);
    return doc;
}

} // namespace

TEST_CASE("reflection lines: a plane is one colour, on a stripe or between stripes as the formula says", "[render][reflection]")
{
    // Eye normals (sin a, 0, cos a) (world (sin a, -cos a, 0) in the front view): phase = 12 sin a.
    // sin a = 6/12: phase 6, on a stripe (dark); sin a = -6.5/12: half way between two (light).
    constexpr double kStripes = 12; // display.stripes' default
    const double dark = std::asin(6.0 / 12), light = -std::asin(6.5 / 12);
    REQUIRE(phaseDistance(Eigen::Vector3d(std::sin(dark), 0, std::cos(dark)), kStripes) < 1e-12);
    REQUIRE(std::abs(phaseDistance(Eigen::Vector3d(std::sin(light), 0, std::cos(light)), kStripes) - 0.5) < 1e-12);
    auto tangent = [](double a) { return Eigen::Vector3d(std::cos(a), std::sin(a), 0); };
    const Json objects = Json::array({plane("dark", {-1.0, 0, 0}, tangent(dark), 0.7, 0.8), plane("light", {1.0, 0, 0}, tangent(light), 0.7, 0.8)});
    const std::string doc = reflectionShot("reflection_planes", objects);
    const test::RgbImage image = test::loadPng(cat(kTmp, "/promises_reflection_planes.png"));
    REQUIRE(image.width == kW);
    const Scene scene = Scene::load(doc);
    // The inside of each plane's picture (its projected corners, 4 pixels in): every pixel the one
    // colour.
    auto check = [&](const Eigen::Vector3d& c, const Eigen::Vector3d& t, bool wantDark) {
        const Eigen::Vector2d lo = worldToPixel(scene, kW, kH, c - 0.7 * t + 0.8 * Eigen::Vector3d::UnitZ());
        const Eigen::Vector2d hi = worldToPixel(scene, kW, kH, c + 0.7 * t - 0.8 * Eigen::Vector3d::UnitZ());
        const int x0 = static_cast<int>(std::min(lo.x(), hi.x())) + 4, x1 = static_cast<int>(std::max(lo.x(), hi.x())) - 4;
        const int y0 = static_cast<int>(std::min(lo.y(), hi.y())) + 4, y1 = static_cast<int>(std::max(lo.y(), hi.y())) - 4;
        REQUIRE(x1 - x0 > 100);
        REQUIRE(y1 - y0 > 100);
        long wrong = 0, total = 0;
        int minC = 255, maxC = 0;
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                const unsigned char* p = image.at(x, y);
                ++total;
                wrong += wantDark ? !isDark(p) : !isLight(p);
                minC = std::min(minC, int(p[0]));
                maxC = std::max(maxC, int(p[0]));
            }
        INFO((wantDark ? "dark" : "light") << " plane: " << wrong << " of " << total << " pixels wrong, red from " << minC << " to " << maxC);
        CHECK(wrong == 0);
        CHECK(maxC - minC <= 2); // one colour
    };
    check({-1.0, 0, 0}, tangent(dark), true);
    check({1.0, 0, 0}, tangent(light), false);
}

TEST_CASE("reflection lines: a half cylinder facing the view has 23 straight stripes where the formula puts them", "[render][reflection]")
{
    // The exact half cylinder x^2 + y^2 = 1, y <= 0, z in [-1, 1] (a NURBS of two quadratic arcs),
    // axis along the view's vertical. At a point of it seen at world x = X the eye normal is
    // (X, 0, sqrt(1 - X^2)), so phase = 12 X: stripes centred at X = k/12, k = -11..11, in
    // |X| < 0.96 (23 of them), equally spaced and the same on every row.
    constexpr double kStripes = 12;
    const double w = std::sqrt(0.5);
    const Json cylinder = {{"name", "cylinder"},
                           {"type", "nurbs_surface"},
                           {"degree", {2, 1}},
                           {"knots", {{0, 0, 0, 1, 1, 2, 2, 2}, {0, 0, 1, 1}}},
                           {"points", {points({{-1, 0, -1}, {-1, 0, 1}}), points({{-1, -1, -1}, {-1, -1, 1}}), points({{0, -1, -1}, {0, -1, 1}}),
                                       points({{1, -1, -1}, {1, -1, 1}}), points({{1, 0, -1}, {1, 0, 1}})}},
                           {"weights", {{1, 1}, {w, w}, {1, 1}, {w, w}, {1, 1}}}};
    const std::string doc = reflectionShot("reflection_cylinder", Json::array({cylinder}));
    const test::RgbImage image = test::loadPng(cat(kTmp, "/promises_reflection_cylinder.png"));
    REQUIRE(image.width == kW);
    const Scene scene = Scene::load(doc);
    const Eigen::Vector2d left = worldToPixel(scene, kW, kH, {-1, 0, 0}), right = worldToPixel(scene, kW, kH, {1, 0, 0});
    const double cx = 0.5 * (left.x() + right.x()), scale = 0.5 * (right.x() - left.x()); // pixels per world unit
    REQUIRE(scale > 150);
    for (double height : {-0.5, 0.0, 0.5}) {
        const int row = static_cast<int>(std::floor(worldToPixel(scene, kW, kH, {0, 0, height}).y()));
        int agree = 0, disagree = 0, runs = 0;
        bool inRun = false;
        for (int x = static_cast<int>(left.x()); x <= static_cast<int>(right.x()); ++x) {
            const double X = (x + 0.5 - cx) / scale;
            if (std::abs(X) >= 0.96) continue;
            const unsigned char* p = image.at(x, row);
            const bool dark = isDark(p);
            if (dark && !inRun) ++runs;
            inRun = dark;
            // Classify only pixels clearly on or off a stripe (the edges are antialiased over
            // about a pixel: 0.06 of a phase period here).
            const double d = phaseDistance(Eigen::Vector3d(X, 0, std::sqrt(1 - X * X)), kStripes);
            if (d < 0.25 - 0.06) (dark ? agree : disagree) += 1;
            else if (d > 0.25 + 0.06) (isLight(p) ? agree : disagree) += 1;
        }
        INFO("row " << row << " (z = " << height << "): " << runs << " dark runs, " << agree << " pixels as the formula says, " << disagree
                    << " not");
        CHECK(runs == 23);
        CHECK(agree > 300);
        CHECK(disagree == 0);
    }
}

TEST_CASE("First steps: the reflection lines of the C0 patch pair break at the shared edge, as the formula says", "[render][reflection]")
{
    // examples/data/c0-patches.json: two bicubic patches over x in [-1.5, 0] and [0, 1.5], y in
    // [-0.75, 0.75], whose control points are evenly spaced in x and y, so the surface is the
    // height field z = s(x) + y^2 / 3 + c with slope ds/dx = 0.6 on the left and -0.6 on the right
    // (the rows rise by 0.3 every 0.5; across y the Bezier heights (A, B, B, A), A - B = 0.25, give
    // dz/dy = 0.75 (2v - 1) / 1.5 = y / 1.5). The unit normal is (-z_x, -z_y, 1) / N. Seen from
    // above (orthographic, turned 45 degrees about the view axis, so that the eye's x is
    // (cos 45, sin 45, 0)) the eye normal's z is positive and the stripe phase is 12 n.x_eye: on
    // each side a different function of y, so the stripes do not meet at x = 0.
    const Json source = Json::parse(test::slurp(cat(FREEFORM_SOURCE_DIR, "/examples/data/c0-patches.json")));
    constexpr double kStripes = 12, gamma = M_PI / 4;
    const Eigen::Quaterniond q(Eigen::AngleAxisd(gamma, Eigen::Vector3d::UnitZ()));
    const Json camera = {{"target", {0.0, 0.0, 0.6}}, {"distance", 5.0}, {"orientation", {q.w(), q.x(), q.y(), q.z()}},
                         {"fovy", 35.0}, {"projection", "orthographic"}, {"orbit", "turntable"}};
    const Json editor = {{"camera", camera},
                         {"display", {{"analysis", "reflection_lines"}, {"grid", false}, {"axes", false}, {"background", {0.5, 0.5, 0.5}}}}};
    const std::string doc = writeDoc("reflection_c0", document(source["objects"], editor)), png = cat(kTmp, "/promises_reflection_c0.png");
    fs::remove(png);
    const auto r = runEditor(cat("'", doc, "' --screenshot '", png, "' --no-ui --size ", kW, "x", kH));
    INFO(r.err);
    REQUIRE(r.status == 0);
    const test::RgbImage image = test::loadPng(png);
    REQUIRE(image.width == kW);
    const Scene scene = Scene::load(doc);
    const Eigen::Vector3d ex(std::cos(gamma), std::sin(gamma), 0), ey(-std::sin(gamma), std::cos(gamma), 0);
    const Eigen::Vector2d o = worldToPixel(scene, kW, kH, {0, 0, 0.6}), unit = worldToPixel(scene, kW, kH, Eigen::Vector3d(0, 0, 0.6) + ex);
    const double scale = (unit - o).norm();
    REQUIRE(scale > 150);
    auto expectedDistance = [&](double x, double y) {
        const double zx = x < 0 ? 0.6 : -0.6, zy = y / 1.5;
        const Eigen::Vector3d n = Eigen::Vector3d(-zx, -zy, 1).normalized();
        const double phase = kStripes * n.dot(ex);
        return std::abs(phase - std::round(phase));
    };
    int agree = 0, disagree = 0, breaks = 0;
    for (int row = 0; row < kH; ++row)
        for (int col = 0; col < kW; ++col) {
            const double a = (col + 0.5 - o.x()) / scale, b = -(row + 0.5 - o.y()) / scale;
            const Eigen::Vector2d w = a * ex.head<2>() + b * ey.head<2>(); // world x, y under the pixel
            if (std::abs(w.x()) < 4 / scale || std::abs(w.x()) > 1.5 - 4 / scale || std::abs(w.y()) > 0.75 - 4 / scale) continue;
            const double d = expectedDistance(w.x(), w.y());
            const unsigned char* p = image.at(col, row);
            if (d < 0.25 - 0.06) (isDark(p) ? agree : disagree) += 1;
            else if (d > 0.25 + 0.06) (isLight(p) ? agree : disagree) += 1;
        }
    // Along the edge: how many places have a dark stripe on one side and light on the other.
    for (double y = -0.7; y <= 0.7; y += 0.01) {
        const double left = expectedDistance(-1e-9, y), right = expectedDistance(1e-9, y);
        breaks += (left < 0.19 && right > 0.31) || (left > 0.31 && right < 0.19);
    }
    INFO(agree << " pixels as the formula says, " << disagree << " not; " << breaks << " of 141 places along the edge dark on one side, light on the other");
    CHECK(agree > 100000);
    CHECK(disagree <= agree / 1000); // a few pixels at the patches' tessellation seams
    CHECK(breaks > 30);
}

TEST_CASE("the wireframe overlay (W) draws every triangle edge of the tessellation where it lies", "[render][wireframe]")
{
    // The light plane of the reflection-line case (one colour, 242) tessellated uniformly in 6 x 6
    // cells, with and without --wireframe. On the row through the middle of a row of cells the
    // edges cross at every cell boundary (the 5 inner ones) and each cell's diagonal crosses at the
    // cell's middle (whichever diagonal it is): 11 dark lines inside the plane, equally spaced at
    // half a cell, at the places computed here from the corners' pixels.
    constexpr int kCells = 6;
    const double light = -std::asin(6.5 / 12);
    const Eigen::Vector3d c(0, 0, 0), t(std::cos(light), std::sin(light), 0);
    Json object = plane("p", c, t, 0.9, 0.8);
    object["editor"] = {{"tessellation", {{"mode", "uniform"}, {"segments", kCells}}}};
    const std::string doc = reflectionShot("wireframe_off", Json::array({object}));
    reflectionShot("wireframe_on", Json::array({object}), "--wireframe");
    const test::RgbImage off = test::loadPng(cat(kTmp, "/promises_wireframe_off.png")), on = test::loadPng(cat(kTmp, "/promises_wireframe_on.png"));
    REQUIRE(off.width == kW);
    REQUIRE(on.width == kW);
    const Scene scene = Scene::load(doc);
    const Eigen::Vector2d left = worldToPixel(scene, kW, kH, c - 0.9 * t), right = worldToPixel(scene, kW, kH, c + 0.9 * t);
    const double width = right.x() - left.x();
    REQUIRE(width > 200);
    // The middle of cell row 2 (of 0..5) along z in [-0.8, 0.8].
    const int row = static_cast<int>(std::floor(worldToPixel(scene, kW, kH, c + Eigen::Vector3d(0, 0, -0.8 + 1.6 * 2.5 / kCells)).y()));
    auto darkRuns = [&](const test::RgbImage& image) {
        std::vector<double> centres;
        int start = -1;
        const int x0 = static_cast<int>(std::ceil(left.x())) + 4, x1 = static_cast<int>(std::floor(right.x())) - 4;
        for (int x = x0; x <= x1 + 1; ++x) {
            const bool dark = x <= x1 && image.at(x, row)[0] < 200;
            if (dark && start < 0) start = x;
            if (!dark && start >= 0) {
                centres.push_back(0.5 * (start + x)); // pixels start..x-1: centre (start + x) / 2
                start = -1;
            }
        }
        return centres;
    };
    CHECK(darkRuns(off).empty()); // the plane alone is one light colour
    const std::vector<double> lines = darkRuns(on);
    INFO("row " << row << ", plane from x = " << left.x() << " to " << right.x());
    REQUIRE(lines.size() == 2 * kCells - 1);
    for (int m = 1; m < 2 * kCells; ++m) {
        const double expected = left.x() + width * m / (2.0 * kCells);
        INFO("line " << m << " at " << lines[m - 1] << ", expected " << expected);
        CHECK(std::abs(lines[m - 1] - expected) <= 1.5);
    }
}

// --------------------------------------------------------------------------------------- --frames

TEST_CASE("--frames N prints the documented statistics and nothing else on stdout", "[render][frames]")
{
    Json patch = bumpPatch("p", -1);
    patch["editor"] = {{"tessellation", {{"mode", "uniform"}, {"segments", 6}}}};
    const std::string doc = writeDoc("frames", document(Json::array({patch}), {{"camera", frontCamera(8, "perspective")},
                                                                              {"display", {{"grid", false}, {"axes", false}}}}));
    const auto r = runEditor(cat("'", doc, "' --frames 5 --size 320x200"));
    INFO(r.err);
    INFO(r.out);
    REQUIRE(r.status == 0);
    CHECK(r.err.empty());
    const auto lines = keyLines(r.out);
    std::vector<std::string> keys;
    std::map<std::string, std::string> values;
    for (const auto& [k, v] : lines) {
        keys.push_back(k);
        values[k] = v;
    }
    // The documented order: the renderer, the antialiasing and samples, the triangle count, the
    // frame times (median, mean, min, max) and the CPU time per frame.
    const std::vector<std::string> expected = {"renderer", "antialiasing", "size", "triangles", "vertices", "tessellation_ms",
                                               "first_frame_ms", "frames", "frame_ms_median", "frame_ms_mean", "frame_ms_min",
                                               "frame_ms_max", "frame_cpu_ms_median"};
    CHECK(keys == expected);
    CHECK(!values["renderer"].empty());
    CHECK(values["size"].rfind("320x200, samples: ", 0) == 0);
    CHECK(values["frames"] == "5");
    CHECK(values["triangles"] == std::to_string(2 * 6 * 6)); // 6 x 6 cells, two triangles each
    CHECK(values["vertices"] == std::to_string(7 * 7));
    const double median = std::stod(values["frame_ms_median"]), mean = std::stod(values["frame_ms_mean"]),
                 lo = std::stod(values["frame_ms_min"]), hi = std::stod(values["frame_ms_max"]), cpu = std::stod(values["frame_cpu_ms_median"]);
    CHECK(lo > 0);
    CHECK(lo <= median);
    CHECK(median <= hi);
    CHECK(lo <= mean);
    CHECK(mean <= hi);
    CHECK(cpu >= 0);

    // The samples its frames used (docs/editor.md, "Anti-aliasing"): under auto none for a
    // software renderer's frames; --samples 2 forces two on every renderer.
    const bool software = values["renderer"].find("llvmpipe") != std::string::npos || values["renderer"].find("softpipe") != std::string::npos;
    CHECK(values["antialiasing"] == "auto");
    if (software) CHECK(values["size"] == "320x200, samples: 0, shading: phong");
    const auto forced = runEditor(cat("'", doc, "' --frames 2 --size 320x200 --samples 2"));
    REQUIRE(forced.status == 0);
    std::map<std::string, std::string> forcedValues;
    for (const auto& [k, v] : keyLines(forced.out)) forcedValues[k] = v;
    CHECK(forcedValues["antialiasing"] == "always");
    CHECK(forcedValues["size"] == "320x200, samples: 2, shading: phong");

    // A wrong count: exit 2, one error line, nothing on stdout.
    const auto bad = runEditor(cat("'", doc, "' --frames 0"));
    CHECK(bad.status == 2);
    CHECK(bad.out.empty());
    CHECK(bad.err.rfind("error:", 0) == 0);
}

} // namespace test_render_promises
