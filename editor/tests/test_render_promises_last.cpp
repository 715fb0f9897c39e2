// The last promises of docs/editor.md that had no test (issue 12; label "render": they need an X
// display). Each runs build/bin/freeform-editor through a replayed session and checks what it wrote
// (--state, --save, --screenshot) against facts computed here, independently of the editor:
//   - the lattice panel's read-out row (--state `lattice_readout`, the numbers the panel formats and
//     its lines as drawn): the vertices outside the lattice box counted here from the OBJ file's
//     own `v` lines and the saved lattice frame; det J's range and the fold-over count from the
//     trivariate Bernstein derivatives of the saved lattice evaluated per vertex here, in double;
//     a lattice point dragged across its neighbour gives a red fold-over line (red pixels in the
//     screenshot where `widgets` puts that line);
//   - + / - (the proportional-editing radius): the radius in --state is scaled by 1.25 per key, and
//     a drag then moves each neighbour by the documented falloff 1 - 3t^2 + 2t^3, t = d / radius,
//     of the new radius (computed here), the points beyond it not at all;
//   - Ctrl+Q without unsaved changes quits (--state `quit`; the replay handles no later event);
//     with unsaved changes the unsaved-changes dialog appears, the editor stays, and the document
//     keeps the change (Escape, Cancel, closes the dialog). That the process then exits 0 in a
//     real window is editor/tests/x11/quit_window.sh (editor_x11_quit).

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "image_compare.h"
#include "interaction/replay.h"
#include "scene/scene.h"
#include "support/process.h"
#include "support/replay_session.h"

namespace test_render_promises_last {

using namespace freeform;
using namespace freeform::editor;
using namespace freeform::editor::replay_test;
using Catch::Matchers::WithinAbs;
using Json = nlohmann::ordered_json;

namespace {

namespace fs = std::filesystem;

struct Run {
    test::ProcessResult process;
    Json state;
    Json saved; // the --save output
};

/// Replays `events` on `doc` with --state and --save (and --screenshot when `png` is given, and
/// the further options `extra`).
Run replayRun(const std::string& doc, const std::string& name, const Json& events, const std::string& png = "",
              const std::string& extra = "")
{
    const std::string file = cat(kTmp, "/promises_last_", name, ".events.json"), state = cat(kTmp, "/promises_last_", name, ".state.json"),
                      out = cat(kTmp, "/promises_last_", name, ".out.json");
    test::writeText(file, Json{{"events", events}}.dump(1));
    fs::remove(state);
    fs::remove(out);
    std::string args = cat("'", doc, "' --replay '", file, "' --state '", state, "' --save '", out, "' --size ", kW, "x", kH, extra);
    if (!png.empty()) {
        fs::remove(png);
        args += cat(" --screenshot '", png, "'");
    }
    Run r;
    r.process = runEditor(args, "FREEFORM_NO_ZENITY=1");
    INFO(r.process.err);
    REQUIRE(r.process.status == 0);
    REQUIRE(fs::exists(state));
    REQUIRE(fs::exists(out));
    r.state = Json::parse(test::slurp(state));
    r.saved = Json::parse(test::slurp(out));
    return r;
}

std::string writeDoc(const std::string& name, const Json& doc)
{
    const std::string path = cat(kTmp, "/promises_last_", name, ".json");
    test::writeText(path, doc.dump(1));
    return path;
}

Eigen::Vector3d vec(const Json& p) { return {p[0].get<double>(), p[1].get<double>(), p[2].get<double>()}; }
Json array(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

Json objectNamed(const Json& saved, const std::string& name)
{
    for (const Json& o : saved["objects"])
        if (o["name"] == name) return o;
    return nullptr;
}

/// The `v` lines of an OBJ file, read here (not through the library).
std::vector<Eigen::Vector3d> objVertices(const std::string& path)
{
    std::vector<Eigen::Vector3d> v;
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("v ", 0) != 0) continue;
        std::istringstream s(line.substr(2));
        Eigen::Vector3d p;
        s >> p.x() >> p.y() >> p.z();
        v.push_back(p);
    }
    return v;
}

double binomial(int n, int k)
{
    double b = 1;
    for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
    return b;
}

/// The Bernstein polynomial B_i^n(x) (B_0^0 = 1).
double bernstein(int n, int i, double x) { return binomial(n, i) * std::pow(x, i) * std::pow(1 - x, n - i); }

/// A lattice as docs/format.md writes it: degrees, frame, points (i, j, k) at i(m+1)(n+1) + j(n+1) + k.
struct TestLattice {
    int l = 0, m = 0, n = 0;
    Eigen::Vector3d origin;
    Eigen::Matrix3d axes; // columns S, T, U
    std::vector<Eigen::Vector3d> points;

    static TestLattice of(const Json& o)
    {
        TestLattice L;
        L.l = o["degree"][0];
        L.m = o["degree"][1];
        L.n = o["degree"][2];
        L.origin = vec(o["origin"]);
        for (int a = 0; a < 3; ++a) L.axes.col(a) = vec(o["axes"][a]);
        for (const Json& p : o["points"]) L.points.push_back(vec(p));
        return L;
    }
    const Eigen::Vector3d& P(int i, int j, int k) const { return points[static_cast<std::size_t>((i * (m + 1) + j) * (n + 1) + k)]; }
    Eigen::Vector3d coordinates(const Eigen::Vector3d& p) const { return axes.inverse() * (p - origin); }
    /// det J of the world-space map at lattice coordinates (s, t, u) inside the box, from the
    /// tensor hodographs: f_s = l sum B^{l-1}_i(s) B^m_j(t) B^n_k(u) (P_{i+1,j,k} - P_ijk) and likewise,
    /// det J = f_s . (f_t x f_u) / det[S T U] (docs/ffd.md, "The certificate").
    double detJ(const Eigen::Vector3d& x) const
    {
        Eigen::Vector3d fs = Eigen::Vector3d::Zero(), ft = Eigen::Vector3d::Zero(), fu = Eigen::Vector3d::Zero();
        for (int i = 0; i <= l; ++i)
            for (int j = 0; j <= m; ++j)
                for (int k = 0; k <= n; ++k) {
                    if (i < l) fs += l * bernstein(l - 1, i, x.x()) * bernstein(m, j, x.y()) * bernstein(n, k, x.z()) * (P(i + 1, j, k) - P(i, j, k));
                    if (j < m) ft += m * bernstein(l, i, x.x()) * bernstein(m - 1, j, x.y()) * bernstein(n, k, x.z()) * (P(i, j + 1, k) - P(i, j, k));
                    if (k < n) fu += n * bernstein(l, i, x.x()) * bernstein(m, j, x.y()) * bernstein(n - 1, k, x.z()) * (P(i, j, k + 1) - P(i, j, k));
                }
        return fs.dot(ft.cross(fu)) / axes.determinant();
    }
};

std::string format(const char* f, double a, double b)
{
    char line[160];
    std::snprintf(line, sizeof line, f, a, b);
    return line;
}

/// The proportional-editing weight of docs/editor.md: 1 - 3t^2 + 2t^3, t = d / radius; 0 beyond.
double falloff(double d, double radius)
{
    const double t = d / radius;
    return t < 1 ? 1 - 3 * t * t + 2 * t * t * t : 0.0;
}

} // namespace

// ------------------------------------------------------------------ the lattice panel's read-out

TEST_CASE("the lattice read-out's numbers: vertices outside the box, det J's range and the red fold-over count, "
          "computed here from the saved lattice",
          "[render][replay][ffd]")
{
    // The bumpy sphere (266 vertices of radius about 1) and a lattice of degrees 2 x 1 x 1 on the
    // box [-0.77, 0.77]^3, linked to it, `keep` outside: the box holds the caps of the sphere near
    // its eight corners, the rest is outside (J = I there, det J = 1).
    const std::string mesh = cat(FREEFORM_SOURCE_DIR, "/data/meshes/sphere.obj");
    const std::vector<Eigen::Vector3d> vertices = objVertices(mesh);
    REQUIRE(vertices.size() == 266);
    const double a = 0.77;
    Json points = Json::array();
    for (int i = 0; i <= 2; ++i)
        for (int j = 0; j <= 1; ++j)
            for (int k = 0; k <= 1; ++k) points.push_back(array(Eigen::Vector3d(-a + a * i, -a + 2 * a * j, -a + 2 * a * k)));
    const Json lattice = {{"name", "L"},
                          {"type", "lattice"},
                          {"degree", {2, 1, 1}},
                          {"origin", {-a, -a, -a}},
                          {"axes", {{2 * a, 0, 0}, {0, 2 * a, 0}, {0, 0, 2 * a}}},
                          {"points", points},
                          {"outside", "keep"},
                          {"editor", {{"ffd", {{"mesh", "sphere"}}}}}};
    const std::string doc = writeDoc("readout", {{"format", "freeform"},
                                                 {"version", 1},
                                                 {"objects", Json::array({lattice})},
                                                 {"editor",
                                                  {{"camera", frontRightCamera(Eigen::Vector3d::Zero(), 6)},
                                                   {"display", {{"control_points", true}}}, // every object's points pickable
                                                   {"meshes", Json::array({{{"name", "sphere"}, {"path", mesh}}})}}}});
    const Scene scene = Scene::load(doc);
    const TestLattice rest = TestLattice::of(lattice);

    // Counted here: the vertices outside the box (none within 1e-6 of its faces, so that the
    // editor's float coordinates cannot count one differently).
    std::size_t outside = 0;
    for (const Eigen::Vector3d& p : vertices) {
        const Eigen::Vector3d x = rest.coordinates(p);
        REQUIRE((x.array() - 0).abs().minCoeff() > 1e-6);
        REQUIRE((x.array() - 1).abs().minCoeff() > 1e-6);
        outside += (x.array() < 0).any() || (x.array() > 1).any();
    }
    REQUIRE(outside > 0);
    REQUIRE(outside < vertices.size());

    // Point (2, 1, 1) (the corner (a, a, a)) is clicked: the lattice and that point are selected;
    // Properties scrolled to its end shows the lattice panel's read-out.
    const Eigen::Vector2d corner = worldToPixel(scene, kW, kH, rest.P(2, 1, 1)), neighbour = worldToPixel(scene, kW, kH, rest.P(1, 1, 1));
    Json select = Json::array();
    click(select, corner);
    select.push_back(frames(2));
    auto scrollProperties = [](Json& events) {
        events.push_back({{"type", "scroll"}, {"dy", -30}, {"x", 1100}, {"y", 60}});
        events.push_back(frames(3));
    };

    SECTION("the rest lattice: every det J is 1, no fold-over line")
    {
        Json events = select;
        scrollProperties(events);
        const Run r = replayRun(doc, "readout_rest", events);
        REQUIRE(r.state["selection"]["item"] == "L");
        const Json& out = r.state["lattice_readout"];
        REQUIRE(out.is_object());
        CHECK(out["vertices"] == vertices.size());
        CHECK(out["outside"] == outside);
        CHECK(out["det_j_min"].get<double>() == Approx(1).margin(1e-5));
        CHECK(out["det_j_max"].get<double>() == Approx(1).margin(1e-5));
        CHECK(out["fold_overs"] == 0);
        REQUIRE(out["lines"].size() == 2); // no fold-over line
        CHECK(out["lines"][1] == "det J in [1, 1]");
        CHECK(r.state["widgets"].contains("read-out"));
        CHECK_FALSE(r.state["widgets"].contains("fold-over"));
    }

    SECTION("--frame-log: one line per frame with the documented columns; the drag's frames flagged")
    {
        Json events = select;
        drag(events, corner, neighbour);
        events.push_back(frames(2));
        const std::string log = cat(kTmp, "/promises_last_frame_log.tsv");
        fs::remove(log);
        const Run r = replayRun(doc, "frame_log", events, "", cat(" --frame-log '", log, "'"));
        CHECK(r.process.out.empty()); // the log goes to its file only
        std::istringstream in(test::slurp(log));
        std::string line;
        REQUIRE(std::getline(in, line));
        CHECK(line == "frame\tdragging\tchanged\tinput_ms\tui_ms\tupdate_ms\toverlay_ms\tdraw_ms\tgui_ms\tend_ms\ttotal_ms\tperiod_ms\tcpu_ms");
        int index = 0, dragChanged = 0, dragging = 0;
        while (std::getline(in, line)) {
            INFO(line);
            std::vector<double> v;
            std::istringstream fields(line);
            for (std::string f; std::getline(fields, f, '\t');) v.push_back(std::stod(f));
            REQUIRE(v.size() == 13);
            CHECK(v[0] == index);
            CHECK((v[1] == 0 || v[1] == 1));
            CHECK((v[2] == 0 || v[2] == 1));
            for (std::size_t k = 3; k < 13; ++k) CHECK(v[k] >= 0);
            // total is the sum of the seven phases (each printed to 0.001 ms, the sum rounded once).
            CHECK(std::abs(v[3] + v[4] + v[5] + v[6] + v[7] + v[8] + v[9] - v[10]) <= 0.0045);
            CHECK((index == 0 ? v[11] == 0 : v[11] > 0));
            dragging += v[1] == 1;
            if (v[1] == 1 && v[2] == 1) {
                ++dragChanged;
                CHECK(v[5] > 0); // the deformation of the 266 vertices is in update
            }
            ++index;
        }
        // The lattice changes in the frame after each of the drag's two moves, and only then
        // while a drag runs (the presses and releases change nothing while flagged).
        CHECK(dragging > dragChanged);
        CHECK(dragChanged == 2);
        CHECK(index > 6);
    }

    SECTION("the corner dragged across its neighbour: det J <= 0 at some vertices, in red")
    {
        // The drag goes on past the neighbour's place on screen by the same distance again.
        Json events = select;
        drag(events, corner, neighbour + 1.0 * (neighbour - corner));
        events.push_back(frames(2));
        scrollProperties(events);
        const std::string png = cat(kTmp, "/promises_last_readout_fold.png");
        const Run r = replayRun(doc, "readout_fold", events, png);
        const Json saved = objectNamed(r.saved, "L");
        REQUIRE(saved.is_object());
        const TestLattice moved = TestLattice::of(saved);
        REQUIRE(moved.points.size() == rest.points.size());
        for (std::size_t k = 0; k < rest.points.size(); ++k) CHECK((k == 11) == (moved.points[k] != rest.points[k])); // (2, 1, 1) is 11

        // det J at every vertex, here, in double: 1 outside the box (`keep`), the polynomial inside.
        double lo = INFINITY, hi = -INFINITY, nearZero = INFINITY;
        std::size_t folds = 0;
        for (const Eigen::Vector3d& p : vertices) {
            const Eigen::Vector3d x = moved.coordinates(p);
            const bool inside = (x.array() >= 0).all() && (x.array() <= 1).all();
            const double d = inside ? moved.detJ(x) : 1.0;
            lo = std::min(lo, d);
            hi = std::max(hi, d);
            folds += d <= 0;
            nearZero = std::min(nearZero, std::abs(d));
        }
        INFO("det J here in [" << lo << ", " << hi << "], " << folds << " fold-overs");
        REQUIRE(folds > 0);
        REQUIRE(nearZero > 1e-3); // no vertex so close to 0 that float could count it otherwise

        const Json& out = r.state["lattice_readout"];
        REQUIRE(out.is_object());
        INFO(out.dump());
        CHECK(out["vertices"] == vertices.size());
        CHECK(out["outside"] == outside);
        CHECK_THAT(out["det_j_min"].get<double>(), WithinAbs(lo, 1e-4 * std::max(1.0, std::abs(lo)))); // the view computes in float
        CHECK_THAT(out["det_j_max"].get<double>(), WithinAbs(hi, 1e-4 * std::max(1.0, std::abs(hi))));
        CHECK(out["fold_overs"] == folds);
        const double ms = out["update_ms"].get<double>();
        CHECK(ms >= 0);
        CHECK(ms < 1000);

        // The lines as drawn: the numbers above, in the panel's formats; the det J values read back
        // from the text agree with ours to its 4 significant digits.
        REQUIRE(out["lines"].size() == 3);
        char first[160];
        std::snprintf(first, sizeof first, "%zu vertices (%zu outside), update %.2f ms", vertices.size(), outside, ms);
        CHECK(out["lines"][0] == first);
        double textLo = 0, textHi = 0;
        REQUIRE(std::sscanf(out["lines"][1].get<std::string>().c_str(), "det J in [%lf, %lf]", &textLo, &textHi) == 2);
        CHECK_THAT(textLo, WithinAbs(lo, 1e-3 * std::max(1.0, std::abs(lo))));
        CHECK_THAT(textHi, WithinAbs(hi, 1e-3 * std::max(1.0, std::abs(hi))));
        CHECK(out["lines"][1] == format("det J in [%.4g, %.4g]", out["det_j_min"].get<double>(), out["det_j_max"].get<double>()));
        CHECK(out["lines"][2] == cat("fold-over: det J <= 0 at ", folds, " vertices"));

        // Red where the fold-over line is drawn (ImGui's text in (1, 0.35, 0.3)); the first line
        // above it is not red.
        const test::RgbImage image = test::loadPng(png);
        REQUIRE_FALSE(image.empty());
        auto redPixels = [&](const Json& rect) {
            int count = 0;
            const int x0 = int(rect[0].get<double>()), y0 = int(rect[1].get<double>());
            const int x1 = x0 + int(rect[2].get<double>()), y1 = y0 + int(rect[3].get<double>());
            for (int y = std::max(0, y0); y < std::min(image.height, y1); ++y)
                for (int x = std::max(0, x0); x < std::min(image.width, x1); ++x) {
                    const unsigned char* c = image.at(x, y);
                    count += c[0] > 180 && c[1] < 140 && c[2] < 140;
                }
            return count;
        };
        const Json& widgets = r.state["widgets"];
        REQUIRE(widgets.contains("fold-over"));
        REQUIRE(widgets.contains("read-out"));
        CHECK(redPixels(widgets["fold-over"]) >= 20);
        CHECK(redPixels(widgets["read-out"]) == 0);
    }
}

// ------------------------------------------------------------------ + / -: the proportional radius

TEST_CASE("+ and - scale the proportional-editing radius by 1.25; a drag then moves the neighbours by the falloff of that radius",
          "[render][replay][interaction]")
{
    // Nine control points on the x axis, 1 apart: the curve is the segment from -4 to 4, so the
    // scene's diagonal is 8 and the first radius (a quarter of it, docs/editor.md) is 2.
    Json points = Json::array();
    for (int i = 0; i < 9; ++i) points.push_back({i - 4.0, 0.0, 0.0});
    const std::string doc = writeDoc("radius", {{"format", "freeform"},
                                                {"version", 1},
                                                {"objects", Json::array({{{"name", "c"}, {"type", "bezier_curve"}, {"points", points}}})},
                                                {"editor", {{"camera", frontRightCamera(Eigen::Vector3d::Zero(), 12)}}}});
    const Scene scene = Scene::load(doc);
    const Eigen::Vector2d middle = worldToPixel(scene, kW, kH, Eigen::Vector3d::Zero());
    // Point 4 (the origin) clicked: the curve and the point are selected; O: proportional on.
    Json start = Json::array();
    click(start, middle);
    start.push_back(frames(2));
    start.push_back(key("O"));

    struct Case {
        const char* name;
        std::vector<std::string> keys;
        double radius;
    };
    const Case cases[] = {{"plus", {"Plus", "Plus"}, 2.0 * 1.25 * 1.25}, {"minus", {"Minus"}, 2.0 / 1.25}};
    for (const Case& c : cases) {
        DYNAMIC_SECTION(c.name)
        {
            Json events = start;
            for (const std::string& k : c.keys) events.push_back(key(k));
            drag(events, middle, middle + Eigen::Vector2d(0, -60)); // up on screen
            events.push_back(frames(2));
            const Run r = replayRun(doc, cat("radius_", c.name), events);
            CHECK(r.state["proportional"]["on"] == true);
            CHECK_THAT(r.state["proportional"]["radius"].get<double>(), WithinAbs(c.radius, 1e-9));
            const Json curve = objectNamed(r.saved, "c");
            REQUIRE(curve["points"].size() == 9);
            const Eigen::Vector3d delta = vec(curve["points"][4]) - Eigen::Vector3d::Zero();
            REQUIRE(delta.norm() > 0.1);
            int moved = 0;
            for (int i = 0; i < 9; ++i) {
                INFO("point " << i);
                const Eigen::Vector3d before(i - 4.0, 0, 0), expected = before + falloff(std::abs(i - 4.0), c.radius) * delta;
                CHECK((vec(curve["points"][i]) - expected).norm() < 1e-9);
                moved += vec(curve["points"][i]) != before;
            }
            // 2.5 + 0.625 = 3.125 reaches three neighbours on each side; 1.6 one.
            CHECK(moved == (c.radius > 3 ? 7 : 3));
        }
    }
}

// ------------------------------------------------------------------ Ctrl+Q

TEST_CASE("Ctrl+Q quits without unsaved changes; with them it asks, and the document keeps them", "[render][replay][files]")
{
    const std::string doc = writeDoc("quit", {{"format", "freeform"},
                                              {"version", 1},
                                              {"objects", Json::array({{{"name", "c"},
                                                                        {"type", "bezier_curve"},
                                                                        {"points", {{-2, 0, 0}, {-1, 0, 1.5}, {1, 0, 1.5}, {2, 0, 0}}}}})},
                                              {"editor", {{"camera", frontRightCamera(Eigen::Vector3d::Zero(), 8)}}}});
    const Scene scene = Scene::load(doc);

    SECTION("no changes: it quits, and a key after Ctrl+Q is never handled")
    {
        // W (wireframe) alone toggles the saved display; after Ctrl+Q it does not.
        const Run w = replayRun(doc, "quit_w", Json::array({key("W")}));
        CHECK(w.state["quit"] == false);
        const bool wireframe = w.saved["editor"]["display"]["wireframe"].get<bool>();
        const Run r = replayRun(doc, "quit_clean", Json::array({key("Q", {"ctrl"}), key("W")}));
        CHECK(r.state["quit"] == true);
        CHECK(r.state["unsaved_dialog"] == false);
        CHECK(r.saved["editor"]["display"]["wireframe"].get<bool>() == !wireframe);
    }

    SECTION("unsaved changes: the dialog, the editor stays; Escape (Cancel) keeps the change")
    {
        // The curve selected by a click on it (its middle, B(1/2) = (0, 0, 9/8)), then point 1
        // dragged: one change.
        const Eigen::Vector2d p1 = worldToPixel(scene, kW, kH, Eigen::Vector3d(-1, 0, 1.5));
        Json events = Json::array();
        click(events, worldToPixel(scene, kW, kH, Eigen::Vector3d(0, 0, 1.125)));
        events.push_back(frames(2));
        drag(events, p1, p1 + Eigen::Vector2d(30, -20));
        events.push_back(key("Q", {"ctrl"}));
        events.push_back(frames(3));
        const Run asked = replayRun(doc, "quit_asked", events);
        CHECK(asked.state["unsaved_dialog"] == true);
        CHECK(asked.state["quit"] == false);
        CHECK(asked.state["modified"] == true);

        events.push_back(key("Escape"));
        events.push_back(frames(3));
        const Run cancelled = replayRun(doc, "quit_cancelled", events);
        CHECK(cancelled.state["unsaved_dialog"] == false);
        CHECK(cancelled.state["quit"] == false);
        CHECK(cancelled.state["modified"] == true);
        const Json curve = objectNamed(cancelled.saved, "c");
        REQUIRE(curve.is_object());
        CHECK((vec(curve["points"][1]) - Eigen::Vector3d(-1, 0, 1.5)).norm() > 0.1); // the drag is kept
        CHECK(vec(curve["points"][0]) == Eigen::Vector3d(-2, 0, 0));
    }
}

TEST_CASE("L frames the view on a fitted lattice that does not fit in it, and leaves a view that holds it",
          "[render][replay][ffd]")
{
    // The bumpy sphere seen from the front right at distance 3.2 (close: the sphere fills the
    // view) and at 12 (far): L fits a lattice with the panel's margin around it.
    const std::string mesh = cat(FREEFORM_SOURCE_DIR, "/data/meshes/sphere.obj");
    for (const double distance : {3.2, 12.0}) {
        INFO(distance);
        const std::string doc = writeDoc(cat("frame_fit_", distance),
                                         {{"format", "freeform"},
                                          {"version", 1},
                                          {"objects", Json::array()},
                                          {"editor",
                                           {{"camera", frontRightCamera(Eigen::Vector3d::Zero(), distance)},
                                            {"meshes", Json::array({{{"name", "sphere"}, {"path", mesh}}})}}}});
        Json events = Json::array();
        click(events, Eigen::Vector2d(kW / 2.0, kH / 2.0)); // the sphere
        events.push_back(key("L"));
        events.push_back(frames(2));
        const Run r = replayRun(doc, cat("frame_fit_", distance), events);
        const Json lattice = objectNamed(r.saved, "sphere_lattice");
        REQUIRE(lattice.is_object());
        const std::string saved = cat(kTmp, "/promises_last_frame_fit_saved.json");
        test::writeText(saved, r.saved.dump(1));
        const Scene after = Scene::load(saved);
        // Every control point of the lattice inside the window, computed here from the saved camera.
        for (const Json& p : lattice["points"]) {
            const Eigen::Vector2d px = worldToPixel(after, kW, kH, vec(p));
            CHECK(px.x() >= 0);
            CHECK(px.x() <= kW);
            CHECK(px.y() >= 0);
            CHECK(px.y() <= kH);
        }
        if (distance == 12.0) CHECK(r.state["camera"]["distance"] == Approx(12.0)); // it held the lattice already
        else CHECK(r.state["camera"]["distance"].get<double>() > 3.2);
    }
}

} // namespace test_render_promises_last
