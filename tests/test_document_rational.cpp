// The document layer (document/document.h) on the rational and NURBS object types, through every
// operation, as test_document_model.cpp does for the polynomial ones: evaluate (the quarter circle
// at t = 1/2 is (1/sqrt 2, 1/sqrt 2) by hand; a quadratic B-spline at a simple knot is the midpoint
// of its two middle points, Cox-de Boor by hand), continuity (C1 and not C2 at a simple knot of a
// quadratic), tessellate (every vertex of a quarter cylinder at radius 1), the control net (counts),
// convert (to NURBS and back, every number kept; convertObject's routes, a B-spline's Bezier joint by
// hand) and deformDocument under an affine lattice
// p -> 2 p + (1, 0, 0) (the images of the circles are circles of radius 2 around (1, 0, z); the
// surfaces are skipped with the documented reason, docs/ffd.md).

#include <catch2/catch.hpp>

#include <cmath>
#include <set>

#include "freeform/document/document.h"
#include "freeform/io/geometry_data.h"

namespace test_document_rational {

using namespace freeform;
using V3 = Eigen::Vector3d;

namespace {

const double kH = std::sqrt(0.5); // the middle weight of a quarter circle, cos 45 degrees

// The four rational and NURBS types and an affine lattice over [-2, 2]^3: p -> 2 p + (1, 0, 0).
const char* kDocument = R"({"format": "freeform", "version": 1, "objects": [
  {"name": "arc2", "type": "rational_bezier_curve", "points": [[1,0],[1,1],[0,1]], "weights": [1, 0.7071067811865476, 1]},
  {"name": "arc3", "type": "rational_bezier_curve", "points": [[1,0,0.5],[1,1,0.5],[0,1,0.5]], "weights": [1, 0.7071067811865476, 1]},
  {"name": "narc", "type": "nurbs_curve", "degree": 2, "knots": [0,0,0,1,1,1],
   "points": [[1,0,0.5],[1,1,0.5],[0,1,0.5]], "weights": [1, 0.7071067811865476, 1]},
  {"name": "bs", "type": "nurbs_curve", "degree": 2, "knots": [0,0,0,1,2,2,2],
   "points": [[0,0,0],[1,1,0],[2,-1,0.5],[3,0,1]]},
  {"name": "cyl", "type": "rational_bezier_surface", "degree": [2, 1],
   "points": [[[1,0,0],[1,0,1]],[[1,1,0],[1,1,1]],[[0,1,0],[0,1,1]]],
   "weights": [[1,1],[0.7071067811865476,0.7071067811865476],[1,1]]},
  {"name": "ncyl", "type": "nurbs_surface", "degree": [2, 1], "knots": [[0,0,0,1,1,1],[0,0,1,1]],
   "points": [[[1,0,0],[1,0,1]],[[1,1,0],[1,1,1]],[[0,1,0],[0,1,1]]],
   "weights": [[1,1],[0.7071067811865476,0.7071067811865476],[1,1]]},
  {"name": "L", "type": "lattice", "degree": [1, 1, 1], "origin": [-2, -2, -2], "axes": [[4,0,0],[0,4,0],[0,0,4]],
   "points": [[-3,-4,-4],[-3,-4,4],[-3,4,-4],[-3,4,4],[5,-4,-4],[5,-4,4],[5,4,-4],[5,4,4]], "outside": "keep"}
]})";

TypedDocument load() { return TypedDocument(parseDocument(kDocument, "r.json"), ""); }

} // namespace

TEST_CASE("rational and NURBS objects: evaluate against hand values", "[document][nurbs]")
{
    const TypedDocument doc = load();
    // The quarter circle at t = 1/2: Bernstein 1/4, 1/2, 1/4, so (1/4 + h/2) / (1/2 + h/2) in x and y,
    // which is 1/sqrt 2 for h = 1/sqrt 2.
    const double mid = (0.25 + kH / 2) / (0.5 + kH / 2);
    CHECK(std::abs(mid - kH) <= 1e-15);
    for (const char* name : {"arc2", "arc3", "narc"}) {
        INFO(name);
        const Evaluation e = evaluate(doc, doc.object(name), {0.5}, 1);
        CHECK(std::abs(e.point[0] - kH) <= 1e-15);
        CHECK(std::abs(e.point[1] - kH) <= 1e-15);
        // On a circle the velocity is orthogonal to the radius.
        REQUIRE(e.derivatives.size() == 1);
        CHECK(std::abs(e.derivatives[0].head<2>().dot(e.point.head<2>())) <= 1e-14);
        for (double t : {0.0, 0.2, 0.7, 1.0}) {
            const Evaluation p = evaluate(doc, doc.object(name), {t}, 0);
            CHECK(std::abs(p.point.head<2>().norm() - 1) <= 1e-15);
        }
    }
    // A quadratic B-spline at its simple knot u = 1 of {0,0,0,1,2,2,2}: N_1 = N_2 = 1/2 (Cox-de Boor
    // by hand), so (P1 + P2) / 2; the domain is [0, 2] and 2.5 is refused.
    const Evaluation k = evaluate(doc, doc.object("bs"), {1.0}, 0);
    CHECK((k.point - V3(1.5, 0, 0.25)).norm() <= 1e-15);
    CHECK_THROWS_AS(evaluate(doc, doc.object("bs"), {2.5}, 0), Error);
    // The cylinder patches at (1/2, v): the quarter circle's midpoint at height v.
    for (const char* name : {"cyl", "ncyl"}) {
        INFO(name);
        const Evaluation e = evaluate(doc, doc.object(name), {0.5, 0.25}, 0);
        CHECK((e.point - V3(kH, kH, 0.25)).norm() <= 1e-15);
    }
}

TEST_CASE("rational and NURBS objects: continuity at the knots, control nets", "[document][nurbs]")
{
    const TypedDocument doc = load();
    // A quadratic with a simple interior knot is C1: the first derivatives agree, the second jump
    // (P0..P3 are not on one parabola).
    const auto joints = continuity(doc, doc.object("bs"));
    REQUIRE(joints.size() == 1);
    CHECK(joints[0].t == 1.0);
    CHECK(joints[0].C == 1);
    CHECK(joints[0].G >= 1);

    // Nets: 3 points and 2 edges for the arcs (2D with z = 0), a 3 x 2 grid (3 + 4 edges) for the patches.
    const ControlNet arc = controlNet(doc.object("arc2"));
    CHECK(arc.points.cols() == 3);
    CHECK(arc.points.row(2).isZero());
    CHECK(arc.edges.size() == 2);
    for (const char* name : {"cyl", "ncyl"}) {
        const ControlNet grid = controlNet(doc.object(name));
        CHECK(grid.points.cols() == 6);
        CHECK(grid.edges.size() == 7);
    }
}

TEST_CASE("rational and NURBS objects: tessellations lie on the cylinder, polylines on the circle", "[document][nurbs]")
{
    const TypedDocument doc = load();
    for (const char* name : {"cyl", "ncyl"}) {
        INFO(name);
        ObjectTessellation options;
        options.tolerance = 1e-3;
        TessellationReport report;
        const auto mesh = tessellateObject(doc.object(name), options, &report);
        REQUIRE(mesh);
        CHECK(mesh->faceCount() > 0);
        CHECK(report.errorBound <= 1e-3);
        for (Eigen::Index i = 0; i < mesh->positions.cols(); ++i) {
            const V3 p = mesh->positions.col(i);
            CHECK(std::abs(p.head<2>().norm() - 1) <= 1e-14);
            CHECK(p.z() >= 0);
            CHECK(p.z() <= 1);
        }
    }
    for (const char* name : {"arc3", "narc"}) {
        INFO(name);
        const auto line = objectPolyline(doc.object(name), 1e-4);
        REQUIRE(line);
        CHECK(line->cols() >= 3);
        for (Eigen::Index i = 0; i < line->cols(); ++i) CHECK(std::abs(line->col(i).head<2>().norm() - 1) <= 1e-14);
    }
    CHECK_FALSE(tessellateObject(doc.object("arc3"), ObjectTessellation{}));
}

TEST_CASE("rational and NURBS objects: to NURBS and back keeps every number", "[document][nurbs]")
{
    const TypedDocument doc = load();
    // The rational arc as a nurbs_curve: clamped knots on [0, 1], the same points and weights.
    const auto n = std::get<NurbsCurveData>(toNurbsData(doc, doc.object("arc3")));
    CHECK(n.degree == 2);
    CHECK(n.knots == std::vector<double>{0, 0, 0, 1, 1, 1});
    CHECK(n.points == std::get<RationalBezierCurveData>(doc.object("arc3").data()).points);
    CHECK(n.weights == std::get<RationalBezierCurveData>(doc.object("arc3").data()).weights);
    // And the one-span NURBS arc back as a rational_bezier_curve equal to arc3.
    const auto back = std::get<RationalBezierCurveData>(fromNurbsData(doc, doc.object("narc")));
    CHECK(back.points == std::get<RationalBezierCurveData>(doc.object("arc3").data()).points);
    CHECK(back.weights == std::get<RationalBezierCurveData>(doc.object("arc3").data()).weights);
    // The NURBS patch back as the rational patch.
    const auto patch = std::get<RationalBezierSurfaceData>(fromNurbsData(doc, doc.object("ncyl")));
    CHECK(patch.degree == std::get<RationalBezierSurfaceData>(doc.object("cyl").data()).degree);
    CHECK(patch.points == std::get<RationalBezierSurfaceData>(doc.object("cyl").data()).points);
    CHECK(patch.weights == std::get<RationalBezierSurfaceData>(doc.object("cyl").data()).weights);
    CHECK_THROWS_WITH(toNurbsData(doc, doc.object("narc")), Catch::Contains("narc"));
}

TEST_CASE("convertObject: one call takes the kind table's route for every kind", "[document][nurbs]")
{
    TypedDocument doc = load();
    const ObjectId bs = doc.object("bs").id();
    // The two-span quadratic B-spline as its Bezier pieces: knot 1 inserted once more (Boehm,
    // alpha = (1 - 0) / (2 - 0)) gives the joint (P1 + P2) / 2 = (1.5, 0, 0.25) by hand.
    convertObject(doc, bs, "bezier_spline");
    const auto& s = std::get<BezierSplineData>(doc.object(bs).data());
    CHECK(s.degree == 2);
    CHECK(s.intervals.empty()); // two spans of length 1: the format's default intervals
    CHECK(AnyCurve::of(doc.object(bs))->domainEnd() == 2);
    REQUIRE(s.points.cols() == 5);
    CHECK(s.points.col(1) == V3(1, 1, 0));
    CHECK(s.points.col(2) == V3(1.5, 0, 0.25));
    CHECK(s.points.col(3) == V3(2, -1, 0.5));
    CHECK(doc.object(bs).name() == "bs");
    // And back: the joint's knot twice, the five points as they are.
    convertObject(doc, bs, "nurbs_curve");
    const auto& n = std::get<NurbsCurveData>(doc.object(bs).data());
    CHECK(n.knots == std::vector<double>{0, 0, 0, 1, 1, 2, 2, 2});
    CHECK(n.points.col(2) == V3(1.5, 0, 0.25));

    // The rational arc asked for as a nurbs_surface: the mismatch names the kind it converts to,
    // and the document is as it was.
    const std::string before = formatDocument(doc.toDocument());
    bool mismatch = false;
    try {
        convertObject(doc, doc.object("arc3").id(), "nurbs_surface");
    } catch (const ConversionMismatch& e) {
        mismatch = true;
        CHECK(e.converted == "nurbs_curve");
        CHECK_THAT(e.what(), Catch::Contains("arc3") && Catch::Contains("not a nurbs_surface"));
    }
    CHECK(mismatch);
    // No route (a lattice as a patch), and an end condition on the NURBS route.
    CHECK_THROWS_WITH(convertObject(doc, doc.object("L").id(), "bezier_surface"), Catch::Contains("does not convert"));
    CHECK_THROWS_WITH(convertObject(doc, doc.object("narc").id(), "rational_bezier_curve", EndCondition::Open),
                      Catch::Contains("end condition"));
    CHECK(formatDocument(doc.toDocument()) == before);
}

TEST_CASE("rational and NURBS objects: deformDocument under an affine lattice", "[document][nurbs][ffd]")
{
    TypedDocument doc = load();
    const TypedDocument before = doc;
    const Lattice lattice = latticeFromData(std::get<LatticeData>(doc.object("L").data()));
    const DeformDocumentReport r = deformDocument(doc, lattice);
    std::set<std::string> deformed, skipped;
    for (const auto& o : r.objects) deformed.insert(o.name);
    for (const auto& s : r.skipped) skipped.insert(s.name);
    CHECK(deformed == std::set<std::string>{"arc3", "narc", "bs", "cyl", "ncyl"});
    CHECK(skipped == std::set<std::string>{"arc2", "L"});
    // The 3D rational surfaces are composed exactly too (docs/ffd.md): the map of the old surface
    // at every (u, v) of a 9 x 9 grid over their domain [0, 1]^2.
    for (const char* name : {"cyl", "ncyl"}) {
        INFO(name);
        for (int i = 0; i <= 8; ++i)
            for (int j = 0; j <= 8; ++j) {
                const std::vector<double> uv{i / 8.0, j / 8.0};
                const Eigen::VectorXd p = evaluate(before, before.object(name), uv, 0).point;
                const Eigen::VectorXd q = evaluate(doc, doc.object(name), uv, 0).point;
                CHECK((q - (2 * p + V3(1, 0, 0))).norm() <= 1e-13);
            }
    }
    // Every deformed curve is the map of the old one: q(t) = 2 p(t) + (1, 0, 0), at many parameters.
    for (const char* name : {"arc3", "narc", "bs"}) {
        INFO(name);
        const std::vector<double> domain = parameterDomain(before.object(name));
        const double end = domain.empty() ? 1.0 : domain.back();
        for (int k = 0; k <= 16; ++k) {
            const double t = end * k / 16;
            const Eigen::VectorXd p = evaluate(before, before.object(name), {t}, 0).point;
            const Eigen::VectorXd q = evaluate(doc, doc.object(name), {t}, 0).point;
            CHECK((q - (2 * p + V3(1, 0, 0))).norm() <= 1e-13);
        }
    }
    // The arcs' images are circles of radius 2 around (1, 0).
    for (double t : {0.1, 0.5, 0.9}) {
        const Eigen::VectorXd q = evaluate(doc, doc.object("narc"), {t}, 0).point;
        CHECK(std::abs((q.head<2>() - Eigen::Vector2d(1, 0)).norm() - 2) <= 1e-13);
    }
}

} // namespace test_document_rational
