// The rational object types of the document (docs/format.md): rational_bezier_curve,
// rational_bezier_surface, nurbs_curve, nurbs_surface. Strict reading (errors naming the object and
// the field / knot), byte-for-byte round trips of what the writer produces, evaluation in each
// type's own parameter against independent values (circles and a sphere, finite differences), the
// certified tessellation bound of rational patches checked against point-to-triangle distances,
// and `freeform eval` in process with its exit statuses.

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "freeform/document/document.h"
#include "freeform/io/geometry_data.h"
#include "freeform/io/mesh_io.h"
#include "freeform/tessellate/tessellate_rational.h"
#include "support/cli.h"

namespace test_cli_rational {

using namespace freeform;
using Json = nlohmann::json;

namespace {

const char* kDoc = R"({"format": "freeform", "version": 1, "objects": [
  {"name": "arc", "type": "rational_bezier_curve", "points": [[1,0],[1,1],[0,1]], "weights": [1, 0.7071067811865476, 1]},
  {"name": "circle", "type": "nurbs_curve", "degree": 2, "knots": [0,0,0,1,1,2,2,3,3,4,4,4],
   "points": [[1,0],[1,1],[0,1],[-1,1],[-1,0],[-1,-1],[0,-1],[1,-1],[1,0]],
   "weights": [1, 0.7071067811865476, 1, 0.7071067811865476, 1, 0.7071067811865476, 1, 0.7071067811865476, 1]},
  {"name": "b", "type": "nurbs_curve", "degree": 3, "knots": [0,0,0,0,0.5,1.5,1.5,3,3,3,3],
   "points": [[0,0,0],[1,2,0],[2,2,1],[3,0,1],[4,1,2],[5,3,0],[6,0,0]]},
  {"name": "cyl", "type": "rational_bezier_surface", "degree": [2, 1],
   "points": [[[1,0,0],[1,0,2]], [[1,1,0],[1,1,2]], [[0,1,0],[0,1,2]]],
   "weights": [[1, 1], [0.7071067811865476, 0.7071067811865476], [1, 1]]},
  {"name": "ns", "type": "nurbs_surface", "degree": [2, 1], "knots": [[0,0,0,1,1,2,2,2],[0,0,3,3]],
   "points": [[[1,0,0],[1,0,2]], [[1,1,0],[1,1,2]], [[0,1,0],[0,1,2]], [[-1,1,0],[-1,1,2]], [[-1,0,0],[-1,0,2]]],
   "weights": [[1, 1], [0.7071067811865476, 0.7071067811865476], [1, 1], [0.7071067811865476, 0.7071067811865476], [1, 1]]}
]})";

std::string replaced(std::string text, const std::string& from, const std::string& to)
{
    const auto at = text.find(from);
    REQUIRE(at != std::string::npos);
    return text.replace(at, from.size(), to);
}

std::string errorOf(const std::string& text)
{
    try {
        TypedDocument doc(parseDocument(text, "t.json"));
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

std::string tmp(const std::string& name) { return std::string(FREEFORM_TEST_TMP) + "/" + name; }

double pointTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c)
{
    // Closest point on a triangle (Ericson, Real-Time Collision Detection 5.1.5), distance.
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return ap.norm();
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return bp.norm();
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return cp.norm();
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
    const double den = 1 / (va + vb + vc);
    return (p - (a + ab * (vb * den) + ac * (vc * den))).norm();
}

} // namespace

TEST_CASE("rational document: the writer's output reads back byte for byte")
{
    const Document doc = parseDocument(kDoc, "t.json");
    REQUIRE(doc.objects.size() == 5);
    CHECK(objectType(doc.objects[0].data) == "rational_bezier_curve");
    CHECK(objectType(doc.objects[1].data) == "nurbs_curve");
    CHECK(objectType(doc.objects[3].data) == "rational_bezier_surface");
    CHECK(objectType(doc.objects[4].data) == "nurbs_surface");
    const std::string once = formatDocument(doc);
    const std::string twice = formatDocument(parseDocument(once, "once.json"));
    CHECK(once == twice);
    // Value for value against the hand-written file.
    const Json a = Json::parse(kDoc), b = Json::parse(once);
    for (std::size_t i = 0; i < a["objects"].size(); ++i)
        for (const char* key : {"points", "weights", "knots", "degree"})
            if (a["objects"][i].contains(key)) CHECK(a["objects"][i][key] == b["objects"][i][key]);
    // A polynomial NURBS (no weights) is written without weights.
    CHECK(!b["objects"][2].contains("weights"));
}

TEST_CASE("rational document: strict validation names the object, the field and the knot")
{
    CHECK(errorOf(kDoc).empty());
    // wrong knot count
    std::string e = errorOf(replaced(kDoc, "[0,0,0,1,1,2,2,3,3,4,4,4]", "[0,0,0,1,1,2,2,3,3,4,4]"));
    CHECK(e.find("object \"circle\"") != std::string::npos);
    CHECK(e.find("field \"knots\"") != std::string::npos);
    CHECK(e.find("11 knots") != std::string::npos);
    // decreasing knot: named by index
    e = errorOf(replaced(kDoc, "[0,0,0,0,0.5,1.5,1.5,3,3,3,3]", "[0,0,0,0,0.5,0.4,1.5,3,3,3,3]"));
    CHECK(e.find("object \"b\"") != std::string::npos);
    CHECK(e.find("knots[5]") != std::string::npos);
    // multiplicity above p + 1
    e = errorOf(replaced(kDoc, "[0,0,0,0,0.5,1.5,1.5,3,3,3,3]", "[0,0,0,0,0,1.5,1.5,3,3,3,3]"));
    CHECK(e.find("knots[4]") != std::string::npos);
    CHECK(e.find("multiplicity") != std::string::npos);
    // non-positive weight
    e = errorOf(replaced(kDoc, "\"weights\": [1, 0.7071067811865476, 1]}", "\"weights\": [1, 0, 1]}"));
    CHECK(e.find("object \"arc\"") != std::string::npos);
    CHECK(e.find("weights[1]") != std::string::npos);
    // weights missing on a rational Bézier curve; weight count
    e = errorOf(replaced(kDoc, ", \"weights\": [1, 0.7071067811865476, 1]}", "}"));
    CHECK(e.find("field \"weights\": is missing") != std::string::npos);
    e = errorOf(replaced(kDoc, "\"weights\": [1, 0.7071067811865476, 1]}", "\"weights\": [1, 1]}"));
    CHECK(e.find("2 weights for 3 points") != std::string::npos);
    // surface weights grid shape, surface knots
    e = errorOf(replaced(kDoc, "[[0,0,0,1,1,2,2,2],[0,0,3,3]]", "[[0,0,0,1,1,2,2,2],[0,0,3]]"));
    CHECK(e.find("object \"ns\"") != std::string::npos);
    CHECK(e.find("knots[1]") != std::string::npos);
    e = errorOf(replaced(kDoc, "\"weights\": [[1, 1], [0.7071067811865476, 0.7071067811865476], [1, 1]]}",
                         "\"weights\": [[1, 1], [0.7071067811865476], [1, 1]]}"));
    CHECK(e.find("weights[1]") != std::string::npos);
    // unknown field, empty domain
    e = errorOf(replaced(kDoc, "\"type\": \"nurbs_curve\", \"degree\": 3", "\"type\": \"nurbs_curve\", \"closed\": true, \"degree\": 3"));
    CHECK(e.find("field \"closed\": unknown field") != std::string::npos);
    e = errorOf(replaced(kDoc, "[0,0,0,0,0.5,1.5,1.5,3,3,3,3]", "[0,0,0,0,0,0,0,0,3,3,3]"));
    CHECK(!e.empty());
}

TEST_CASE("rational document: circles evaluate on the circle, NURBS in their own knot range")
{
    const TypedDocument doc(parseDocument(kDoc, "t.json"));
    for (int k = 0; k <= 64; ++k) {
        const double t = k / 64.0;
        const Evaluation a = evaluate(doc, doc.object("arc"), {t}, 1);
        CHECK(std::abs(a.point.norm() - 1) <= 1e-15);
        // The tangent is perpendicular to the radius.
        CHECK(std::abs(a.point.dot(a.derivatives[0])) <= 1e-14 * a.derivatives[0].norm());
        const Evaluation c = evaluate(doc, doc.object("circle"), {4 * t}, 0);
        CHECK(std::abs(c.point.norm() - 1) <= 1e-15);
    }
    // T in [0, 4], not normalised: T = 1 is the quarter point (0, 1), T = 3 is (0, -1).
    const Evaluation q = evaluate(doc, doc.object("circle"), {1}, 0);
    CHECK(std::abs(q.point[0]) <= 1e-16);
    CHECK(q.point[1] == Approx(1).epsilon(1e-15));
    CHECK(evaluate(doc, doc.object("circle"), {3}, 0).point[1] == Approx(-1).epsilon(1e-15));
    CHECK(parameterDomain(doc.object("circle")) == std::vector<double>{4});
    CHECK_THROWS_WITH(evaluate(doc, doc.object("circle"), {4.5}, 0),
                      Catch::Contains("object \"circle\"") && Catch::Contains("outside") && Catch::Contains("[0, 4]"));
    CHECK_THROWS_WITH(evaluate(doc, doc.object("arc"), {1.5}, 0), Catch::Contains("[0, 1]"));
    // The surfaces: points on the unit cylinder x^2 + y^2 = 1, z = 2 v (rational Bézier) / (2/3) v.
    for (int i = 0; i <= 16; ++i)
        for (int j = 0; j <= 4; ++j) {
            const Evaluation s = evaluate(doc, doc.object("cyl"), {i / 16.0, j / 4.0}, 1);
            CHECK(std::abs(s.point.head<2>().norm() - 1) <= 1e-15);
            CHECK(s.point[2] == Approx(2 * j / 4.0).margin(1e-15));
            REQUIRE(s.normal);
            CHECK((*s.normal - Eigen::Vector3d(s.point[0], s.point[1], 0)).norm() <= 1e-14);
            const Evaluation n = evaluate(doc, doc.object("ns"), {2 * i / 16.0, 3 * j / 4.0}, 0);
            CHECK(std::abs(n.point.head<2>().norm() - 1) <= 1e-15);
            CHECK(n.point[2] == Approx(2 * j / 4.0).margin(1e-15));
        }
    CHECK_THROWS_WITH(evaluate(doc, doc.object("ns"), {1, 3.5}, 0), Catch::Contains("v = 3.5") && Catch::Contains("[0, 3]"));
}

TEST_CASE("rational document: derivatives against central differences")
{
    const TypedDocument doc(parseDocument(kDoc, "t.json"));
    const double h = 1e-5;
    for (double t : {0.1, 0.7, 1.2, 2.0, 2.9}) {
        const Evaluation e = evaluate(doc, doc.object("b"), {t}, 2);
        const Eigen::VectorXd p = evaluate(doc, doc.object("b"), {t + h}, 0).point;
        const Eigen::VectorXd m = evaluate(doc, doc.object("b"), {t - h}, 0).point;
        // Away from knots (0.5, 1.5) the curve is smooth: the first derivative to O(h^2).
        if (std::abs(t - 0.5) > 2 * h && std::abs(t - 1.5) > 2 * h)
            CHECK((e.derivatives[0] - (p - m) / (2 * h)).norm() <= 1e-6 * (1 + e.derivatives[0].norm()));
    }
    for (double t : {0.2, 0.5, 0.9}) {
        const Evaluation e = evaluate(doc, doc.object("arc"), {t}, 2);
        const Evaluation p = evaluate(doc, doc.object("arc"), {t + h}, 1), m = evaluate(doc, doc.object("arc"), {t - h}, 1);
        CHECK((e.derivatives[0] - (p.point - m.point) / (2 * h)).norm() <= 1e-8);
        CHECK((e.derivatives[1] - (p.derivatives[0] - m.derivatives[0]) / (2 * h)).norm() <= 1e-6);
    }
    const Evaluation s = evaluate(doc, doc.object("ns"), {0.6, 1.1}, 1);
    REQUIRE(s.keys == std::vector<std::string>{"u", "v"});
    const Eigen::VectorXd su = (evaluate(doc, doc.object("ns"), {0.6 + h, 1.1}, 0).point -
                                evaluate(doc, doc.object("ns"), {0.6 - h, 1.1}, 0).point) / (2 * h);
    CHECK((s.derivatives[0] - su).norm() <= 1e-8);
}

TEST_CASE("rational document: certified tessellation of rational patches and NURBS surfaces")
{
    const TypedDocument doc(parseDocument(kDoc, "t.json"));
    for (const char* name : {"cyl", "ns"}) {
        for (double tol : {1e-2, 1e-4}) {
            ObjectTessellation o;
            o.tolerance = tol;
            TessellationReport report;
            const auto mesh = tessellateObject(doc.object(name), o, &report);
            REQUIRE(mesh);
            CHECK(report.errorBound <= tol);
            CHECK(report.errorBound > 0);
            // Every surface point within the bound of the mesh (its distance to the nearest triangle).
            const auto dom = parameterDomain(doc.object(name));
            double worst = 0;
            for (int i = 0; i <= 40; ++i)
                for (int j = 0; j <= 10; ++j) {
                    const Eigen::Vector3d p = evaluate(doc, doc.object(name), {dom[0] * (i + 0.37) / 41.5, dom[1] * (j + 0.5) / 11}, 0).point;
                    double best = 1e300;
                    for (int f = 0; f < mesh->faceCount(); ++f) {
                        const int* v = mesh->face(f);
                        best = std::min(best, pointTriangle(p, mesh->positions.col(v[0]), mesh->positions.col(v[1]), mesh->positions.col(v[2])));
                    }
                    worst = std::max(worst, best);
                }
            CHECK(worst <= report.errorBound);
            // The chord error of a circle sampled at angle step a is 1 - cos(a/2): the mesh is no
            // coarser than that tolerance allows (at least one vertex off the straight line).
            CHECK(worst > 0);
            // Crack-free: one shared grid of vertices, every vertex on the cylinder.
            for (Eigen::Index k = 0; k < mesh->positions.cols(); ++k)
                CHECK(std::abs(mesh->positions.col(k).head<2>().norm() - 1) <= 1e-15);
        }
    }
}

TEST_CASE("rational patches: the bound per axis of the patch's frame is exact on a parabola across a line")
{
    // S(u, v) = (v + k v^2, u, c u^2): across (u) a parabola, along (v) a straight line run
    // unevenly. On the cell [0, 1]^2 cut along its diagonal the mesh point T(x) misses S(x) by
    // k v (1 - v) along x (the interpolant of v^2 from the corners is v) and c u (1 - u) across
    // the line in the y-z plane: |S - T| = sqrt(k^2 v^2 (1 - v)^2 + c^2 u^2 (1 - u)^2), largest at
    // the centre, sqrt(k^2 + c^2) / 4. The second differences' norms summed give (k + c) / 4;
    // per axis of the frame (the corners' normal, their u direction, a third) the two parts are
    // orthogonal and the bound is the exact sqrt(k^2 + c^2) / 4 (docs/surfaces.md).
    for (const auto& [k, c] : {std::pair{0.5, 0.5}, std::pair{0.3, 1.7}, std::pair{2.0, 0.1}}) {
        PointMatrix<double, 3> points(3, 9);
        const double xs[3] = {0, 0.5, 1 + k}, ys[3] = {0, 0.5, 1}, zs[3] = {0, 0, c};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) points.col(i * 3 + j) = Eigen::Vector3d(xs[j], ys[i], zs[i]);
        const RationalPatch patch(2, 2, points, Eigen::VectorXd::Ones(9));
        INFO("k " << k << ", c " << c);
        CHECK(patch.evaluate(0.3, 0.6).isApprox(Eigen::Vector3d(0.6 + k * 0.36, 0.3, c * 0.09), 1e-14));
        const double bound = rationalTessellationErrorBound(patch, 1, 1);
        CHECK(std::abs(bound - std::hypot(k, c) / 4) <= 1e-12);
        CHECK(bound < (k + c) / 4 * (1 - 1e-3));
        // Measured: the two triangles (0,0),(1,0),(1,1) and (0,0),(1,1),(0,1) of the cell.
        const Eigen::Vector3d p00 = patch.evaluate(0, 0), p10 = patch.evaluate(1, 0), p01 = patch.evaluate(0, 1), p11 = patch.evaluate(1, 1);
        double worst = 0;
        for (int a = 0; a <= 64; ++a)
            for (int b = 0; b <= 64; ++b) {
                const double u = a / 64.0, v = b / 64.0;
                const Eigen::Vector3d t = u >= v ? Eigen::Vector3d(p00 + u * (p10 - p00) + v * (p11 - p10))
                                                 : Eigen::Vector3d(p00 + v * (p01 - p00) + u * (p11 - p01));
                worst = std::max(worst, (patch.evaluate(u, v) - t).norm());
            }
        CHECK(worst <= bound * (1 + 1e-12));
        CHECK(worst >= bound * (1 - 1e-12)); // attained at the centre, a sample
        // Finer grids: the per-axis parts shrink with their own counts.
        for (const auto& [nu, nv] : {std::pair{2, 3}, std::pair{5, 1}}) {
            const double expected = std::hypot(c / (4.0 * nu * nu), k / (4.0 * nv * nv));
            CHECK(std::abs(rationalTessellationErrorBound(patch, nu, nv) - expected) <= 1e-12);
        }
    }
}

TEST_CASE("rational patches: rationalBounds gives the whole net's bound and the framed one of one pass, to the bit")
{
    // On the parabola across a line above, the whole net's bound sums the two parts' norms,
    // (k + c) / 4, where the frame's is their root sum of squares.
    const double k = 0.3, c = 1.7;
    PointMatrix<double, 3> points(3, 9);
    const double xs[3] = {0, 0.5, 1 + k}, ys[3] = {0, 0.5, 1}, zs[3] = {0, 0, c};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) points.col(i * 3 + j) = Eigen::Vector3d(xs[j], ys[i], zs[i]);
    const RationalPatch parabola(2, 2, points, Eigen::VectorXd::Ones(9));
    CHECK(std::abs(rationalWholeNetBound(parabola, 1, 1) - (k + c) / 4) <= 1e-12);
    // A patch of degree (3, 4) with weights from 0.5 to 2 and points in no plane: both bounds of
    // rationalBounds are the numbers the two separate functions give, bit for bit (the part
    // mesher's searches take either, and the meshes must not depend on which).
    PointMatrix<double, 3> net(3, 20);
    Eigen::VectorXd weights(20);
    for (int i = 0; i <= 3; ++i)
        for (int j = 0; j <= 4; ++j) {
            const int x = i * 5 + j;
            net.col(x) = Eigen::Vector3d(i + 0.1 * std::sin(3.0 * x), j + 0.2 * std::cos(5.0 * x), 0.3 * i * j - 0.7 * std::sin(x));
            weights[x] = 1.25 + 0.75 * std::sin(7.0 * x);
        }
    const RationalPatch patch(3, 4, net, weights);
    for (const RationalPatch* p : {&parabola, &patch})
        for (const auto& [nu, nv] : {std::pair{1, 1}, std::pair{2, 3}, std::pair{7, 1}}) {
            const RationalBounds both = rationalBounds(*p, nu, nv);
            CHECK(both.wholeNet == rationalWholeNetBound(*p, nu, nv));
            CHECK(both.framed == rationalTessellationErrorBound(*p, nu, nv));
            CHECK(both.framed <= both.wholeNet);
        }
    CHECK(rationalBounds(parabola, 1, 1).framed == Approx(std::hypot(k, c) / 4).epsilon(1e-12)); // the frame's, not the whole net's
    CHECK_THROWS_AS(rationalBounds(patch, 0, 1), Error);
}

TEST_CASE("rational document: freeform eval in process, exit statuses")
{
    const std::string path = tmp("rational_eval.json");
    {
        std::ofstream f(path);
        f << kDoc;
    }
    auto r = test::runCli({"eval", path, "--object", "circle", "--at", "2", "--derivatives", "1"});
    REQUIRE(r.status == 0);
    const Json j = Json::parse(r.out);
    CHECK(j["t"] == 2);
    CHECK(j["point"][0].get<double>() == Approx(-1).epsilon(1e-15));
    CHECK(std::abs(j["point"][1].get<double>()) <= 1e-15);
    CHECK(j["derivatives"].size() == 1);
    r = test::runCli({"eval", path, "--object", "ns", "--at", "1,1.5", "--derivatives", "1"});
    REQUIRE(r.status == 0);
    const Json s = Json::parse(r.out);
    CHECK(s["derivatives"].contains("u"));
    CHECK(s.contains("normal"));
    r = test::runCli({"eval", path, "--object", "circle", "--at", "5"});
    CHECK(r.status == 1);
    CHECK(r.out.empty());
    CHECK(r.err.find("outside") != std::string::npos);
    const std::string bad = tmp("rational_bad.json");
    {
        std::ofstream f(bad);
        f << replaced(kDoc, "[0,0,0,1,1,2,2,3,3,4,4,4]", "[0,0,0,1,1,2,2,3,3,4,4]");
    }
    r = test::runCli({"eval", bad, "--object", "circle", "--at", "1"});
    CHECK(r.status == 1);
    CHECK(r.err.find("object \"circle\"") != std::string::npos);
    CHECK(r.err.find("field \"knots\"") != std::string::npos);
}

TEST_CASE("rational document: freeform tessellate of rational and NURBS surfaces")
{
    const std::string path = tmp("rational_tess.json");
    {
        std::ofstream f(path);
        f << kDoc;
    }
    const std::string obj = tmp("rational_tess.obj");
    auto r = test::runCli({"tessellate", path, "--object", "ns", "--tolerance", "0.001", "-o", obj});
    REQUIRE(r.status == 0);
    Json j = Json::parse(r.out);
    CHECK(j["patches"] == 2); // two knot spans in u, one in v
    CHECK(j["error_bound"].get<double>() <= 0.001);
    const PolygonMesh mesh = readPolygonMesh(obj);
    CHECK(mesh.vertexCount() > 0);
    for (Eigen::Index k = 0; k < mesh.positions.cols(); ++k)
        CHECK(std::abs(mesh.positions.col(k).head<2>().norm() - 1) <= 1e-12); // OBJ text keeps 17 digits or fewer
    // The whole document: both rational surfaces (1 + 2 patches).
    r = test::runCli({"tessellate", path, "--segments", "4", "-o", obj});
    REQUIRE(r.status == 0);
    j = Json::parse(r.out);
    CHECK(j["patches"] == 3);
    CHECK(j["triangles"] == 2 * (4 * 4 + 8 * 4));
}

TEST_CASE("rational document: freeform convert to and from NURBS keeps the curve")
{
    const std::string path = tmp("rational_conv.json");
    {
        std::ofstream f(path);
        f << replaced(kDoc, "\"objects\": [", R"("objects": [
  {"name": "sp", "type": "bezier_spline", "degree": 2, "closed": false, "points": [[0,0],[1,2],[2,0],[3,1],[4,4]], "intervals": [1, 2.5]},
  {"name": "cl", "type": "bezier_spline", "degree": 1, "closed": true, "points": [[0,0,0],[1,0,0],[1,1,1]]},
)");
    }
    const TypedDocument before = TypedDocument::read(path);
    const std::string out = tmp("rational_conv_out.json");
    // bezier_spline -> nurbs_curve: the same points at the same global parameter.
    for (const char* name : {"sp", "cl", "arc"}) {
        auto r = test::runCli({"convert", path, "--object", name, "--to", "nurbs_curve", "-o", out});
        REQUIRE(r.status == 0);
        CHECK(Json::parse(r.out)["to"] == "nurbs_curve");
        const TypedDocument after = TypedDocument::read(out);
        REQUIRE(after.object(name).type() == "nurbs_curve");
        const double end = parameterDomain(before.object(name))[0];
        CHECK(parameterDomain(after.object(name))[0] == end);
        for (int k = 0; k <= 20; ++k) {
            const double t = end * k / 20;
            const Evaluation a = evaluate(before, before.object(name), {t}, 1);
            const Evaluation b = evaluate(after, after.object(name), {t}, 1);
            CHECK((a.point - b.point).norm() <= 1e-14);
            if (k % 5 != 0) CHECK((a.derivatives[0] - b.derivatives[0]).norm() <= 1e-12 * (1 + a.derivatives[0].norm()));
        }
    }
    // nurbs_curve (polynomial, spans 0.5, 1, 1.5) -> bezier_spline on the same parameter.
    auto r = test::runCli({"convert", path, "--object", "b", "--to", "bezier_spline", "-o", out});
    REQUIRE(r.status == 0);
    {
        const TypedDocument after = TypedDocument::read(out);
        const auto& d = std::get<BezierSplineData>(after.object("b").data());
        CHECK(d.degree == 3);
        CHECK(d.intervals == std::vector<double>{0.5, 1, 1.5});
        for (int k = 0; k <= 30; ++k) {
            const double t = 3.0 * k / 30;
            CHECK((evaluate(before, before.object("b"), {t}, 0).point - evaluate(after, after.object("b"), {t}, 0).point).norm() <=
                  1e-13);
        }
    }
    // A one-patch NURBS from a rational patch and back.
    r = test::runCli({"convert", path, "--object", "cyl", "--to", "nurbs_surface", "-o", out});
    REQUIRE(r.status == 0);
    r = test::runCli({"convert", out, "--object", "cyl", "--to", "rational_bezier_surface", "-o", tmp("rational_conv_back.json")});
    REQUIRE(r.status == 0);
    {
        const TypedDocument back = TypedDocument::read(tmp("rational_conv_back.json"));
        const auto& a = std::get<RationalBezierSurfaceData>(before.object("cyl").data());
        const auto& b = std::get<RationalBezierSurfaceData>(back.object("cyl").data());
        CHECK((a.points - b.points).norm() <= 1e-15);
        CHECK(a.weights == b.weights);
    }
    // Refused: several rational pieces in one object, already NURBS, the wrong target form.
    r = test::runCli({"convert", path, "--object", "circle", "--to", "bezier_spline", "-o", out});
    CHECK(r.status == 1);
    CHECK(r.err.find("rational") != std::string::npos);
    r = test::runCli({"convert", path, "--object", "circle", "--to", "nurbs_curve", "-o", out});
    CHECK(r.status == 1);
    CHECK(r.err.find("already") != std::string::npos);
    r = test::runCli({"convert", path, "--object", "b", "--to", "bezier_surface", "-o", out});
    CHECK(r.status == 1);
    CHECK(r.err.find("use --to bezier_spline") != std::string::npos);
}

TEST_CASE("rational document: freeform continuity of a nurbs_curve from the geometry")
{
    const std::string path = tmp("rational_cont.json");
    {
        std::ofstream f(path);
        f << replaced(kDoc, "\"objects\": [", R"("objects": [
  {"name": "line", "type": "nurbs_curve", "degree": 2, "knots": [0,0,0,1,1,2,2,2], "points": [[0,0],[1,0],[2,0],[3,0],[4,0]]},
)");
    }
    // b: simple knot 0.5 (C2 for these generic points), double knot 1.5 (C1).
    auto r = test::runCli({"continuity", path, "--object", "b"});
    REQUIRE(r.status == 0);
    Json j = Json::parse(r.out);
    REQUIRE(j["joints"].size() == 2);
    CHECK(j["joints"][0]["t"] == 0.5);
    CHECK(j["joints"][0]["C"] == 2);
    CHECK(j["joints"][1]["t"] == 1.5);
    CHECK(j["joints"][1]["C"] == 1);
    // line: a double knot (C0 by multiplicity) but the points lie evenly on a line: x = 2u, C2.
    r = test::runCli({"continuity", path, "--object", "line"});
    REQUIRE(r.status == 0);
    j = Json::parse(r.out);
    REQUIRE(j["joints"].size() == 1);
    CHECK(j["joints"][0]["C"] == 2);
    CHECK(j["joints"][0]["G"] == 2);
}

TEST_CASE("rational document: deformDocument composes NURBS and rational curves exactly")
{
    TypedDocument doc(parseDocument(R"({"format": "freeform", "version": 1, "objects": [
  {"name": "b", "type": "nurbs_curve", "degree": 3, "knots": [0,0,0,0,0.5,1.5,1.5,3,3,3,3],
   "points": [[0.1,0.1,0.1],[0.2,0.8,0.3],[0.4,0.6,0.9],[0.6,0.2,0.5],[0.7,0.5,0.2],[0.8,0.9,0.4],[0.9,0.3,0.6]],
   "weights": [1, 2, 0.5, 1, 1.5, 1, 1]},
  {"name": "r", "type": "rational_bezier_curve", "points": [[0.2,0.2,0.2],[0.8,0.3,0.5],[0.5,0.9,0.8]], "weights": [1, 3, 1]}
]})", "d.json"));
    LatticeData ld;
    ld.degree = {1, 1, 2};
    ld.points.resize(3, 12);
    for (int i = 0; i <= 1; ++i)
        for (int j = 0; j <= 1; ++j)
            for (int k = 0; k <= 2; ++k) ld.points.col(i * 6 + j * 3 + k) = Eigen::Vector3d(i, j, k / 2.0);
    ld.points.col(1 * 6 + 1 * 3 + 1) += Eigen::Vector3d(0.3, -0.2, 0.25); // not affine
    const Lattice lattice = latticeFromData(ld);
    const TypedDocument before = doc;
    const DeformDocumentReport report = deformDocument(doc, lattice);
    REQUIRE(report.objects.size() == 2);
    CHECK(report.skipped.empty());
    CHECK(report.objects[0].type == "nurbs_curve");
    CHECK(report.objects[1].type == "rational_bezier_curve");
    for (const char* name : {"b", "r"}) {
        const double end = parameterDomain(before.object(name))[0];
        for (int k = 0; k <= 40; ++k) {
            const double t = end * k / 40;
            const Eigen::Vector3d p = evaluate(before, before.object(name), {t}, 0).point;
            const Eigen::Vector3d expected = lattice.deform(p).point; // point-wise FFD, independent of the composition
            CHECK((evaluate(doc, doc.object(name), {t}, 0).point - expected).norm() <= 1e-13);
        }
    }
}

TEST_CASE("rational document: freeform interpolate --degree P passes through the data and reproduces polynomials")
{
    for (int p : {2, 3, 5}) {
        // p(t) = (t, t^p - t, 2 t^2 - t^(p-1)) sampled at uneven given parameters in [0, 1].
        auto f = [p](double t) { return Eigen::Vector3d(t, std::pow(t, p) - t, 2 * t * t - std::pow(t, p - 1)); };
        std::vector<double> params{0, 0.07, 0.2, 0.31, 0.5, 0.62, 0.7, 0.85, 1};
        Json pts = Json::array();
        for (double t : params) pts.push_back({f(t)[0], f(t)[1], f(t)[2]});
        const std::string in = tmp("interp_points.json"), out = tmp("interp_out.json");
        {
            std::ofstream s(in);
            s << Json{{"points", pts}, {"params", params}}.dump();
        }
        auto r = test::runCli({"interpolate", in, "--degree", std::to_string(p), "-o", out});
        REQUIRE(r.status == 0);
        CHECK(Json::parse(r.out)["degree"] == p);
        const TypedDocument doc = TypedDocument::read(out);
        const TypedObject& c = doc.object("interpolant");
        REQUIRE(c.type() == "nurbs_curve");
        for (double t : params) CHECK((evaluate(doc, c, {t}, 0).point - f(t)).norm() <= 1e-12);
        for (int k = 0; k <= 50; ++k) CHECK((evaluate(doc, c, {k / 50.0}, 0).point - f(k / 50.0)).norm() <= 1e-12);
    }
    const std::string in = tmp("interp_points.json");
    CHECK(test::runCli({"interpolate", in, "--degree", "0", "-o", tmp("x.json")}).status == 2);
    CHECK(test::runCli({"interpolate", in, "--degree", "3", "--end", "periodic", "-o", tmp("x.json")}).status == 2);
}

TEST_CASE("rational document: freeform ffd DOC composes the 3D NURBS curve and the rational surfaces, skips 2D objects")
{
    const std::string path = tmp("rational_ffd.json"), lat = tmp("rational_ffd_lattice.json"), out = tmp("rational_ffd_out.json");
    {
        std::ofstream f(path);
        f << kDoc;
    }
    {
        std::ofstream f(lat);
        f << R"({"format": "freeform", "version": 1, "objects": [{"name": "L", "type": "lattice", "degree": [1, 1, 1],
  "origin": [-2, -2, -1], "axes": [[4, 0, 0], [0, 4, 0], [0, 0, 4]],
  "points": [[-2,-2,-1],[-2,-2,3],[-2,2,-1],[-2,2,3],[2,-2,-1],[2,-2,3],[2,2,-1],[3,2,3]]}]})";
    }
    const auto r = test::runCli({"ffd", path, "--lattice", lat, "-o", out});
    REQUIRE(r.status == 0);
    const Json j = Json::parse(r.out);
    // The one rule of docs/ffd.md (deformDocument): the 3D nurbs_curve "b" is composed exactly (it
    // stays a nurbs_curve, its degree times l+m+n = 3), and so are the rational_bezier_surface "cyl"
    // (degrees (2, 1) times 3) and the nurbs_surface "ns" (same, breakpoints kept); the 2D curves
    // are skipped and copied unchanged.
    REQUIRE(j["objects"].size() == 3);
    CHECK(j["objects"][0]["name"] == "b");
    CHECK(j["objects"][0]["type"] == "nurbs_curve");
    CHECK(j["objects"][1]["name"] == "cyl");
    CHECK(j["objects"][1]["type"] == "rational_bezier_surface");
    CHECK(j["objects"][1]["degree"] == Json::array({6, 3}));
    CHECK(j["objects"][1]["inside"] == true);
    CHECK(j["objects"][2]["name"] == "ns");
    CHECK(j["objects"][2]["type"] == "nurbs_surface");
    CHECK(j["objects"][2]["degree"] == Json::array({6, 3}));
    CHECK(j["skipped"].size() == 2);
    const Document before = parseDocument(kDoc, "k"), after = readDocument(out);
    CHECK(std::get<NurbsCurveData>(after.object("circle").data).knots == std::get<NurbsCurveData>(before.object("circle").data).knots);
    const auto& ns = std::get<NurbsSurfaceData>(after.object("ns").data);
    CHECK(ns.knots[0] == std::vector<double>{0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 2, 2, 2, 2, 2, 2, 2});
    CHECK(ns.knots[1] == std::vector<double>{0, 0, 0, 0, 3, 3, 3, 3});
    // Against the lattice applied point by point to the original surfaces' points: the trilinear
    // map, written out here (x + sum B d with only the corner (1, 1, 1) displaced by (1, 0, 0)).
    auto map = [](const Eigen::Vector3d& p) {
        const Eigen::Vector3d stu = (p - Eigen::Vector3d(-2, -2, -1)) / 4;
        return Eigen::Vector3d(p + stu[0] * stu[1] * stu[2] * Eigen::Vector3d(1, 0, 0));
    };
    const TypedDocument a(parseDocument(kDoc, "k")), b = TypedDocument::read(out);
    double worst = 0;
    for (int i = 0; i <= 20; ++i)
        for (int k = 0; k <= 20; ++k) {
            const double u = i / 20.0, v = k / 20.0;
            const Eigen::Vector3d p = evaluate(a, a.object("cyl"), {u, v}, 0).point;
            worst = std::max(worst, (evaluate(b, b.object("cyl"), {u, v}, 0).point - map(p)).norm() / map(p).norm());
            const Eigen::Vector3d q = evaluate(a, a.object("ns"), {2 * u, 3 * v}, 0).point;
            worst = std::max(worst, (evaluate(b, b.object("ns"), {2 * u, 3 * v}, 0).point - map(q)).norm() / map(q).norm());
        }
    CHECK(worst <= 1e-12);
}

} // namespace test_cli_rational
