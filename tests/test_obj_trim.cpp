// OBJ's free-form trimming statements (issue 28): `vp`, `curv2`, `trim` and `hole` read into a
// trimmed_surface and written from one. Facts checked: a hand-written plate with a circular outer
// trim and a square hole has the area 6 (0.16 pi - 0.04) computed by hand; points are classified
// as the hand-drawn loops say; the document's trimmed square and the hand-written file are fixed
// points of document -> OBJ -> document (every number) and of OBJ -> document -> OBJ (the text);
// every error names its line.

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "freeform/brep/trimmed_surface.h"
#include "freeform/document/model.h"
#include "freeform/io/obj_freeform.h"
#include "support/obj_errors.h"

namespace test_obj_trim {

using namespace freeform;

namespace {

// A flat 2 x 3 B-spline patch (z = 0), trimmed to the circle of radius 0.4 about (0.5, 0.5) in its
// parameters, with the square hole [0.4, 0.6]^2 run clockwise (trim range given high to low).
const std::string kPlate = "o plate\n"
                           // curv2 1: the circle, 9 rational quadratic points (weights as the 3rd vp value)
                           "vp 0.9 0.5\nvp 0.9 0.9 0.7071067811865476\nvp 0.5 0.9\nvp 0.1 0.9 0.7071067811865476\n"
                           "vp 0.1 0.5\nvp 0.1 0.1 0.7071067811865476\nvp 0.5 0.1\nvp 0.9 0.1 0.7071067811865476\nvp 0.9 0.5\n"
                           "cstype rat bspline\ndeg 2\ncurv2 1 2 3 4 5 6 7 8 9\nparm u 0 0 0 1 1 2 2 3 3 4 4 4\nend\n"
                           // curv2 2: the square hole, one degree-1 B-spline through its corners
                           "vp 0.4 0.4\nvp 0.6 0.4\nvp 0.6 0.6\nvp 0.4 0.6\nvp 0.4 0.4\n"
                           "cstype bspline\ndeg 1\ncurv2 -5 -4 -3 -2 -1\nparm u 0 0 1 2 3 4 4\nend\n"
                           "v 0 0 0\nv 2 0 0\nv 0 3 0\nv 2 3 0\n"
                           "cstype bspline\ndeg 1 1\nsurf 0 1 0 1 1 2 3 4\nparm u 0 0 1 1\nparm v 0 0 1 1\n"
                           "trim 0 4 1\n"
                           "hole 4 0 -1\n"
                           "end\n";

std::string err(const std::string& text) { return test::objError(text); }

const TrimmedSurface& trimmed(TypedDocument& doc, const ObjectData& data)
{
    return std::get<TrimmedSurface>(doc.object(doc.add("t", data)).geometry());
}

} // namespace

TEST_CASE("a hand-written trimmed plate reads as a trimmed_surface with the area computed by hand", "[obj][trim]")
{
    const Document d = parseObjFreeform(kPlate, "plate.obj");
    REQUIRE(d.objects.size() == 1); // the two curv2 are the trims, not objects of their own
    CHECK(d.objects[0].name == "plate");
    const auto& t = std::get<TrimmedSurfaceData>(d.objects[0].data);
    CHECK(t.domain == std::array<double, 4>{0, 1, 0, 1});
    REQUIRE(t.loops.size() == 2);
    REQUIRE(t.loops[0].size() == 1);
    CHECK(t.loops[0][0].curve.nurbs.weights.size() == 9);
    CHECK(t.loops[0][0].curve.first == 0);
    CHECK(t.loops[0][0].curve.last == 4);
    CHECK_FALSE(t.loops[0][0].reversed);
    CHECK(t.loops[1][0].reversed); // hole 4 0: from 4 back to 0
    CHECK(t.loops[1][0].curve.nurbs.points.col(1) == Eigen::Vector2d(0.6, 0.4));

    TypedDocument doc;
    const TrimmedSurface& s = trimmed(doc, t);
    // The disc of radius 0.4 less the 0.2 x 0.2 square, times the patch's scale 2 x 3.
    const double area = 6 * (0.16 * std::numbers::pi - 0.04);
    CHECK(std::abs(s.area() - area) < 1e-9 * area);
    CHECK(s.classify({0.5, 0.5}) == TrimClass::Outside);  // in the hole
    CHECK(s.classify({0.5, 0.25}) == TrimClass::Inside);  // between hole and circle
    CHECK(s.classify({0.05, 0.05}) == TrimClass::Outside); // outside the circle, inside the patch
    CHECK(s.classify({0.5, 0.9}) == TrimClass::Boundary);  // on the circle
    CHECK((s.point(0.5, 0.25) - Eigen::Vector3d(1, 0.75, 0)).norm() < 1e-15);
}

TEST_CASE("trimmed surfaces are fixed points of document -> OBJ -> document and OBJ -> document -> OBJ", "[obj][trim]")
{
    const TypedDocument square = TypedDocument::read(std::string(FREEFORM_SOURCE_DIR) + "/data/parts/trimmed_square.json");
    Document doc;
    doc.source = "square.json";
    for (const TypedObject& o : square.objects()) doc.objects.push_back({o.name(), o.data(), ""});
    const std::string text = formatObjFreeform(doc);
    CHECK(text.find("curv2 1 2\n") != std::string::npos);
    CHECK(text.find("trim 0 1 1 0 1 2 0 1 3 0 1 4\nhole 0 4 5\nend\n") != std::string::npos);
    const Document back = parseObjFreeform(text, "square.obj");
    REQUIRE(back.objects.size() == 1);
    CHECK(formatDocument(back) == formatDocument(Document{doc.objects, "", "square.obj"}));
    CHECK(formatObjFreeform(back) == text);

    // The hand-written plate: its text comes back the same once written (relative references
    // become absolute, the hole's reversed range stays reversed).
    const Document plate = parseObjFreeform(kPlate, "plate.obj");
    const std::string once = formatObjFreeform(plate);
    CHECK(once.find("hole 4 0 2\n") != std::string::npos);
    CHECK(formatObjFreeform(parseObjFreeform(once)) == once);
    CHECK(formatDocument(parseObjFreeform(once)) == formatDocument(plate));
}

TEST_CASE("a Bézier surf with a trim, holes alone and a B-spline surf over part of its domain", "[obj][trim]")
{
    const std::string square = "vp 0.5 0.5\nvp 1.5 0.5\nvp 1.5 1\nvp 0.5 1\nvp 0.5 0.5\n"
                               "cstype bspline\ndeg 1\ncurv2 1 2 3 4 5\nparm u 0 0 1 2 3 4 4\nend\n"
                               "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 2 2 1\n";
    // A Bézier patch over parm u 0 2, parm v 0 2: the NURBS surface with knots 0 0 2 2.
    const Document a = parseObjFreeform(square + "cstype bezier\ndeg 1 1\nsurf 0 2 0 2 1 2 3 4\nparm u 0 2\nparm v 0 2\nhole 0 4 1\nend\n", "a.obj");
    REQUIRE(a.objects.size() == 1);
    const auto& t = std::get<TrimmedSurfaceData>(a.objects[0].data);
    CHECK(t.surface.knots[0] == std::vector<double>{0, 0, 2, 2});
    CHECK(t.domain == std::array<double, 4>{0, 2, 0, 2});
    // Holes alone: the outer loop is the surf range, four lines.
    REQUIRE(t.loops.size() == 2);
    CHECK(t.loops[0].size() == 4);
    TypedDocument doc;
    const TrimmedSurface& s = trimmed(doc, t);
    // z = u v / 4 over [0, 2]^2 (the bilinear patch with its corner at height 1).
    CHECK((s.point(1, 1.5) - Eigen::Vector3d(1, 1.5, 0.375)).norm() < 1e-15);
    CHECK(s.classify({1, 0.75}) == TrimClass::Outside); // in the hole [0.5, 1.5] x [0.5, 1]
    CHECK(s.classify({1, 1.5}) == TrimClass::Inside);

    // A B-spline surf over a part of its knot domain is a trimmed_surface without loops.
    const Document b = parseObjFreeform(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\ncstype bspline\ndeg 1 1\nsurf 0 0.5 0.25 1 1 2 3 4\nparm u 0 0 1 1\nparm v 0 0 1 1\nend\n", "b.obj");
    const auto& tb = std::get<TrimmedSurfaceData>(b.objects.at(0).data);
    CHECK(tb.loops.empty());
    CHECK(tb.domain == std::array<double, 4>{0, 0.5, 0.25, 1});
    CHECK(std::abs(trimmed(doc, tb).area() - 0.375) < 1e-12);

    // A curv2 no surface takes is kept as a 2D curve.
    const Document c = parseObjFreeform(square, "c.obj");
    REQUIRE(c.objects.size() == 1);
    CHECK(std::get<NurbsCurveData>(c.objects[0].data).points.rows() == 2);
}

TEST_CASE("OBJ trim errors name the line, and parameter maps are refused by field", "[obj][trim][errors]")
{
    const std::string curve = "vp 0 0\nvp 1 0\ncstype bspline\ndeg 1\ncurv2 1 2\nparm u 0 0 1 1\nend\n"; // lines 1-7
    const std::string surf = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\ncstype bspline\ndeg 1 1\nsurf 0 1 0 1 1 2 3 4\n"
                             "parm u 0 0 1 1\nparm v 0 0 1 1\n"; // lines 8-16
    CHECK(err(curve + surf + "trim 0 1 2\nend\n") == "x.obj: line 17: curv2 2 is not defined (1 curv2 so far)");
    CHECK(err(curve + surf + "trim 0 1 1\ntrim 0 1 1\nend\n") ==
          "x.obj: line 18: a second trim loop: a freeform trimmed surface has one outer boundary (holes are \"hole\" statements)");
    CHECK(err(curve + surf + "trim 0 2 1\nend\n") == "x.obj: line 17: the trim range 0 2 of curv2 1 is outside its domain 0 1");
    CHECK(err(curve + surf + "trim 1 1 1\nend\n") == "x.obj: line 17: the trim range 1 1 is empty");
    CHECK(err(curve + surf + "trim 0 1\nend\n") == "x.obj: line 17: expected \"trim u0 u1 curv2 [u0 u1 curv2 ...]\"");
    CHECK(err(curve + "trim 0 1 1\n") == "x.obj: line 8: trim outside a surf element");
    CHECK(err("vp 0\nvp 1 0\ncstype bspline\ndeg 1\ncurv2 1 2\n") ==
          "x.obj: line 5: parameter vertex 1 (line 1) has u alone; a trimming curve needs u and v");
    CHECK(err("vp 0 0\ncstype bspline\ndeg 1\ncurv2 1 2\n") == "x.obj: line 4: parameter vertex index 2 is out of range (1 vp so far)");
    CHECK(err("vp 0 0 0\nvp 1 0\ncstype rat bspline\ndeg 1\ncurv2 1 2\nparm u 0 0 1 1\nend\n") ==
          "x.obj: line 5: parameter vertex 1 (line 1) has weight 0; rational weights must be positive");
    CHECK(err(curve + "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\ncstype bspline\ndeg 1 1\nsurf 0 2 0 1 1 2 3 4\nparm u 0 0 1 1\nparm v 0 0 1 1\nend\n") ==
          "x.obj: line 14: the parameter range 0 2 in u is outside the surface's domain 0 1");
    CHECK(err(curve + "cstype bspline\ndeg 1\ncurv2 1 2\n") == "x.obj: line 10: curv2 element has no \"end\"");
    CHECK(err("sp 1 2\n") == "x.obj: line 1: special curves and points (sp) are not supported");

    // Writing: OBJ has no parameter maps (a CAD face's angle parameters), so they are refused.
    TrimmedSurfaceData t = std::get<TrimmedSurfaceData>(parseObjFreeform(kPlate).objects[0].data);
    t.map[1] = ParameterMap::periodic(0, 2);
    Document doc;
    doc.source = "d.json";
    doc.objects.push_back({"plate", t, ""});
    CHECK_THROWS_WITH(formatObjFreeform(doc), "d.json: object \"plate\": field \"map_v\": OBJ has no parameter maps (a CAD face's angles; "
                                              "write the part as STEP or IGES, or the document as JSON)");
}

} // namespace test_obj_trim
