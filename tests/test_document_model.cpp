// The document layer (document/document.h): every object type through every operation, with
// values computed by hand (Bernstein and uniform B-spline weights, the bilinear patch z = x y, the
// lattice x -> x + x y z D of a unit cube with one corner moved), identities (affine invariance,
// round trips through convert) and the rule of deformDocument (docs/ffd.md, "Documents").

#include <catch2/catch.hpp>

#include <cmath>
#include <set>

#include "freeform/document/document.h"
#include "freeform/io/geometry_data.h"

namespace test_document_model {

using namespace freeform;
using V3 = Eigen::Vector3d;

namespace {

// All nine object kinds (2D and 3D curves and splines, both surfaces, a lattice, a cage).
const char* kDocument = R"({"format": "freeform", "version": 1, "objects": [
  {"name": "c2", "type": "bezier_curve", "points": [[0,0],[1,2],[3,2],[4,0]]},
  {"name": "c3", "type": "bezier_curve", "points": [[0.2,0.2,0.2],[0.6,0.6,0.6],[0.8,0.2,0.8]]},
  {"name": "s2", "type": "bezier_spline", "degree": 1, "closed": false, "points": [[0,0],[1,0],[1,2]], "intervals": [1, 2]},
  {"name": "d3", "type": "deboor_spline", "degree": 3, "end": "open",
   "points": [[0.1,0.1,0.1],[0.7,0.1,0.1],[0.7,0.7,0.1],[0.1,0.7,0.7],[0.4,0.4,0.9]]},
  {"name": "p", "type": "bezier_surface", "degree": [1, 1], "points": [[[0,0,0],[0,1,0]],[[1,0,0],[1,1,1]]]},
  {"name": "g", "type": "deboor_surface", "degree": [3, 3], "end": ["open", "open"],
   "points": [[[0,0,0],[0,1,0],[0,2,0],[0,3,0]],[[1,0,0],[1,1,1],[1,2,2],[1,3,3]],
              [[2,0,0],[2,1,2],[2,2,4],[2,3,6]],[[3,0,0],[3,1,3],[3,2,6],[3,3,9]]]},
  {"name": "L", "type": "lattice", "degree": [1, 1, 1], "origin": [0, 0, 0], "axes": [[1,0,0],[0,1,0],[0,0,1]],
   "points": [[0,0,0],[0,0,1],[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1.1,1.2,1.3]], "outside": "clamp"},
  {"name": "cube", "type": "subdivision_surface", "scheme": "catmark",
   "vertices": [[0.25,0.25,0.25],[0.75,0.25,0.25],[0.75,0.75,0.25],[0.25,0.75,0.25],
                [0.25,0.25,0.75],[0.75,0.25,0.75],[0.75,0.75,0.75],[0.25,0.75,0.75]],
   "faces": [[0,3,2,1],[4,5,6,7],[0,1,5,4],[1,2,6,5],[2,3,7,6],[3,0,4,7]]},
  {"name": "s3", "type": "bezier_spline", "degree": 2, "closed": false,
   "points": [[0.1,0.1,0.1],[0.5,0.2,0.9],[0.6,0.6,0.6],[0.7,1.0,0.3],[0.9,0.8,0.9]], "intervals": [1, 2]}
]})";

const V3 kD(0.1, 0.2, 0.3); // the displacement of corner (1,1,1) of the lattice L

/// Point-wise FFD through L inside the unit cube, by hand: x -> x + x y z D.
V3 ffd(const V3& p) { return p + p.x() * p.y() * p.z() * kD; }

TypedDocument load() { return TypedDocument(parseDocument(kDocument, "t.json"), ""); }

/// The uniform cubic B-spline segment of d0..d3 at local t (hand weights).
V3 bspline(const V3& d0, const V3& d1, const V3& d2, const V3& d3, double t)
{
    const double s = 1 - t;
    return (s * s * s * d0 + (3 * t * t * t - 6 * t * t + 4) * d1 + (-3 * t * t * t + 3 * t * t + 3 * t + 1) * d2 +
            t * t * t * d3) /
           6;
}

V3 col(const PointColumns& p, Eigen::Index i) { return p.col(i).head<3>(); }

} // namespace

TEST_CASE("typed document: ids, names, round trip to plain data", "[document]")
{
    TypedDocument doc = load();
    REQUIRE(doc.objects().size() == 9);
    std::set<ObjectId> ids;
    for (const TypedObject& o : doc.objects()) ids.insert(o.id());
    CHECK(ids.size() == 9);
    CHECK(doc.object("c2").dimension() == 2);
    CHECK(doc.object("c3").dimension() == 3);
    CHECK(doc.object("cube").type() == "subdivision_surface");
    // The plain document formats exactly as the parsed one.
    CHECK(formatDocument(doc.toDocument()) == formatDocument(parseDocument(kDocument, "t.json")));

    // Ids are never reused: remove, add, the new id is above every earlier one.
    const ObjectId c3 = doc.object("c3").id();
    doc.remove(c3);
    CHECK(doc.find(c3) == nullptr);
    const ObjectId added = doc.add("again", BezierCurveData{PointColumns::Zero(3, 2)});
    CHECK(ids.count(added) == 0);
    CHECK(added > *ids.rbegin());
    // An invalid replacement throws naming the object and changes nothing.
    const ObjectId g = doc.object("g").id();
    DeBoorSurfaceData bad;
    bad.rows = 2;
    bad.cols = 2;
    bad.points = PointColumns::Zero(3, 4);
    CHECK_THROWS_WITH(doc.replace(g, bad), Catch::StartsWith("t.json: object \"g\": "));
    CHECK(doc.object(g).type() == "deboor_surface");
    // The reader's message (Document::object), which the command line prints for --object.
    CHECK_THROWS_WITH(doc.object("nope"), Catch::Contains("no object named \"nope\"") && Catch::Contains(" (objects: "));
    std::string plain; // the plain document's message for the same lookup, byte for byte
    try {
        doc.toDocument().object("nope");
    } catch (const Error& e) {
        plain = e.what();
    }
    REQUIRE_FALSE(plain.empty());
    CHECK_THROWS_WITH(doc.object("nope"), plain);
}

TEST_CASE("evaluate: every type against hand values", "[document]")
{
    const TypedDocument doc = load();
    SECTION("2D cubic curve at 1/2: (P0 + 3 P1 + 3 P2 + P3) / 8 and its derivatives")
    {
        const Evaluation e = evaluate(doc, doc.object("c2"), {0.5}, 2);
        REQUIRE(e.point.size() == 2);
        CHECK((e.point - Eigen::Vector2d(2, 1.5)).norm() < 1e-15);
        REQUIRE(e.derivatives.size() == 2);
        CHECK((e.derivatives[0] - Eigen::Vector2d(4.5, 0)).norm() < 1e-14);
        CHECK((e.derivatives[1] - Eigen::Vector2d(0, -12)).norm() < 1e-13);
        CHECK(e.keys.empty());
        CHECK_THROWS_WITH(evaluate(doc, doc.object("c2"), {1.5}, 0), Catch::Contains("outside the curve's domain [0, 1]"));
    }
    SECTION("3D quadratic curve")
    {
        const Evaluation e = evaluate(doc, doc.object("c3"), {0.5}, 0);
        CHECK((V3(e.point) - V3(0.55, 0.4, 0.55)).norm() < 1e-15);
    }
    SECTION("2D polyline spline: global parameter, derivative scaled by the interval")
    {
        const Evaluation e = evaluate(doc, doc.object("s2"), {2}, 1);
        CHECK((e.point - Eigen::Vector2d(1, 1)).norm() < 1e-15);
        CHECK((e.derivatives[0] - Eigen::Vector2d(0, 1)).norm() < 1e-15);
        CHECK(parameterDomain(doc.object("s2")) == std::vector<double>{3});
        CHECK_THROWS_WITH(evaluate(doc, doc.object("s2"), {3.5}, 0), Catch::Contains("outside the spline's domain [0, 3]"));
    }
    SECTION("de Boor spline: uniform cubic B-spline weights 1/6, 4/6, 1/6")
    {
        const PointColumns& d = std::get<DeBoorSplineData>(doc.object("d3").data()).points;
        const Evaluation e = evaluate(doc, doc.object("d3"), {0}, 1);
        CHECK((V3(e.point) - (col(d, 0) + 4 * col(d, 1) + col(d, 2)) / 6).norm() < 1e-15);
        CHECK((V3(e.derivatives[0]) - (col(d, 2) - col(d, 0)) / 2).norm() < 1e-14);
        const Evaluation f = evaluate(doc, doc.object("d3"), {1.25}, 0);
        CHECK((V3(f.point) - bspline(col(d, 1), col(d, 2), col(d, 3), col(d, 4), 0.25)).norm() < 1e-15);
    }
    SECTION("bilinear patch f = (u, v, u v)")
    {
        const Evaluation e = evaluate(doc, doc.object("p"), {0.5, 0.25}, 2);
        CHECK((V3(e.point) - V3(0.5, 0.25, 0.125)).norm() < 1e-15);
        REQUIRE(e.keys == std::vector<std::string>{"u", "v", "uu", "uv", "vv"});
        CHECK((V3(e.derivatives[0]) - V3(1, 0, 0.25)).norm() < 1e-15);
        CHECK((V3(e.derivatives[1]) - V3(0, 1, 0.5)).norm() < 1e-15);
        CHECK((V3(e.derivatives[3]) - V3(0, 0, 1)).norm() < 1e-15);
        CHECK((*e.normal - V3(-0.25, -0.5, 1).normalized()).norm() < 1e-15);
    }
    SECTION("bicubic de Boor surface of z = x y reproduces it: f = (1+u, 1+v, (1+u)(1+v))")
    {
        const Evaluation e = evaluate(doc, doc.object("g"), {0.5, 0.25}, 1);
        CHECK((V3(e.point) - V3(1.5, 1.25, 1.875)).norm() < 1e-14);
        CHECK((V3(e.derivatives[0]) - V3(1, 0, 1.25)).norm() < 1e-14);
        CHECK((V3(e.derivatives[1]) - V3(0, 1, 1.5)).norm() < 1e-14);
        CHECK_THROWS_WITH(evaluate(doc, doc.object("g"), {1.5, 0}, 0), Catch::Contains("outside the surface's domain [0, 1]"));
    }
    SECTION("lattice: x + x y z D and det J = 1 + D . (y z, x z, x y)")
    {
        const Evaluation e = evaluate(doc, doc.object("L"), {0.5, 0.5, 0.5}, 1);
        CHECK((V3(e.point) - ffd(V3(0.5, 0.5, 0.5))).norm() < 1e-15);
        REQUIRE(e.keys == std::vector<std::string>{"s", "t", "u"});
        CHECK((V3(e.derivatives[0]) - (V3(1, 0, 0) + 0.25 * kD)).norm() < 1e-15);
        REQUIRE(e.det);
        CHECK(std::abs(*e.det - 1.15) < 1e-14);
        CHECK_THROWS_WITH(evaluate(doc, doc.object("L"), {0.5, 0.5, 0.5}, 2), Catch::Contains("--derivatives 0 or 1"));
    }
    SECTION("subdivision cube: symmetric, so the centre of a face lies on the axis with the axis as normal")
    {
        const Evaluation e = evaluate(doc, doc.object("cube"), {1, 0.5, 0.5}, 1);
        CHECK(e.face == 1);
        CHECK(std::abs(e.point.x() - 0.5) < 1e-14);
        CHECK(std::abs(e.point.y() - 0.5) < 1e-14);
        CHECK(e.point.z() > 0.5);
        CHECK(e.point.z() < 0.75);
        CHECK(std::abs(std::abs(e.normal->z()) - 1) < 1e-14);
        CHECK(e.keys == std::vector<std::string>{"u", "v"});
        CHECK_THROWS_WITH(evaluate(doc, doc.object("cube"), {1, 0.5, 0.5}, 2), Catch::Contains("first derivatives only"));
    }
}

TEST_CASE("continuity: splines by hand, other types refused", "[document]")
{
    const TypedDocument doc = load();
    const auto kink = continuity(doc, doc.object("s2"));
    REQUIRE(kink.size() == 1);
    CHECK(kink[0].C == 0);
    CHECK(kink[0].G == 0);
    CHECK(kink[0].t == 1);
    CHECK(std::abs(kink[0].jumps[1] - std::sqrt(2.0)) < 1e-15); // (0, 1) - (1, 0)
    const auto c2 = continuity(doc, doc.object("d3"));
    REQUIRE(c2.size() == 1);
    CHECK(c2[0].C == 2); // a C2 cubic whose third derivative jumps (generic de Boor points)
    CHECK_THROWS_WITH(continuity(doc, doc.object("p")), Catch::Contains("not a spline"));
}

TEST_CASE("tessellate: surfaces, cages, curves; control nets", "[document]")
{
    const TypedDocument doc = load();
    TessellationReport report;
    const auto patch = tessellateObject(doc.object("p"), {0, 2, false, {}, {}}, &report);
    REQUIRE(patch);
    CHECK(patch->vertexCount() == 9);
    CHECK(patch->faceCount() == 8);
    for (Eigen::Index i = 0; i < patch->positions.cols(); ++i) {
        const V3 q = patch->positions.col(i);
        CHECK(std::abs(q.z() - q.x() * q.y()) < 1e-15);
    }
    const auto grid = tessellateObject(doc.object("g"), {1e-3, 8, false, {}, {}});
    REQUIRE(grid);
    for (Eigen::Index i = 0; i < grid->positions.cols(); ++i) {
        const V3 q = grid->positions.col(i);
        CHECK(std::abs(q.z() - q.x() * q.y()) < 1e-13);
    }
    CHECK(documentPatches(doc).patches.size() == 2);
    const auto cube = tessellateObject(doc.object("cube"), {0, 2, false, {}, {}});
    REQUIRE(cube);
    CHECK(cube->faceCount() == 6 * 2 * 2 * 2); // 2 x 2 quads per face, two triangles each
    for (Eigen::Index i = 0; i < cube->positions.cols(); ++i)
        CHECK((cube->positions.col(i).array() >= 0.25).all()); // inside the cage's hull
    CHECK_FALSE(tessellateObject(doc.object("L"), {}));

    // Curves: a polyline from t = 0 to t = 1, in 3D; the 2D curve lifted with z = 0.
    const auto line = objectPolyline(doc.object("c2"), 1e-3);
    REQUIRE(line);
    CHECK((line->col(0) - V3(0, 0, 0)).norm() == 0);
    CHECK((line->col(line->cols() - 1) - V3(4, 0, 0)).norm() < 1e-15);
    CHECK(line->row(2).isZero(0));
    CHECK_FALSE(objectPolyline(doc.object("p"), 1e-3));

    // Control nets: edge counts by hand.
    CHECK(controlNet(doc.object("c2")).edges.size() == 3);
    CHECK(controlNet(doc.object("p")).edges.size() == 4);
    CHECK(controlNet(doc.object("g")).edges.size() == 24);
    CHECK(controlNet(doc.object("L")).edges.size() == 12);
    CHECK(controlNet(doc.object("cube")).edges.size() == 12);
    CHECK(controlNet(doc.object("d3")).points.cols() == 5);
}

TEST_CASE("convert: the A-frame by hand and round trips", "[document]")
{
    TypedDocument doc = load();
    const ObjectId id = doc.object("d3").id();
    const PointColumns d = std::get<DeBoorSplineData>(doc.object(id).data()).points;
    convertSpline(doc, id, "bezier_spline");
    const auto& b = std::get<BezierSplineData>(doc.object(id).data());
    REQUIRE(b.points.cols() == 7);
    // Segment 0: (d0 + 4 d1 + d2)/6, (2 d1 + d2)/3, (d1 + 2 d2)/3, (d1 + 4 d2 + d3)/6.
    CHECK((col(b.points, 0) - (col(d, 0) + 4 * col(d, 1) + col(d, 2)) / 6).norm() < 1e-15);
    CHECK((col(b.points, 1) - (2 * col(d, 1) + col(d, 2)) / 3).norm() < 1e-15);
    CHECK((col(b.points, 2) - (col(d, 1) + 2 * col(d, 2)) / 3).norm() < 1e-15);
    CHECK((col(b.points, 3) - (col(d, 1) + 4 * col(d, 2) + col(d, 3)) / 6).norm() < 1e-15);
    CHECK(doc.object(id).name() == "d3");
    convertSpline(doc, id, "deboor_spline", EndCondition::Open);
    const auto& back = std::get<DeBoorSplineData>(doc.object(id).data());
    CHECK(back.end == "open");
    CHECK((back.points - d).norm() < 1e-14);
    CHECK_THROWS_WITH(convertSpline(doc, id, "deboor_spline"), Catch::Contains("already a deboor_spline"));
    CHECK_THROWS_WITH(convertSpline(doc, doc.object("s2").id(), "deboor_spline"), Catch::Contains("need a cubic spline"));
    CHECK_THROWS_WITH(convertSpline(doc, doc.object("p").id(), "bezier_spline"), Catch::Contains("not a spline"));
}

TEST_CASE("deformDocument: one rule for every type", "[document][ffd]")
{
    TypedDocument doc = load();
    const Lattice lattice = latticeFromData(std::get<LatticeData>(doc.object("L").data()));
    const TypedDocument before = doc;
    const DeformDocumentReport r = deformDocument(doc, lattice);
    auto deformed = [&](const std::string& name) -> const DeformedObject& {
        for (const auto& o : r.objects)
            if (o.name == name) return o;
        FAIL("not deformed: " << name);
        return r.objects.front();
    };
    // Skipped: the 2D objects, the lattice, the de Boor surface (the lattice is not affine).
    std::set<std::string> skipped;
    for (const auto& s : r.skipped) skipped.insert(s.name);
    CHECK(skipped == std::set<std::string>{"c2", "s2", "L", "g"});
    CHECK(r.objects.size() == 5);
    CHECK(r.certificate.verdict == Verdict::CertifiedInjective);
    // Ids and order stay.
    for (std::size_t i = 0; i < doc.objects().size(); ++i) CHECK(doc.objects()[i].id() == before.objects()[i].id());

    SECTION("curves, splines, patches: composition equals point-wise FFD at every parameter")
    {
        CHECK(deformed("c3").degree == std::vector<int>{6});
        CHECK(deformed("c3").inside);
        CHECK(deformed("c3").exact);
        for (double t : {0.0, 0.3, 0.5, 0.9, 1.0}) {
            CHECK((V3(evaluate(doc, doc.object("c3"), {t}, 0).point) - ffd(evaluate(before, before.object("c3"), {t}, 0).point)).norm() < 1e-14);
            CHECK((V3(evaluate(doc, doc.object("s3"), {3 * t}, 0).point) - ffd(evaluate(before, before.object("s3"), {3 * t}, 0).point)).norm() < 1e-14);
            const V3 p = V3(t, 1 - t, t * (1 - t)); // on the bilinear patch at (u, v) = (t, 1 - t)
            CHECK((V3(evaluate(doc, doc.object("p"), {t, 1 - t}, 0).point) - ffd(p)).norm() < 1e-14);
        }
        CHECK(deformed("p").degree == std::vector<int>{3, 3});
        CHECK(deformed("s3").degree == std::vector<int>{6});
    }
    SECTION("a de Boor spline under a non-affine lattice becomes a bezier_spline of degree 9")
    {
        CHECK(deformed("d3").from == "deboor_spline");
        CHECK(deformed("d3").type == "bezier_spline");
        CHECK(deformed("d3").degree == std::vector<int>{9});
        CHECK_FALSE(deformed("d3").note.empty());
        const PointColumns& d = std::get<DeBoorSplineData>(before.object("d3").data()).points;
        for (double t : {0.0, 0.4, 1.0, 1.7})
            CHECK((V3(evaluate(doc, doc.object("d3"), {t}, 0).point) -
                   ffd(t < 1 ? bspline(col(d, 0), col(d, 1), col(d, 2), col(d, 3), t)
                             : bspline(col(d, 1), col(d, 2), col(d, 3), col(d, 4), t - 1)))
                      .norm() < 1e-14);
    }
    SECTION("the cage is deformed as a cage: its vertices through the lattice, faces kept")
    {
        CHECK(deformed("cube").type == "subdivision_surface");
        CHECK(deformed("cube").degree.empty());
        CHECK_FALSE(deformed("cube").exact); // not affine: the limit surface moves only approximately
        const auto& a = std::get<SubdivisionSurfaceData>(before.object("cube").data());
        const auto& b = std::get<SubdivisionSurfaceData>(doc.object("cube").data());
        CHECK(b.faces == a.faces);
        for (Eigen::Index i = 0; i < a.vertices.cols(); ++i) CHECK((col(b.vertices, i) - ffd(col(a.vertices, i))).norm() < 1e-15);
    }
}

TEST_CASE("deformDocument: objects outside the box, affine lattices", "[document][ffd]")
{
    const char* text = R"({"format": "freeform", "version": 1, "objects": [
      {"name": "out", "type": "bezier_curve", "points": [[0.5,0.5,0.5],[1.5,0.5,0.5]]},
      {"name": "d3", "type": "deboor_spline", "degree": 3, "end": "open",
       "points": [[0.1,0.1,0.1],[0.7,0.1,0.1],[0.7,0.7,0.1],[0.1,0.7,0.7]]},
      {"name": "g", "type": "deboor_surface", "degree": [3, 3], "end": ["open", "open"],
       "points": [[[0,0,0],[0,0.1,0],[0,0.2,0],[0,0.3,0]],[[0.1,0,0],[0.1,0.1,0.1],[0.1,0.2,0.2],[0.1,0.3,0.3]],
                  [[0.2,0,0],[0.2,0.1,0.2],[0.2,0.2,0.4],[0.2,0.3,0.6]],[[0.3,0,0],[0.3,0.1,0.3],[0.3,0.2,0.6],[0.3,0.3,0.9]]]}]})";
    SECTION("outside the box under clamp: the polynomial continued, reported inexact; or skipped on request")
    {
        const TypedDocument start(parseDocument(text, "o.json"), "");
        const Eigen::Vector3d S(1, 0, 0), T(0, 1, 0), U(0, 0, 1);
        Lattice lattice = Lattice::identity({1, 1, 1}, V3::Zero(), Eigen::Matrix3d::Identity());
        lattice.setControlPoint(1, 1, 1, V3(1, 1, 1) + kD);
        TypedDocument doc = start;
        const auto r = deformDocument(doc, lattice);
        const DeformedObject& out = r.objects.front();
        CHECK(out.name == "out");
        CHECK_FALSE(out.inside);
        CHECK_FALSE(out.exact);
        CHECK(out.note.find("clamp") != std::string::npos);
        const auto& p = std::get<BezierCurveData>(doc.object("out").data()).points;
        CHECK((col(p, p.cols() - 1) - ffd(V3(1.5, 0.5, 0.5))).norm() < 1e-14); // x y z D continued
        TypedDocument strict = start;
        DeformDocumentOptions options;
        options.skipInexact = true;
        const auto s = deformDocument(strict, lattice, options);
        REQUIRE_FALSE(s.skipped.empty());
        CHECK(s.skipped.front().name == "out");
        CHECK(s.skipped.front().reason.find("outside the lattice box") != std::string::npos);
        CHECK(std::get<BezierCurveData>(strict.object("out").data()).points == std::get<BezierCurveData>(start.object("out").data()).points);
    }
    SECTION("an affine lattice keeps de Boor splines and surfaces: p -> 2 p + (1, 0, 0)")
    {
        // Control points 2 R + (1, 0, 0): the displacement p + (1, 0, 0) is affine.
        Lattice lattice = Lattice::identity({2, 1, 1}, V3::Zero(), Eigen::Matrix3d::Identity(), OutsidePolicy::Extrapolate);
        for (int i = 0; i <= 2; ++i)
            for (int j = 0; j <= 1; ++j)
                for (int k = 0; k <= 1; ++k) lattice.setControlPoint(i, j, k, 2 * lattice.restPoint(i, j, k) + V3(1, 0, 0));
        CHECK(isAffineLattice(lattice));
        TypedDocument doc(parseDocument(text, "o.json"), "");
        const TypedDocument before = doc;
        const auto r = deformDocument(doc, lattice);
        CHECK(r.skipped.empty());
        for (const std::string name : {"d3", "g"}) {
            const TypedObject& o = doc.object(name);
            CHECK(o.type() == before.object(name).type());
            const PointColumns& a = o.type() == "deboor_spline" ? std::get<DeBoorSplineData>(before.object(name).data()).points
                                                                 : std::get<DeBoorSurfaceData>(before.object(name).data()).points;
            const PointColumns& b = o.type() == "deboor_spline" ? std::get<DeBoorSplineData>(o.data()).points
                                                                 : std::get<DeBoorSurfaceData>(o.data()).points;
            for (Eigen::Index i = 0; i < a.cols(); ++i) CHECK((col(b, i) - (2 * col(a, i) + V3(1, 0, 0))).norm() < 1e-15);
        }
        // The curve outside the box is exact under extrapolate.
        CHECK(r.objects.front().exact);
        // Not affine: one moved corner.
        lattice.setControlPoint(0, 0, 0, V3(0.1, 0, 0));
        CHECK_FALSE(isAffineLattice(lattice));
    }
}

} // namespace test_document_model
