// Reading CAD parts (freeform/cad/cad_file.h, brep/part.h) against Open CASCADE as the independent
// reference: the sample parts Debian ships (occt-misc: STEP, IGES and .brep files, the latter read
// with Open CASCADE's own BRepTools::Read) and parts built here with Open CASCADE's modelling
// algorithms (a box with holes, fillets, a B-spline solid, a cylinder, a torus, a sphere, a cone),
// written to STEP and read back. Checked per part: face, edge, vertex, shell and solid counts;
// every edge's curve at 9 parameters against BRepAdaptor_Curve; every trim curve against
// BRep_Tool::CurveOnSurface; points at random parameters inside the trims against
// BRepAdaptor_Surface, all to 1e-12 of the part's size; the trim classification against
// BRepClass_FaceClassifier; closed shells against BRep_Tool::IsClosed.

#include <catch2/catch.hpp>

#include <freeform/brep/part_mesh.h>
#include <freeform/cad/cad_file.h>
#include <freeform/cad/occt_bridge.h>

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepClass_FaceClassifier.hxx>
#include <BRepFilletAPI_MakeFillet.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRepPrimAPI_MakeRevol.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_OffsetSurface.hxx>
#include <Geom_Plane.hxx>
#include <IGESControl_Reader.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shell.hxx>
#include <gp_Ax2.hxx>
#include <gp_Pln.hxx>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <random>
#include <sstream>

#include "support/occt_parts.h"
#include "support/occt_reference.h"
#include "support/sanitizers.h"

namespace test_cad_read {

using namespace freeform;
using test::bsplinePrism;
using test::bsplineRevolution;
using test::boxWithHoles;
using test::filletedBox;
using test::writeStep;

namespace {

const std::string kData = "/usr/share/opencascade/data";

Eigen::Vector3d vec(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }

/// Whether t lies within 1e-8 of a break of the B-spline pcurve (a knot of multiplicity >= its
/// degree, where the pieces may differ by a rounding) or outside its domain. There Open CASCADE
/// snaps t to the knot (BSplCLib::LocateParameter) or extrapolates the end piece, while freeform
/// evaluates at t itself or clamps t to the domain: a file whose edge range ends 1e-9 beside a
/// break of its pcurve (linkrods.step does) gets two answers that differ by about that much.
bool nearBreak(const Handle(Geom2d_Curve)& curve, double t)
{
    Handle(Geom2d_Curve) c = curve;
    if (auto tc = Handle(Geom2d_TrimmedCurve)::DownCast(c)) c = tc->BasisCurve();
    const auto bs = Handle(Geom2d_BSplineCurve)::DownCast(c);
    if (bs.IsNull()) return false;
    if (t < bs->FirstParameter() || t > bs->LastParameter()) return true;
    for (int k = 1; k <= bs->NbKnots(); ++k)
        if (std::abs(bs->Knot(k) - t) < 1e-8 && bs->Multiplicity(k) >= bs->Degree()) return true;
    return false;
}

struct Stats {
    int edgePoints = 0, trimPoints = 0, facePoints = 0, classified = 0, endsNearBreaks = 0;
    double worst = 0; // largest distance found, relative to the part's size
};

/// Every check of the header comment for one part read from `shape`.
Stats compare(const TopoDS_Shape& shape, const Part& part, const std::string& name)
{
    INFO(name);
    REQUIRE(part.faces.size() == static_cast<std::size_t>(test::occtCount(shape, TopAbs_FACE)));
    REQUIRE(part.edges.size() == static_cast<std::size_t>(test::occtCount(shape, TopAbs_EDGE)));
    CHECK(part.vertices.size() == static_cast<std::size_t>(test::occtCount(shape, TopAbs_VERTEX)));
    CHECK(part.shells.size() == static_cast<std::size_t>(test::occtCount(shape, TopAbs_SHELL)));
    CHECK(part.solids.size() == static_cast<std::size_t>(test::occtCount(shape, TopAbs_SOLID)));
    CHECK(checkPart(part).closed == test::occtClosed(shape));

    Bnd_Box box;
    BRepBndLib::Add(shape, box);
    double x0, y0, z0, x1, y1, z1;
    box.Get(x0, y0, z0, x1, y1, z1);
    const double size = std::max({std::abs(x0), std::abs(y0), std::abs(z0), std::abs(x1), std::abs(y1), std::abs(z1), 1.0});
    const double tol = 1e-12 * size;
    // The part's bounds hold Open CASCADE's box (which may be enlarged by the tolerances).
    const Box<double, 3> ours = part.bounds();
    CHECK(ours.min().x() <= x1);
    CHECK(ours.max().x() >= x0);

    TopTools_IndexedMapOfShape faces, edges;
    TopExp::MapShapes(shape, TopAbs_FACE, faces);
    TopExp::MapShapes(shape, TopAbs_EDGE, edges);
    Stats stats;
    auto note = [&](double d) { stats.worst = std::max(stats.worst, d / size); };

    for (int i = 1; i <= edges.Extent(); ++i) {
        const PartEdge& e = part.edges[static_cast<std::size_t>(i - 1)];
        if (!e.curve) continue;
        BRepAdaptor_Curve ac(TopoDS::Edge(edges(i).Oriented(TopAbs_FORWARD)));
        for (int k = 0; k <= 8; ++k) {
            const double t = e.first + (e.last - e.first) * k / 8;
            const double d = (e.curve->point(t) - vec(ac.Value(t))).norm();
            note(d);
            CHECK(d <= tol);
            ++stats.edgePoints;
        }
    }

    std::mt19937 rng(20261204);
    for (int i = 1; i <= faces.Extent(); ++i) {
        INFO("face " << i);
        const TopoDS_Face face = TopoDS::Face(faces(i));
        const PartFace& pf = part.faces[static_cast<std::size_t>(i - 1)];
        const TrimmedSurface& ts = pf.surface;
        int wires = 0;
        for (TopExp_Explorer ex(face, TopAbs_WIRE); ex.More(); ex.Next()) ++wires;
        CHECK(ts.loops().size() == static_cast<std::size_t>(wires));
        CHECK(pf.reversed == (face.Orientation() == TopAbs_REVERSED));

        // Trim curves against Open CASCADE's pcurves (the seam's two by the edge's orientation).
        for (const TrimLoop& loop : ts.loops())
            for (const TrimCurve& trim : loop.curves) {
                const TopoDS_Edge e = TopoDS::Edge(edges(trim.edge + 1).Oriented(trim.reversed ? TopAbs_REVERSED : TopAbs_FORWARD));
                double f, l;
                const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(e, face, f, l);
                REQUIRE(!pc.IsNull());
                for (int k = 0; k <= 8; ++k) {
                    const double t = f + (l - f) * k / 8;
                    const gp_Pnt2d q = pc->Value(t);
                    const double d = (trim.curve.point(t) - Eigen::Vector2d(q.X(), q.Y())).norm();
                    const double scale = std::max({1.0, std::abs(q.X()), std::abs(q.Y())});
                    if ((k == 0 || k == 8) && d > 1e-12 * scale && d <= 1e-8 * scale && nearBreak(pc, t)) {
                        ++stats.endsNearBreaks; // the file's range ends within 1e-8 of a break: see nearBreak
                        continue;
                    }
                    CHECK(d <= 1e-12 * scale);
                    ++stats.trimPoints;
                }
            }

        // Points inside the trims against BRepAdaptor_Surface; the classification against
        // BRepClass_FaceClassifier wherever that is sure (not ON).
        BRepAdaptor_Surface as(face);
        double u0, u1, v0, v1;
        BRepTools::UVBounds(face, u0, u1, v0, v1);
        std::uniform_real_distribution<double> U(u0, u1), V(v0, v1);
        int inside = 0;
        for (int tries = 0; tries < 200 && inside < 12; ++tries) {
            const double u = U(rng), v = V(rng);
            const TrimClass cls = ts.classify({u, v});
            if (cls == TrimClass::Boundary) continue;
            BRepClass_FaceClassifier fc(face, gp_Pnt2d(u, v), 1e-9);
            if (fc.State() != TopAbs_ON) {
                CHECK((cls == TrimClass::Inside) == (fc.State() == TopAbs_IN));
                ++stats.classified;
            }
            if (cls != TrimClass::Inside) continue;
            ++inside;
            const double d = (ts.point(u, v) - vec(as.Value(u, v))).norm();
            note(d);
            CHECK(d <= tol);
            ++stats.facePoints;
            gp_Pnt p;
            gp_Vec du, dv;
            as.D1(u, v, p, du, dv);
            const gp_Vec n = du.Crossed(dv);
            if (n.Magnitude() > 1e-6 * du.Magnitude() * dv.Magnitude()) {
                const Eigen::Vector3d theirs = vec(gp_Pnt(n.XYZ())).normalized();
                CHECK(ts.normal(u, v).dot(theirs) > 1 - 1e-9);
            }
        }
    }
    return stats;
}

} // namespace

TEST_CASE("the sample parts Debian ships read as Open CASCADE reads them", "[cad]")
{
    REQUIRE(std::filesystem::exists(kData + "/step/screw.step")); // occt-misc (scripts/install-deps.sh)
    for (const char* file : {"step/screw.step", "step/linkrods.step", "iges/bearing.iges", "iges/hammer.iges"}) {
        const std::string path = kData + "/" + file;
        std::vector<std::string> warnings;
        const Part part = readCadFile(path, &warnings);
        CHECK(part.units == "mm");
        const Stats s = compare(test::occtRead(path), part, path);
        INFO(path << ": " << s.edgePoints << " edge, " << s.trimPoints << " trim, " << s.facePoints
                  << " face points; worst " << s.worst << "; trim ends near breaks " << s.endsNearBreaks);
        CHECK(s.endsNearBreaks <= 8);
        CHECK(s.facePoints > 10 * static_cast<int>(part.faces.size()) / 2);
        CHECK(s.classified > 0);
    }
    // The .brep files, read with Open CASCADE's own reader, converted from the shape. Under the
    // sanitizers (support/sanitizers.h) three of them, which hold every surface kind of the
    // eleven: the eleven took 80 s there.
    std::vector<const char*> breps = {"Ball", "bottle", "CrankArm", "Motor-c", "Pump_Nut", "wing", "hammer",
                                      "Axis_of_bearing", "Pump_TopCover", "MODERN_Chair_1", "mal_vis"};
    if (test::underSanitizers) breps = {"Ball", "CrankArm", "Pump_Nut"};
    for (const char* file : breps) {
        const std::string path = kData + "/occ/" + file + ".brep";
        const TopoDS_Shape shape = test::occtRead(path);
        const Stats s = compare(shape, partFromShape(shape), path);
        CHECK(s.facePoints > 0);
    }
}

TEST_CASE("parts built with Open CASCADE read back from STEP as Open CASCADE reads them", "[cad]")
{
    const std::pair<const char*, TopoDS_Shape> parts[] = {
        {"box_with_holes", boxWithHoles()},
        {"filleted_box", filletedBox()},
        {"bspline_revolution", bsplineRevolution()},
        {"bspline_prism", bsplinePrism()},
        {"cylinder", BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(1, 2, 3), gp_Dir(1, 1, 0)), 2, 5).Shape()},
        {"torus", BRepPrimAPI_MakeTorus(gp_Ax2(gp_Pnt(0, 0, 1), gp_Dir(0, 1, 1)), 4, 1).Shape()},
        {"sphere", BRepPrimAPI_MakeSphere(gp_Pnt(1, -1, 0), 3).Shape()},
        {"cone", BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 3, 1, 4).Shape()},
        {"fused", BRepAlgoAPI_Fuse(filletedBox(), BRepPrimAPI_MakeSphere(gp_Pnt(2, 1, 2), 1.5).Shape()).Shape()},
    };
    for (const auto& [name, shape] : parts) {
        INFO(name);
        // The shape itself, and the STEP file Open CASCADE writes of it.
        const Part direct = partFromShape(shape);
        compare(shape, direct, name);
        CHECK(checkPart(direct).closed);
        const std::string path = writeStep(shape, name);
        const Part read = readCadFile(path);
        const Stats s = compare(test::occtRead(path), read, path);
        CHECK(s.facePoints >= 12);
        CHECK(checkPart(read).closed);
        CHECK(checkPart(read).openEdges == 0);
    }
}

TEST_CASE("a periodic B-spline face whose range straddles its period's start reads and meshes", "[cad]")
{
    // Ball.brep written as STEP: Open CASCADE reads its sphere faces' B-splines back as periodic,
    // with the period starting at the first knot, and face 10's range runs across that start. The
    // period now starts at the face's range (a knot inserted there): before, reading gave a face
    // that the mesher refused ("its u range straddles the start of its periodic surface's period").
    const std::string path = std::string(FREEFORM_TEST_TMP) + "/cad_ball.step";
    std::filesystem::remove(path);
    const Part original = readCadFile(kData + "/occ/Ball.brep");
    REQUIRE(writeCadFile(original, path).valid);
    const TopoDS_Shape shape = test::occtRead(path);
    // (That face is periodic and straddles its period's start as Open CASCADE reads it.)
    TopTools_IndexedMapOfShape faces;
    TopExp::MapShapes(shape, TopAbs_FACE, faces);
    const TopoDS_Face face10 = TopoDS::Face(faces(10));
    const Handle(Geom_BSplineSurface) bs = Handle(Geom_BSplineSurface)::DownCast(BRep_Tool::Surface(face10));
    REQUIRE(!bs.IsNull());
    REQUIRE(bs->IsUPeriodic());
    double u0, u1, v0, v1, a0, a1, b0, b1;
    BRepTools::UVBounds(face10, u0, u1, v0, v1);
    bs->Bounds(a0, a1, b0, b1);
    CHECK((u0 < a0 - 1e-9 || u1 > a1 + 1e-9));
    const Part part = readCadFile(path);
    const Stats s = compare(shape, part, path);
    CHECK(s.facePoints > 0);
    PartMeshOptions options;
    options.tolerance = 0.4;
    const PartMesh m = tessellatePart(part, options);
    CHECK(m.report.certified);
    CHECK(m.report.watertight);
}

TEST_CASE("face areas equal BRepGProp's, and the closed forms of the primitives", "[cad]")
{
    const double pi = std::numbers::pi;
    const std::pair<TopoDS_Shape, double> parts[] = {
        {BRepPrimAPI_MakeBox(2, 3, 4).Shape(), 2 * (6 + 12 + 8)},
        {BRepPrimAPI_MakeSphere(gp_Pnt(1, -1, 0), 3).Shape(), 4 * pi * 9},
        {BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(1, 2, 3), gp_Dir(1, 1, 0)), 2, 5).Shape(), 2 * pi * 2 * (5 + 2)},
        {BRepPrimAPI_MakeTorus(gp_Ax2(gp_Pnt(0, 0, 1), gp_Dir(0, 1, 1)), 4, 1).Shape(), 4 * pi * pi * 4},
        // A cone frustum of radii 3 and 1 and height 4: the lateral pi (3 + 1) sqrt(4^2 + 2^2) and two discs.
        {BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 3, 1, 4).Shape(), pi * 4 * std::sqrt(20.0) + pi * 10},
        {boxWithHoles(), -1},
        {filletedBox(), -1},
        {bsplineRevolution(), -1},
        {bsplinePrism(), -1},
    };
    int index = 0;
    for (const auto& [shape, closedForm] : parts) {
        ++index;
        INFO("part " << index);
        const Part part = partFromShape(shape);
        TopTools_IndexedMapOfShape faces;
        TopExp::MapShapes(shape, TopAbs_FACE, faces);
        double total = 0;
        for (int i = 1; i <= faces.Extent(); ++i) {
            INFO("face " << i << " (" << part.faces[static_cast<std::size_t>(i - 1)].surfaceKind << ")");
            GProp_GProps props;
            const double err = BRepGProp::SurfaceProperties(faces(i), props, 1e-12);
            const double ours = part.faces[static_cast<std::size_t>(i - 1)].surface.area();
            INFO("BRepGProp's error estimate " << err);
            if (index == 9 && part.faces[static_cast<std::size_t>(i - 1)].surfaceKind == "extrusion") {
                // The B-spline prism's curved side: BRepGProp reports 9.4387999725 with an error
                // estimate of 2e-16, 1.1e-6 below the area. Its area is the integral of
                // |C'(u) x D| over the cubic's [0, 1] (D the prism's vector): Simpson in long
                // double on 20000 intervals is the reference there.
                auto integrand = [](long double u) {
                    const long double P[4][2] = {{0, 0}, {1, 2}, {3, -1}, {4, 1}};
                    long double d[2];
                    for (int k = 0; k < 2; ++k)
                        d[k] = 3 * ((1 - u) * (1 - u) * (P[1][k] - P[0][k]) + 2 * u * (1 - u) * (P[2][k] - P[1][k]) +
                                    u * u * (P[3][k] - P[2][k]));
                    const long double D[3] = {0.5L, 0.25L, 2.0L};
                    const long double c[3] = {d[1] * D[2], -d[0] * D[2], d[0] * D[1] - d[1] * D[0]};
                    return std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
                };
                const int n = 20000;
                long double simpson = integrand(0) + integrand(1);
                for (int k = 1; k < n; ++k) simpson += (k % 2 ? 4 : 2) * integrand(static_cast<long double>(k) / n);
                simpson /= 3 * n;
                CHECK(ours == Approx(static_cast<double>(simpson)).epsilon(1e-12));
            } else {
                CHECK(ours == Approx(props.Mass()).epsilon(1e-9));
            }
            total += ours;
        }
        CHECK(part.area() == Approx(total).epsilon(1e-15));
        if (closedForm > 0) CHECK(total == Approx(closedForm).epsilon(1e-10));
    }
    // The sample screw, face by face.
    const TopoDS_Shape screw = test::occtRead(kData + "/step/screw.step");
    const Part part = readCadFile(kData + "/step/screw.step");
    TopTools_IndexedMapOfShape faces;
    TopExp::MapShapes(screw, TopAbs_FACE, faces);
    for (int i = 1; i <= faces.Extent(); ++i) {
        GProp_GProps props;
        BRepGProp::SurfaceProperties(faces(i), props, 1e-12);
        CHECK(part.faces[static_cast<std::size_t>(i - 1)].surface.area() == Approx(props.Mass()).epsilon(1e-9));
    }
}

TEST_CASE("a part keeps the file's length unit: a STEP file written in inches reads in inches", "[cad]")
{
    // Open CASCADE writes the same box in inches when write.step.unit says so; freeform reads the
    // file's unit and keeps its coordinates (a 25.4 mm edge is 1), where Open CASCADE's default
    // reading converts them to millimetres.
    const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(25.4, 0, -50.8), 25.4, 76.2, 127).Shape();
    const std::string path = std::string(FREEFORM_TEST_TMP) + "/cad_box_inch.step";
    {
        test::quietOcct();
        STEPControl_Controller::Init(); // registers write.step.unit
        const std::string old = Interface_Static::CVal("write.step.unit");
        Interface_Static::SetCVal("write.step.unit", "INCH");
        STEPControl_Writer w;
        REQUIRE(w.Transfer(box, STEPControl_AsIs) == IFSelect_RetDone);
        REQUIRE(w.Write(path.c_str()) == IFSelect_RetDone);
        Interface_Static::SetCVal("write.step.unit", old.c_str());
    }
    const Part part = readCadFile(path);
    CHECK(part.units == "in");
    const Box<double, 3> b = part.bounds();
    CHECK((b.min() - Eigen::Vector3d(1, 0, -2)).norm() < 1e-9);
    CHECK((b.max() - Eigen::Vector3d(2, 3, 3)).norm() < 1e-9);
    // Open CASCADE's own reading of the same file, in millimetres, is 25.4 times larger.
    Bnd_Box mm;
    BRepBndLib::Add(test::occtRead(path), mm);
    double x0, y0, z0, x1, y1, z1;
    mm.Get(x0, y0, z0, x1, y1, z1);
    CHECK(x1 == Approx(2 * 25.4).margin(1e-3));
    CHECK(z0 == Approx(-2 * 25.4).margin(1e-3));
    // The unit setting of the transfer is put back: the next millimetre file reads in millimetres.
    CHECK(readCadFile(kData + "/step/screw.step").units == "mm");
    CHECK(std::string(Interface_Static::CVal("xstep.cascade.unit")) == "MM");
}

TEST_CASE("checkPart finds an edge moved off its faces, and open and closed shells", "[cad]")
{
    Part part = partFromShape(BRepPrimAPI_MakeBox(2, 3, 4).Shape());
    PartCheck check = checkPart(part);
    CHECK(check.closed);
    CHECK(check.maxGap < 1e-14);
    CHECK(check.gapsOverTolerance == 0);
    // Move edge 0's curve by 0.01 along a direction normal to it: both faces of the edge see a gap
    // of exactly 0.01, above the edge's tolerance (1e-7).
    PartEdge& e = part.edges[0];
    REQUIRE(e.curve);
    const Eigen::Vector3d along = (e.curve->point(e.last) - e.curve->point(e.first)).normalized();
    const Eigen::Vector3d normal = along.unitOrthogonal();
    PointMatrix<double, 3> p = e.curve->nurbs.controlPoints();
    for (Eigen::Index i = 0; i < p.cols(); ++i) p.col(i) += 0.01 * normal;
    e.curve->nurbs = NurbsCurve<double, 3>(e.curve->nurbs.degree(), e.curve->nurbs.knots(), p, e.curve->nurbs.weights());
    check = checkPart(part);
    CHECK(check.maxGap == Approx(0.01).epsilon(1e-12));
    CHECK(check.gapsOverTolerance == 2);
    // A shell without one of its faces is open: the four edges of that face are used once.
    part.shells[0].faces.pop_back();
    check = checkPart(part);
    CHECK_FALSE(check.closed);
    CHECK(check.openEdges == 4);
    CHECK(part.looseFaces().size() == 1);
}

TEST_CASE("bad CAD input: an error naming the file or the face, and nothing printed", "[cad]")
{
    const std::string dir = std::string(FREEFORM_TEST_TMP);
    CHECK_THROWS_WITH(readCadFile(dir + "/no_such_part.step"), Catch::Contains("no_such_part.step: no such file"));
    {
        std::ofstream(dir + "/not_a_part.step") << "this is not STEP\n";
        std::ofstream(dir + "/not_a_part.igs") << "nor is this IGES\n";
    }
    CHECK_THROWS_WITH(readCadFile(dir + "/not_a_part.step"), Catch::Contains("not_a_part.step"));
    CHECK_THROWS_WITH(readCadFile(dir + "/not_a_part.igs"), Catch::Contains("not_a_part.igs"));
    std::ofstream(dir + "/part.obj") << "v 0 0 0\n";
    CHECK_THROWS_WITH(readCadFile(dir + "/part.obj"), Catch::Contains("not a STEP"));
    CHECK(isCadFile("A.STP"));
    CHECK(isCadFile("b.iges"));
    CHECK_FALSE(isCadFile("c.obj"));

    // An offset surface has no exact rational form: the face is named.
    Handle(Geom_Plane) plane = new Geom_Plane(gp_Pln());
    Handle(Geom_OffsetSurface) offset = new Geom_OffsetSurface(plane, 1.0);
    const TopoDS_Face face = BRepBuilderAPI_MakeFace(offset, 0, 1, 0, 1, 1e-7);
    CHECK_THROWS_WITH(partFromShape(face), Catch::Contains("face 1: a surface of kind Geom_OffsetSurface"));

    // Reading prints nothing (Open CASCADE's IGES reader prints its entity count by default).
    std::ostringstream captured;
    std::streambuf* old = std::cout.rdbuf(captured.rdbuf());
    std::vector<std::string> warnings;
    const Part part = readCadFile(kData + "/iges/hammer.iges", &warnings);
    std::cout.rdbuf(old);
    CHECK(captured.str().empty());
    CHECK(part.faces.size() == 45);
}

} // namespace test_cad_read
