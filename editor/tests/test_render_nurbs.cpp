// Replayed sessions of the NURBS tool (label "render": they need an X display). Each runs
// build/bin/freeform-editor FILE --replay EVENTS.json --save OUT.json and checks the saved document
// with the command-line tool (`freeform eval`) and hand geometry:
//   - a circle drawn with Shift+O and two clicks: every point `freeform eval` gives at 33
//     parameters lies at the radius from the centre to 1e-14 relative and in the view plane, the
//     centre and the radius being where the clicks' rays meet the plane through the scene's centre
//     (computed here from the camera); Ctrl+Z gives the file back byte for byte;
//   - an arc drawn with Shift+U and three clicks: the same, and it starts under the second click;
//   - Alt + drag of a control point 100 pixels up: its weight is the old one times e (to 1e-15
//     relative), the other weights and every point unchanged;
//   - K on a NURBS curve selected by a click: the knot is inserted, and `freeform eval` gives the
//     same points before and after at 41 parameters to 1e-13.

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "interaction/picking.h"
#include "interaction/replay.h"
#include "scene/scene.h"
#include "support/editor_process.h"
#include "support/process.h"

namespace test_render_nurbs {

using namespace freeform;
using namespace freeform::editor;
using JsonR = nlohmann::ordered_json;

namespace {

namespace fs = std::filesystem;

const std::string kTmp = FREEFORM_TEST_TMP;
constexpr int kW = 1280, kH = 800;

template <typename... Parts>
std::string cat(const Parts&... parts)
{
    std::ostringstream s;
    (s << ... << parts);
    return s.str();
}

test::ProcessResult runEditor(const std::string& arguments) { return test::runEditorBinary(arguments); }

/// A camera looking from the front right above.
JsonR camera(const Eigen::Vector3d& target, double distance)
{
    const Eigen::Vector3d back = Eigen::Vector3d(1, -2, 1).normalized(), right = Eigen::Vector3d(2, 1, 0).normalized();
    Eigen::Matrix3d frame;
    frame << right, back.cross(right), back;
    const Eigen::Quaterniond q(frame);
    return {{"target", {target.x(), target.y(), target.z()}}, {"distance", distance}, {"orientation", {q.w(), q.x(), q.y(), q.z()}},
            {"fovy", 35.0}, {"projection", "perspective"}, {"orbit", "turntable"}};
}

std::string writeDocument(const std::string& name, const JsonR& j)
{
    const std::string source = cat(kTmp, "/nurbs_", name, ".source.json"), doc = cat(kTmp, "/nurbs_", name, ".json");
    test::writeText(source, j.dump(2));
    const auto r = runEditor(cat("'", source, "' --save '", doc, "'"));
    INFO(r.err);
    REQUIRE(r.status == 0);
    return doc;
}

std::string replay(const std::string& doc, const std::string& name, const JsonR& events)
{
    const std::string file = cat(kTmp, "/nurbs_", name, ".events.json"), out = cat(kTmp, "/nurbs_", name, ".out.json");
    test::writeText(file, JsonR{{"events", events}}.dump(1));
    fs::remove(out);
    const auto r = runEditor(cat("'", doc, "' --replay '", file, "' --save '", out, "' --size ", kW, "x", kH));
    INFO(r.err);
    REQUIRE(r.status == 0);
    REQUIRE(fs::exists(out));
    return out;
}

JsonR move(const Eigen::Vector2d& p) { return {{"type", "move"}, {"x", p.x()}, {"y", p.y()}}; }
JsonR press(const Eigen::Vector2d& p, const std::vector<std::string>& mods = {})
{
    JsonR e = {{"type", "press"}, {"button", "left"}, {"x", p.x()}, {"y", p.y()}};
    if (!mods.empty()) e["mods"] = mods;
    return e;
}
JsonR release(const Eigen::Vector2d& p) { return {{"type", "release"}, {"button", "left"}, {"x", p.x()}, {"y", p.y()}}; }
JsonR key(const std::string& k, const std::vector<std::string>& mods = {})
{
    JsonR e = {{"type", "key"}, {"key", k}};
    if (!mods.empty()) e["mods"] = mods;
    return e;
}
JsonR frames(int count) { return {{"type", "frame"}, {"count", count}}; }

void click(JsonR& events, const Eigen::Vector2d& p)
{
    events.push_back(move(p));
    events.push_back(press(p));
    events.push_back(release(p));
    events.push_back(frames(1));
}

Eigen::Vector3d vec(const JsonR& p) { return {p[0].get<double>(), p[1].get<double>(), p[2].get<double>()}; }

/// `freeform eval DOC --object NAME --at T`: the point.
Eigen::Vector3d cliEval(const std::string& doc, const std::string& name, double t)
{
    const auto r = test::cli(cat("eval '", doc, "' --object ", name, " --at ", JsonR(t).dump()));
    INFO(r.err);
    REQUIRE(r.status == 0);
    return vec(JsonR::parse(r.out)["point"]);
}

const JsonR& objectNamed(const JsonR& doc, const std::string& name)
{
    for (const JsonR& o : doc["objects"])
        if (o["name"] == name) return o;
    FAIL("no object " << name);
    return doc;
}

/// A scene whose bounds are the control net of one cubic (the curve lies inside it).
JsonR baseDocument()
{
    return {{"format", "freeform"},
            {"version", 1},
            {"objects", {{{"name", "c"}, {"type", "bezier_curve"}, {"points", {{-2, 0, 0}, {-1, 0, 1.5}, {1, 0, 1.5}, {2, 0, 0}}}}}},
            {"editor", {{"camera", camera({0, 0, 0.75}, 9)}}}};
}

/// Where the ray through pixel `at` meets the plane through the scene's centre orthogonal to the
/// view: the camera's own formulas (picking.h), not the tool's code.
Eigen::Vector3d onViewPlane(const Scene& scene, const Eigen::Vector2d& at)
{
    const ViewTransform view = ViewTransform::of(scene, kW, kH);
    Eigen::Vector3d origin, direction;
    view.ray(at.x(), at.y(), origin, direction);
    const Eigen::Vector3d n = scene.camera.back(), q = scene.bounds().center();
    return origin + ((q - origin).dot(n) / direction.dot(n)) * direction;
}

} // namespace

TEST_CASE("a circle drawn with Shift+O and two clicks is exact by freeform eval", "[render][replay][nurbs]")
{
    const std::string doc = writeDocument("circle", baseDocument());
    Scene scene = Scene::load(doc);
    scene.updateGeometry();
    const Eigen::Vector2d centreAt(640.5, 400.25), rimAt(820, 330.75);
    JsonR events = JsonR::array();
    events.push_back(key("O", {"shift"}));
    click(events, centreAt);
    click(events, rimAt);
    const std::string out = replay(doc, "circle", events);
    const JsonR saved = JsonR::parse(test::slurp(out));
    REQUIRE(saved["objects"].size() == 2);
    const JsonR& circle = saved["objects"][1];
    CHECK(circle["type"] == "nurbs_curve");
    const std::string name = circle["name"].get<std::string>();
    const Eigen::Vector3d c = onViewPlane(scene, centreAt), rim = onViewPlane(scene, rimAt);
    const double r = (rim - c).norm();
    const Eigen::Vector3d n = scene.camera.back();
    for (int k = 0; k <= 32; ++k) {
        const Eigen::Vector3d p = cliEval(out, name, k / 32.0);
        INFO("T = " << k / 32.0 << ": " << p.transpose());
        CHECK(std::abs((p - c).norm() - r) <= 1e-14 * r);
        CHECK(std::abs((p - c).dot(n)) <= 1e-14 * r);
    }
    CHECK((worldToPixel(scene, kW, kH, cliEval(out, name, 0)) - rimAt).norm() < 1e-6);
    JsonR undone = events;
    undone.push_back(key("Z", {"ctrl"}));
    CHECK(test::slurp(replay(doc, "circle_undo", undone)) == test::slurp(doc));
}

TEST_CASE("an arc drawn with Shift+U and three clicks is exact by freeform eval", "[render][replay][nurbs]")
{
    const std::string doc = writeDocument("arc", baseDocument());
    Scene scene = Scene::load(doc);
    scene.updateGeometry();
    const Eigen::Vector2d centreAt(600, 420), startAt(760, 420), endAt(520, 300);
    JsonR events = JsonR::array();
    events.push_back(key("U", {"shift"}));
    click(events, centreAt);
    click(events, startAt);
    click(events, endAt);
    const std::string out = replay(doc, "arc", events);
    const JsonR saved = JsonR::parse(test::slurp(out));
    REQUIRE(saved["objects"].size() == 2);
    const JsonR& arc = saved["objects"][1];
    const std::string name = arc["name"].get<std::string>();
    const double end = arc["type"] == "nurbs_curve" ? arc["knots"].back().get<double>() : 1.0;
    const Eigen::Vector3d c = onViewPlane(scene, centreAt), start = onViewPlane(scene, startAt), stop = onViewPlane(scene, endAt);
    const double r = (start - c).norm();
    for (int k = 0; k <= 32; ++k) {
        const Eigen::Vector3d p = cliEval(out, name, end * k / 32.0);
        CHECK(std::abs((p - c).norm() - r) <= 1e-14 * r);
        CHECK(std::abs((p - c).dot(scene.camera.back())) <= 1e-14 * r);
    }
    CHECK((cliEval(out, name, 0) - start).norm() < 1e-12 * r);
    // It ends on the ray from the centre through the third click.
    const Eigen::Vector3d last = cliEval(out, name, end);
    CHECK(((last - c).normalized() - (stop - c).normalized()).norm() < 1e-12);
}

TEST_CASE("Alt + drag 100 pixels up multiplies a weight by e; K inserts a knot, shape unchanged", "[render][replay][nurbs]")
{
    JsonR j = baseDocument();
    j["objects"].push_back({{"name", "wave"}, {"type", "nurbs_curve"}, {"degree", 3}, {"knots", {0, 0, 0, 0, 1, 2, 2, 3, 3, 3, 3}},
                            {"points", {{-2, 0, 0}, {-1.5, 0, 1}, {-0.5, 0, -0.5}, {0, 0, 1}, {1, 0, 0.2}, {1.5, 0, 1.2}, {2, 0, 0.1}}},
                            {"weights", {1, 1.5, 1, 0.75, 1, 1, 1}}});
    const std::string doc = writeDocument("weights", j);
    Scene scene = Scene::load(doc);
    scene.updateGeometry();
    SECTION("weight")
    {
        const Eigen::Vector2d at = worldToPixel(scene, kW, kH, Eigen::Vector3d(-0.5, 0, -0.5)); // point 2
        JsonR events = JsonR::array();
        events.push_back(move(at));
        events.push_back(frames(1));
        events.push_back(press(at, {"alt"}));
        events.push_back(move(at + Eigen::Vector2d(3, -40)));
        events.push_back(move(at + Eigen::Vector2d(5, -100)));
        events.push_back(release(at + Eigen::Vector2d(5, -100)));
        const std::string out = replay(doc, "weight", events);
        const JsonR before = JsonR::parse(test::slurp(doc)), after = JsonR::parse(test::slurp(out));
        const JsonR& w0 = objectNamed(before, "wave")["weights"];
        const JsonR& w1 = objectNamed(after, "wave")["weights"];
        REQUIRE(w1.size() == 7);
        for (std::size_t k = 0; k < 7; ++k) {
            INFO("weight " << k);
            if (k == 2) CHECK(std::abs(w1[k].get<double>() - std::exp(1.0)) <= 1e-15 * std::exp(1.0));
            else CHECK(w1[k] == w0[k]);
        }
        CHECK(objectNamed(after, "wave")["points"] == objectNamed(before, "wave")["points"]);
        CHECK(objectNamed(after, "wave")["knots"] == objectNamed(before, "wave")["knots"]);
        // One undo step takes the whole drag back.
        JsonR undone = events;
        undone.push_back(key("Z", {"ctrl"}));
        CHECK(test::slurp(replay(doc, "weight_undo", undone)) == test::slurp(doc));
    }
    SECTION("knot")
    {
        std::vector<Eigen::Vector3d> before;
        for (int k = 0; k <= 40; ++k) before.push_back(cliEval(doc, "wave", 3.0 * k / 40));
        // Click on the curve (its point at T = 1.3) to select it, K inserts at the slider (t = 0.5: T = 1.5).
        const Eigen::Vector2d at = worldToPixel(scene, kW, kH, cliEval(doc, "wave", 1.3));
        JsonR events = JsonR::array();
        click(events, at);
        events.push_back(key("K"));
        const std::string out = replay(doc, "knot", events);
        const JsonR after = JsonR::parse(test::slurp(out));
        CHECK(objectNamed(after, "wave")["knots"] == JsonR({0, 0, 0, 0, 1, 1.5, 2, 2, 3, 3, 3, 3}));
        for (int k = 0; k <= 40; ++k) CHECK((cliEval(out, "wave", 3.0 * k / 40) - before[static_cast<std::size_t>(k)]).norm() < 1e-13);
    }
}

} // namespace test_render_nurbs
