#pragma once
// What the window-less tool tests share (test_tools.cpp, test_spline_joints.cpp,
// test_lattice_tool.cpp, test_nurbs_tool.cpp): a Scene driven through the tools' entry points with
// the context the application would pass them, under a view whose pixels are worked out by hand;
// the curve scene and the distorted box mesh they load, and readings of curves, splines and their
// joints. The subdivision cage tests (test_subdivision_editing.cpp, test_cage_tool.cpp) have their
// own bench, without a view, and their cage files, in cage_test below. Header only.

#include <catch2/catch.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <freeform/core/transform.h>
#include <freeform/subdivision/subdivision_surface.h>

#include "freeform/document/operations.h"
#include "support/process.h"
#include "tools/tools.h"

namespace freeform::editor::tool_test {

template <typename... Parts>
std::string cat(const Parts&... parts)
{
    std::ostringstream out;
    (out << ... << parts);
    return out.str();
}

/// An orthographic view of x in [-4, 4], y in [-2.5, 2.5] looking down -z, 800 x 500 pixels:
/// world (x, y, z) is at pixel (100 (x + 4), 100 (2.5 - y)).
inline Eigen::Matrix4d handViewProjection()
{
    const Eigen::Matrix4d p = orthographic<double>(-4, 4, -2.5, 2.5, 1, 21);
    const Eigen::Matrix4d v = lookAt<double>(Eigen::Vector3d(0, 0, 10), Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitY());
    return p * v;
}

/// A scene with selection, tools and the context the application would pass them.
struct Bench {
    explicit Bench(Scene s) : scene(std::move(s)) {}
    Scene scene;
    Selection selection;
    Tools tools;
    Overlay overlay;
    ToolContext context{scene, selection, 800, 500, handViewProjection()};
    void update()
    {
        overlay.clear();
        tools.update(context, overlay);
        scene.updateGeometry();
    }
    /// Selects object `name` (and its control points `points`); returns its item index.
    int select(const std::string& name, std::vector<int> points = {})
    {
        selection.selectItem(findItem(scene, name));
        selection.setPoints(std::move(points));
        return selection.item;
    }
    /// The document layer's evaluation of object `name` at `at`.
    Eigen::VectorXd eval(const std::string& name, std::vector<double> at)
    {
        const TypedDocument doc(scene.document(), scene.documentDirectory());
        return evaluate(doc, doc.object(name), at, 0).point;
    }
};

/// A 3D cubic "c", a cubic spline "s" of three segments on intervals (1, 2, 0.5) whose joints are
/// neither C1 nor G1, and a lattice "box".
inline Scene curveScene(const std::string& name)
{
    const std::string path = cat(FREEFORM_TEST_TMP, "/", name);
    test::writeText(path, R"({"format": "freeform", "version": 1, "objects": [
      {"name": "c", "type": "bezier_curve", "points": [[-2, 0, 0.5], [-1, 1, 1.5], [0.5, -1, 2], [2, 0.3, -0.5]]},
      {"name": "s", "type": "bezier_spline", "degree": 3, "intervals": [1, 2, 0.5], "points": [
        [-3, 0, 0], [-2.5, 1, 0.2], [-1.8, 1.2, 0.1], [-1, 0.5, 0], [-0.2, 0.9, 0.3], [0.4, -0.6, 0.2],
        [1, -0.5, 0], [1.6, 0.1, -0.2], [2.4, 1.1, 0], [3, 0.2, 0.1]]},
      {"name": "box", "type": "lattice", "degree": [1, 1, 1], "origin": [0, 0, 0], "axes": [[1, 0, 0], [0, 1, 0], [0, 0, 1]],
       "points": [[0,0,0],[0,0,1],[0,1,0],[0,1,1],[1,0,0],[1,0,1],[1,1,0],[1,1,1]]}]})");
    return Scene::load(path);
}

/// The bezier_curve `name` of the scene, as the library's curve.
inline BezierCurve<double, 3> curveOf(const Scene& scene, const std::string& name)
{
    return BezierCurve<double, 3>(Points3(std::get<BezierCurveData>(scene.object(findItem(scene, name)).data).points));
}

/// The bezier_spline `name` of the scene, as saved.
inline const BezierSplineData& splineData(const Scene& scene, const std::string& name)
{
    return std::get<BezierSplineData>(scene.object(findItem(scene, name)).data);
}

/// The bezier_spline `name` of the scene, as the library's spline.
inline BezierSpline<double, 3> splineOf(const Scene& scene, const std::string& name)
{
    const BezierSplineData& d = splineData(scene, name);
    return BezierSpline<double, 3>(d.degree, d.closed, Points3(d.points), d.intervals);
}

/// The continuity report of joint j (the library's analysis of the spline as saved).
inline JointContinuity<double> jointReport(const Scene& scene, const std::string& name, int j)
{
    for (const auto& c : continuityReport(splineOf(scene, name)))
        if (c.joint == j) return c;
    FAIL("no joint " << j);
    return {};
}

/// The largest distance between a at a0 + u and b at b0 + u, u in [0, length] (201 samples, each
/// clamped to its spline's domain).
inline double maxDistance(const BezierSpline<double, 3>& a, double a0, const BezierSpline<double, 3>& b, double b0, double length)
{
    double worst = 0;
    for (int i = 0; i <= 200; ++i) {
        const double u = length * i / 200.0;
        worst = std::max(worst, (a.evaluate(std::min(a0 + u, a.domainEnd())) - b.evaluate(std::min(b0 + u, b.domainEnd()))).norm());
    }
    return worst;
}

/// A press of `button` at pixel (x, y) whose pick ray starts at `origin` along `direction`.
inline PointerEvent press(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, int button = 0, double x = 0, double y = 0)
{
    PointerEvent e;
    e.type = PointerEvent::Type::Press;
    e.button = button;
    e.x = x;
    e.y = y;
    e.rayOrigin = origin;
    e.rayDirection = direction.normalized();
    return e;
}

/// A distorted box: eight vertices, six quads (none axis-aligned).
inline const double kBox[8][3] = {{-1.0, -0.5, -0.25}, {1.2, -0.6, -0.2}, {1.1, 0.7, -0.3}, {-0.9, 0.5, -0.1},
                                  {-1.05, -0.45, 0.8}, {1.0, -0.55, 0.9}, {1.15, 0.65, 0.75}, {-0.95, 0.55, 0.85}};

/// Writes the distorted box as an OBJ file `name` in the tests' temporary folder; returns its path.
inline std::string writeBox(const std::string& name)
{
    std::string text;
    for (const auto& v : kBox) text += cat("v ", v[0], " ", v[1], " ", v[2], "\n");
    text += "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    const std::string path = cat(FREEFORM_TEST_TMP, "/", name);
    test::writeText(path, text);
    return path;
}

} // namespace freeform::editor::tool_test

/// The subdivision cage tests (test_subdivision_editing.cpp, test_cage_tool.cpp): cages in mesh
/// files (data/cages) copied beside a document, read by hand, and the library's limit surface to
/// compare the editor's with.
namespace freeform::editor::cage_test {

namespace fs = std::filesystem;
using tool_test::cat;

inline const std::string kCages = std::string(FREEFORM_SOURCE_DIR) + "/data/cages";

/// A fresh folder under the test folder with the named cage files copied into it.
inline std::string folderWith(const std::string& name, const std::vector<std::string>& cages)
{
    const fs::path dir = fs::path(FREEFORM_TEST_TMP) / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    for (const std::string& c : cages) fs::copy_file(fs::path(kCages) / c, dir / c);
    return dir.string();
}

/// The `v` and `f` lines of an OBJ text, read here by hand (faces 0-based), so that the editor's
/// cage is compared with the file and not with the library's reader.
struct ObjCage {
    Eigen::Matrix3Xd vertices;
    std::vector<std::vector<int>> faces;
};

inline ObjCage readObjByHand(const std::string& path)
{
    std::istringstream in(test::slurp(path));
    std::vector<Eigen::Vector3d> vs;
    ObjCage cage;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream tokens(line);
        std::string tag;
        tokens >> tag;
        if (tag == "v") {
            Eigen::Vector3d p;
            tokens >> p.x() >> p.y() >> p.z();
            vs.push_back(p);
        } else if (tag == "f") {
            std::vector<int> face;
            int v = 0;
            while (tokens >> v) face.push_back(v - 1);
            cage.faces.push_back(face);
        }
    }
    cage.vertices.resize(3, static_cast<Eigen::Index>(vs.size()));
    for (std::size_t i = 0; i < vs.size(); ++i) cage.vertices.col(static_cast<Eigen::Index>(i)) = vs[i];
    return cage;
}

/// The library's limit surface of a cage with the options the editor's Builder uses: adaptive to
/// `tolerance` (the display tolerance, for default object settings), or `level` segments per edge.
inline PolygonMesh libraryTessellation(const SubdivisionCage& cage, double tolerance, int level = 8)
{
    const SubdivisionSurface surface(cage, SubdivisionScheme::Catmark);
    SubdivisionTessellationOptions options;
    options.tolerance = tolerance;
    options.level = level;
    return surface.tessellate(options);
}

/// The largest distance between corresponding vertices of two meshes with the same faces (infinity
/// when the vertex counts or faces differ).
inline double meshDistance(const PolygonMesh& a, const PolygonMesh& b)
{
    if (a.positions.cols() != b.positions.cols() || a.faceVertices != b.faceVertices || a.faceStart != b.faceStart)
        return std::numeric_limits<double>::infinity();
    return a.positions.cols() == 0 ? 0.0 : (a.positions - b.positions).colwise().norm().maxCoeff();
}

/// The distance from p to the nearest vertex of the mesh.
inline double nearestVertex(const PolygonMesh& mesh, const Eigen::Vector3d& p)
{
    return (mesh.positions.colwise() - p).colwise().norm().minCoeff();
}

/// A v1 document text with these objects (JSON text, comma separated).
inline std::string document(const std::string& objects)
{
    std::string text = R"({"format": "freeform", "version": 1, "objects": [)";
    text += objects;
    text += "]}";
    return text;
}

/// A scene with selection, tools and the context the application would pass them (no GL).
struct Bench {
    explicit Bench(Scene s) : scene(std::move(s)) {}
    Scene scene;
    Selection selection;
    Tools tools;
    ToolContext context{scene, selection, 800, 500, Eigen::Matrix4d::Identity()};
};

} // namespace freeform::editor::cage_test
