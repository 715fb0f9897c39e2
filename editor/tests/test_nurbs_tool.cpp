// The editor on rational Bézier and NURBS objects (NurbsTool, tools/nurbs_tool.h; docs/editor.md
// "Rational and NURBS objects"), without a window: driven through the tools' entry points on a
// Scene, checked against independent values:
//   - the four types are drawn (curve polylines on the exact circle to 1e-12, the sphere's
//     triangle vertices at radius 1), their control points move, and saving writes back every
//     number as read (the objects compared as JSON values with the source file);
//   - weights: a quadratic rational arc's mid point with a typed middle weight w against the
//     hand formula (b0 + 2 w b1 + b2) / (2 + 2 w); a weight that is not positive is refused and
//     leaves the document as it was; one undo step each;
//   - knot insertion (curve and surface, both directions): points before and after, by the
//     document layer's evaluation, equal to 1e-13 at 201 (curve) and 21 x 21 (surface) parameters;
//     one undo step that gives the text back byte for byte;
//   - exact circles and arcs (circleData, arcData): every evaluated point at the radius to 1e-14
//     relative and in the plane, the arc's end angle where it was asked;
//   - the de Boor overlay: its last point is the curve point at the slider's parameter (library
//     evaluation) for a polynomial and a rational curve, with p (p + 1) / 2 construction points;
//   - the knot display: one dot per distinct knot, one tick per unit of multiplicity;
//   - the curvature comb: a circle's teeth radial and of one length, a rational cubic's in the
//     ratio of its curvature by differences, a step at its C1 knot;
//   - FFD "apply exactly" on 3D NURBS and rational curves: number for number what `freeform ffd`
//     writes, and at sample parameters what Lattice::deform gives point by point (1e-9).

#include <catch2/catch.hpp>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <freeform/core/transform.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "freeform/document/operations.h"
#include "freeform/io/geometry_data.h"
#include "support/process.h"
#include "support/tool_bench.h"
#include "tools/tools.h"

namespace test_nurbs_tool {

using namespace freeform;
using namespace freeform::editor;
using namespace freeform::editor::tool_test;
using JsonV = nlohmann::json; // key order ignored (the editor's Json keeps it)
using tool_util::kComb;
using tool_util::sceneSize;

namespace {

const std::string kTmp = FREEFORM_TEST_TMP;
const std::string kSource = FREEFORM_SOURCE_DIR;
constexpr double kPi = 3.14159265358979323846;

const std::string kExample = kSource + "/examples/data/nurbs.json";

Scene example() { return Scene::load(kExample); }

JsonV objectsOf(const std::string& path)
{
    JsonV j = JsonV::parse(test::slurp(path));
    JsonV out = j["objects"];
    for (JsonV& o : out) o.erase("editor");
    return out;
}

} // namespace

TEST_CASE("nurbs editor: the four types are drawn, move and are saved back exactly", "[editor][nurbs]")
{
    Bench b(example());
    b.update();
    for (int i = 0; i < b.scene.itemCount(); ++i) {
        INFO(b.scene.item(i).name);
        CHECK(b.scene.item(i).geometry.error.empty());
        CHECK(b.scene.item(i).geometry.netPoints.cols() == b.scene.controlPointCount(i));
    }
    // The unit circle about the origin: its polyline's points on the circle.
    const ItemGeometry& circle = b.scene.item(findItem(b.scene, "circle")).geometry;
    REQUIRE(circle.curve.cols() > 16);
    for (Eigen::Index k = 0; k < circle.curve.cols(); ++k) CHECK(std::abs(circle.curve.col(k).norm() - 1) < 1e-12);
    CHECK((circle.curve.col(0) - circle.curve.col(circle.curve.cols() - 1)).norm() < 1e-15); // closed
    CHECK(b.scene.item(findItem(b.scene, "arc")).geometry.curve.cols() > 4);
    CHECK(b.scene.item(findItem(b.scene, "wave")).geometry.curve.cols() > 8);
    // The sphere of radius 1 about (4, 0, 0): every vertex of its tessellation on it.
    const auto& sphere = b.scene.item(findItem(b.scene, "sphere")).geometry.surface;
    REQUIRE(sphere);
    REQUIRE(sphere->faceCount() > 50);
    for (Eigen::Index k = 0; k < sphere->positions.cols(); ++k)
        CHECK(std::abs((sphere->positions.col(k) - Eigen::Vector3d(4, 0, 0)).norm() - 1) < 1e-12);
    REQUIRE(b.scene.item(findItem(b.scene, "cyl")).geometry.surface);

    // Saved without a change: every object as read, value for value.
    const std::string out = kTmp + "/nurbs_saved.json";
    b.scene.save(out);
    CHECK(objectsOf(out) == objectsOf(kExample));

    // A control point moved: only that point changes, the weights and knots stay.
    const int wave = findItem(b.scene, "wave");
    b.scene.setControlPoint(wave, 2, Eigen::Vector3d(-2, -5, 0.5));
    b.scene.save(out);
    JsonV expected = objectsOf(kExample);
    expected[2]["points"][2] = {-2, -5, 0.5};
    CHECK(objectsOf(out) == expected);
}

TEST_CASE("nurbs editor: typed weights give the hand formula; a weight <= 0 is refused", "[editor][nurbs]")
{
    Bench b(example());
    const int arc = b.select("arc", {1});
    const std::string before = b.scene.text();
    const std::size_t steps = b.scene.history().size();
    REQUIRE(b.tools.nurbs().setWeights(b.context, arc, {1}, 3.0));
    CHECK(b.scene.history().size() == steps + 1);
    CHECK(NurbsTool::weightsOf(b.scene, arc) == std::vector<double>{1, 3, 1});
    // Quadratic rational Bézier at t = 1/2: (b0 + 2 w b1 + b2) / (2 + 2 w), b = (0,-3), (0,-2), (-1,-2).
    const double w = 3;
    const Eigen::Vector3d hand = (Eigen::Vector3d(0, -3, 0) + 2 * w * Eigen::Vector3d(0, -2, 0) + Eigen::Vector3d(-1, -2, 0)) / (2 + 2 * w);
    CHECK((b.eval("arc", {0.5}) - hand).norm() < 1e-15);
    // Not positive, not finite: refused, the document as it was.
    const std::string edited = b.scene.text();
    CHECK_FALSE(b.tools.nurbs().setWeights(b.context, arc, {1}, 0.0));
    CHECK_FALSE(b.tools.nurbs().setWeights(b.context, arc, {1}, -2.0));
    CHECK_FALSE(b.tools.nurbs().setWeights(b.context, arc, {1}, std::nan("")));
    CHECK_FALSE(b.tools.nurbs().setWeights(b.context, arc, {7}, 2.0));
    CHECK(b.scene.text() == edited);
    CHECK_FALSE(b.tools.message().empty());
    REQUIRE(b.scene.undo());
    CHECK(b.scene.text() == before);

    // A NURBS curve without stored weights gets all of them (the others 1) on the first edit.
    const int wave = b.select("wave", {0, 3});
    REQUIRE(b.tools.nurbs().scaleWeights(b.context, wave, {0, 3}, {1, 1}, 0.5));
    CHECK(NurbsTool::weightsOf(b.scene, wave) == std::vector<double>{0.5, 1, 2, 0.5, 0.5, 1, 1, 1});
}

TEST_CASE("nurbs editor: knot insertion keeps the curve and the surface, one undo step", "[editor][nurbs]")
{
    Bench b(example());
    SECTION("curve")
    {
        b.select("wave");
        std::vector<Eigen::VectorXd> before;
        for (int k = 0; k <= 200; ++k) before.push_back(b.eval("wave", {4.0 * k / 200}));
        const std::string text = b.scene.text();
        const std::size_t steps = b.scene.history().size();
        b.tools.nurbs().t = 0.375; // u = 1.5 on [0, 4]
        CHECK(b.tools.nurbs().sliderParameter(b.context) == 1.5);
        REQUIRE(b.tools.onKey(b.context, GLFW_KEY_K, 0));
        CHECK(b.scene.history().size() == steps + 1);
        const auto& d = std::get<NurbsCurveData>(b.scene.object(b.selection.item).data);
        CHECK(d.knots == std::vector<double>{0, 0, 0, 0, 1, 1.5, 2, 2, 3, 4, 4, 4, 4});
        CHECK(d.points.cols() == 9);
        for (int k = 0; k <= 200; ++k) CHECK((b.eval("wave", {4.0 * k / 200}) - before[static_cast<std::size_t>(k)]).norm() < 1e-13);
        // At an existing knot (multiplicity 2 -> 3 = p): the shape stays too.
        REQUIRE(b.tools.nurbs().insertKnot(b.context, 2.0));
        for (int k = 0; k <= 200; ++k) CHECK((b.eval("wave", {4.0 * k / 200}) - before[static_cast<std::size_t>(k)]).norm() < 1e-13);
        REQUIRE(b.scene.undo());
        REQUIRE(b.scene.undo());
        CHECK(b.scene.text() == text);
        // Outside the domain: refused, nothing changes.
        CHECK_FALSE(b.tools.nurbs().insertKnot(b.context, 4.0));
        CHECK(b.scene.text() == text);
    }
    SECTION("2D curve (the circle of docs/format.md)")
    {
        NurbsCurveData d;
        d.degree = 2;
        d.knots = {0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4};
        d.points.resize(2, 9);
        d.points << 1, 1, 0, -1, -1, -1, 0, 1, 1, 0, 1, 1, 1, 0, -1, -1, -1, 0;
        const double h = std::sqrt(0.5);
        d.weights = {1, h, 1, h, 1, h, 1, h, 1};
        b.selection.selectItem(b.scene.addObject({"flat", d, ""}));
        REQUIRE(b.tools.nurbs().insertKnot(b.context, 0.5));
        const auto& after = std::get<NurbsCurveData>(b.scene.object(b.selection.item).data);
        CHECK(after.points.rows() == 2);
        CHECK(after.points.cols() == 10);
        for (int k = 0; k <= 64; ++k) CHECK(std::abs(b.eval("flat", {4.0 * k / 64}).norm() - 1) < 1e-15 * 2);
    }
    SECTION("surface, in u and in v")
    {
        b.select("sphere");
        auto grid = [&] {
            std::vector<Eigen::VectorXd> out;
            for (int i = 0; i <= 20; ++i)
                for (int j = 0; j <= 20; ++j) out.push_back(b.eval("sphere", {4.0 * i / 20, 2.0 * j / 20}));
            return out;
        };
        const auto before = grid();
        const std::string text = b.scene.text();
        b.tools.nurbs().direction = 0;
        b.tools.nurbs().t = 0.3; // u = 1.2
        REQUIRE(b.tools.onKey(b.context, GLFW_KEY_K, 0));
        b.tools.nurbs().direction = 1;
        b.tools.nurbs().t = 0.3; // v = 0.6
        REQUIRE(b.tools.onKey(b.context, GLFW_KEY_K, 0));
        const auto& d = std::get<NurbsSurfaceData>(b.scene.object(b.selection.item).data);
        CHECK(d.rows == 10);
        CHECK(d.cols == 6);
        CHECK(std::count(d.knots[0].begin(), d.knots[0].end(), 1.2) == 1);
        CHECK(std::count(d.knots[1].begin(), d.knots[1].end(), 0.6) == 1);
        const auto after = grid();
        for (std::size_t k = 0; k < before.size(); ++k) CHECK((after[k] - before[k]).norm() < 1e-13);
        REQUIRE(b.scene.undo());
        REQUIRE(b.scene.undo());
        CHECK(b.scene.text() == text);
    }
}

TEST_CASE("nurbs editor: circles and arcs are exact", "[editor][nurbs]")
{
    const Eigen::Vector3d c(0.3, -1.7, 2.25), n = Eigen::Vector3d(1, -2, 0.5).normalized();
    const Eigen::Vector3d a = n.unitOrthogonal(), b = n.cross(a);
    const double r = 1.75;
    auto check = [&](const ObjectData& data, double sweep) {
        TypedDocument doc;
        const TypedObject& o = doc.object(doc.add("c", data));
        const double end = parameterDomain(o).back();
        for (int k = 0; k <= 64; ++k) {
            const Eigen::Vector3d p = evaluate(doc, o, {end * k / 64}, 0).point;
            CHECK(std::abs((p - c).norm() - r) < 1e-14 * r);
            CHECK(std::abs((p - c).dot(n)) < 1e-14 * r);
        }
        const Eigen::Vector3d first = evaluate(doc, o, {0}, 0).point, last = evaluate(doc, o, {end}, 0).point;
        CHECK((first - (c + r * a)).norm() < 1e-14 * r);
        CHECK((last - (c + r * std::cos(sweep) * a + r * std::sin(sweep) * b)).norm() < 1e-14 * r);
    };
    check(circleData(c, r, a, b), 2 * kPi);
    const ObjectData quarter = arcData(c, r, a, b, 1.2);
    CHECK(std::holds_alternative<RationalBezierCurveData>(quarter));
    check(quarter, 1.2);
    const ObjectData large = arcData(c, r, a, b, 4.5);
    REQUIRE(std::holds_alternative<NurbsCurveData>(large));
    CHECK(std::get<NurbsCurveData>(large).knots == std::vector<double>{0, 0, 0, 1, 1, 2, 2, 3, 3, 3});
    check(large, 4.5);
    CHECK_THROWS_AS(arcData(c, r, a, b, 0), Error);
}

TEST_CASE("nurbs editor: circle and arc by clicks in the hand view", "[editor][nurbs]")
{
    Bench b(Scene{});
    // The top view (looking along -z, as the hand view): the clicks land on the plane through the
    // empty scene's centre (its bounds are the box [-1, 1]^3), z = 0.
    b.scene.camera.setView("top");
    auto ray = [](double x, double y) {
        PointerEvent e;
        e.type = PointerEvent::Type::Press;
        e.button = 0;
        e.x = 100 * (x + 4);
        e.y = 100 * (2.5 - y);
        e.rayOrigin = Eigen::Vector3d(x, y, 10);
        e.rayDirection = -Eigen::Vector3d::UnitZ();
        return e;
    };
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_O, GLFW_MOD_SHIFT));
    CHECK(b.tools.nurbs().creating());
    const Eigen::Vector3d centre = b.scene.bounds().center();
    CHECK(b.tools.onPointer(b.context, ray(1, 0.5)));
    CHECK(b.tools.onPointer(b.context, ray(1, 2)));
    CHECK_FALSE(b.tools.nurbs().creating());
    REQUIRE(b.scene.itemCount() == 1);
    CHECK(b.scene.item(0).type == "nurbs_curve");
    for (int k = 0; k <= 32; ++k) {
        const Eigen::VectorXd p = b.eval(b.scene.item(0).name, {k / 32.0});
        CHECK(std::abs((p - Eigen::Vector3d(1, 0.5, centre.z())).norm() - 1.5) < 1e-14 * 1.5);
    }
    // Arc: centre (0, 0), start (2, 0), end (0, -2): three quarters counter-clockwise about +z.
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_U, GLFW_MOD_SHIFT));
    b.tools.onPointer(b.context, ray(0, 0));
    b.tools.onPointer(b.context, ray(2, 0));
    b.tools.onPointer(b.context, ray(0, -2));
    REQUIRE(b.scene.itemCount() == 2);
    CHECK(b.scene.item(1).type == "nurbs_curve");
    const auto& d = std::get<NurbsCurveData>(b.scene.object(1).data);
    CHECK(d.knots.back() == 3);
    CHECK((b.eval(b.scene.item(1).name, {3.0}) - Eigen::Vector3d(0, -2, centre.z())).norm() < 1e-14);
    CHECK((b.eval(b.scene.item(1).name, {1.0}) - Eigen::Vector3d(0, 2, centre.z())).norm() < 1e-14);
    // Escape cancels a creation; undo removes the arc.
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_O, GLFW_MOD_SHIFT));
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_ESCAPE, 0));
    CHECK_FALSE(b.tools.nurbs().creating());
    REQUIRE(b.scene.undo());
    CHECK(b.scene.itemCount() == 1);
}

TEST_CASE("nurbs editor: the de Boor overlay ends at the curve point; knots drawn with their multiplicity", "[editor][nurbs]")
{
    Bench b(example());
    for (const char* name : {"wave", "circle", "arc"}) {
        INFO(name);
        b.select(name);
        b.tools.nurbs().construction = false;
        b.tools.nurbs().showKnots = false;
        REQUIRE(b.tools.onKey(b.context, GLFW_KEY_T, 0));
        CHECK(b.tools.nurbs().construction);
        b.tools.nurbs().t = 0.3;
        b.update();
        const ObjectData& data = b.scene.object(b.selection.item).data;
        const int p = std::holds_alternative<NurbsCurveData>(data) ? std::get<NurbsCurveData>(data).degree : 2;
        const double end = std::string(name) == "arc" ? 1 : 4; // wave, circle: knots 0..4
        REQUIRE(b.overlay.points.positions.cols() == p * (p + 1) / 2);
        const Eigen::Vector3d last = b.overlay.points.positions.col(b.overlay.points.positions.cols() - 1).cast<double>();
        const Eigen::Vector3d expected = b.eval(name, {0.3 * end});
        INFO(last.transpose() << " vs " << expected.transpose());
        CHECK((last - expected).norm() < 1e-5);
    }
    // The wave's knots 0 (x4), 1, 2 (x2), 3, 4 (x4): five dots, 12 ticks.
    b.select("wave");
    b.tools.nurbs().construction = false;
    b.tools.nurbs().showKnots = true;
    b.update();
    CHECK(b.overlay.points.positions.cols() == 5);
    CHECK(b.overlay.linesOnTop.positions.cols() == 2 * 12);
    for (int k = 0; k < 5; ++k)
        CHECK((b.overlay.points.positions.col(k).cast<double>() - b.eval("wave", {double(k)})).norm() < 1e-5);
    // A surface: isolines at its knots (sphere: u 0, 1, 2, 3, 4 and v 0, 1, 2), 64 segments each.
    b.select("sphere");
    b.update();
    CHECK(b.overlay.lines.positions.cols() == 2 * 64 * 8);
}

namespace {

/// The comb's teeth in the overlay (kComb x 0.7, drawn on top): (base, tip) pairs in drawing order.
std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> teeth(const Overlay& o)
{
    std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> out;
    const Vec3f colour = kComb * 0.7f;
    for (Eigen::Index k = 0; k + 1 < o.linesOnTop.positions.cols(); k += 2)
        if (o.linesOnTop.colors.col(k) == colour)
            out.emplace_back(o.linesOnTop.positions.col(k).cast<double>(), o.linesOnTop.positions.col(k + 1).cast<double>());
    return out;
}

/// The curvature of object `name` at u by central differences of the library's points (step h).
double curvatureAt(Bench& b, const std::string& name, double u, double h = 1e-4)
{
    const Eigen::Vector3d p0 = b.eval(name, {u - h}), p1 = b.eval(name, {u}), p2 = b.eval(name, {u + h});
    const Eigen::Vector3d d1 = (p2 - p0) / (2 * h), d2 = (p2 - 2 * p1 + p0) / (h * h);
    return d1.cross(d2).norm() / std::pow(d1.norm(), 3);
}

} // namespace

TEST_CASE("nurbs editor: the curvature comb of NURBS and rational curves", "[editor][nurbs]")
{
    Bench b(example());
    // The circle (radius 1 about the origin, four spans): 49 teeth per span, all of one length
    // (0.15 of the scene), each radial and outward (the curvature vector points at the centre).
    b.select("circle");
    b.tools.nurbs().showKnots = false;
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_V, 0));
    REQUIRE(b.tools.nurbs().comb);
    b.update();
    auto circle = teeth(b.overlay);
    REQUIRE(circle.size() == 4 * 49);
    const double length = (circle.front().second - circle.front().first).norm();
    CHECK(length == Approx(0.15 * sceneSize(b.scene)).epsilon(1e-5));
    for (const auto& [base, tip] : circle) {
        CHECK(std::abs(base.norm() - 1) < 1e-6);
        CHECK((tip - base * (1 + length)).norm() < 1e-5);
    }
    // The rational wave (weights 1, 1, 2, 1, 0.5, 1, 1, 1; knots 0, 1, 2 twice, 3, 4): the teeth's
    // lengths in the ratio of the curvature by differences of the library's points, and at the
    // double knot u = 2 (C1 there) two teeth on one point whose lengths step by the curvature's jump.
    b.select("wave");
    b.update();
    const auto wave = teeth(b.overlay);
    REQUIRE(wave.size() == 4 * 49);
    auto len = [&](std::size_t i) { return (wave[i].second - wave[i].first).norm(); };
    const double k0 = curvatureAt(b, "wave", 0.5);
    for (const auto& [span, i] : {std::pair{1, 12}, std::pair{2, 24}, std::pair{3, 36}}) {
        const double u = span + i / 48.0;
        INFO("u = " << u);
        CHECK((wave[static_cast<std::size_t>(49 * span + i)].first - b.eval("wave", {u})).norm() < 1e-5);
        CHECK(len(static_cast<std::size_t>(49 * span + i)) / len(24) == Approx(curvatureAt(b, "wave", u) / k0).epsilon(1e-4));
    }
    const double left = curvatureAt(b, "wave", 2 - 2e-4), right = curvatureAt(b, "wave", 2 + 2e-4);
    CHECK(std::abs(left / right - 1) > 0.05); // a real jump, which a comb sampled across the knot would smooth
    CHECK((wave[97].first - wave[98].first).norm() < 1e-6);
    CHECK(len(97) / len(98) == Approx(left / right).epsilon(1e-2));
    // A polynomial spline is the curve tool's: the NURBS tool's V passes it on.
    Bench s(curveScene("comb_spline.json"));
    s.select("s");
    s.tools.nurbs().comb = false;
    s.tools.nurbs().onKey(s.context, KeyAction::Comb);
    CHECK_FALSE(s.tools.nurbs().comb);
}

TEST_CASE("nurbs editor: apply exactly turns NURBS and rational curves as freeform ffd does", "[editor][nurbs][ffd]")
{
    const std::string path = kTmp + "/nurbs_ffd.json";
    test::writeText(path, R"({"format": "freeform", "version": 1, "objects": [
      {"name": "wave", "type": "nurbs_curve", "degree": 3, "knots": [0,0,0,0,1,2,2,3,3,3,3],
       "points": [[0.1,0.2,0.3],[0.4,0.9,0.2],[0.8,0.1,0.5],[1.2,0.8,0.4],[1.5,0.3,0.9],[1.8,0.6,0.2],[1.9,0.1,0.7]],
       "weights": [1, 2, 0.5, 1, 1.5, 1, 1]},
      {"name": "arc", "type": "rational_bezier_curve", "points": [[1,0.2,0.5],[1,1,0.5],[0.2,1,0.5]], "weights": [1, 0.7071067811865476, 1]},
      {"name": "ball", "type": "nurbs_surface", "degree": [1, 1], "knots": [[0,0,1,1],[0,0,1,1]],
       "points": [[[0.2,0.2,0.2],[0.2,1,0.2]],[[1,0.2,0.2],[1,1,0.4]]]},
      {"name": "L", "type": "lattice", "degree": [2, 1, 1], "origin": [0, 0, 0], "axes": [[2, 0, 0], [0, 1.5, 0], [0, 0, 1]],
       "points": [[0,0,0],[0,0,1],[0,1.5,0],[0,1.5,1],[1,0.3,0],[1.2,0,1],[1,1.7,0],[0.9,1.5,1.3],[2,0,0],[2,0,1],[2,1.5,0],[2.4,1.5,1]]}
    ]})");
    Bench b(Scene::load(path));
    const int lattice = findItem(b.scene, "L");
    b.select("L");
    REQUIRE(b.tools.lattice().applyLatticeToObjects(b.context, lattice));
    const std::string editorOut = kTmp + "/nurbs_ffd.editor.json", cliOut = kTmp + "/nurbs_ffd.cli.json";
    b.scene.save(editorOut);
    const auto r = test::cli(cat("ffd '", path, "' --lattice '", path, "' -o '", cliOut, "'"));
    INFO(r.err);
    REQUIRE(r.status == 0);
    const JsonV e = objectsOf(editorOut), c = objectsOf(cliOut);
    REQUIRE(e.size() == c.size());
    for (std::size_t k = 0; k < e.size(); ++k) {
        INFO(e[k]["name"]);
        CHECK(e[k] == c[k]);
    }
    // Whatever deformDocument does with the surface, the editor keeps what it returns: here the
    // surface is unchanged exactly when the command line left it unchanged.
    CHECK((e[2] == objectsOf(path)[2]) == (c[2] == objectsOf(path)[2]));
    // Point by point: the deformed curves at sample parameters against Lattice::deform.
    const Lattice L = latticeFromData(std::get<LatticeData>(Scene::load(path).object(lattice).data));
    Bench original(Scene::load(path));
    for (const char* name : {"wave", "arc"}) {
        const double end = std::string(name) == "wave" ? 3 : 1;
        for (int k = 0; k <= 20; ++k) {
            const Eigen::Vector3d p = original.eval(name, {end * k / 20});
            CHECK((b.eval(name, {end * k / 20}) - L.deform(p).point).norm() < 1e-9);
        }
    }
}

} // namespace test_nurbs_tool
