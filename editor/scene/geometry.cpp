// Derived geometry of scene items: curves sampled to polylines, surfaces tessellated to triangle
// meshes with normals, control nets as edge lists. Everything here is library code driven from
// document data; nothing touches the GPU.

#include <algorithm>
#include <cmath>
#include <set>
#include <type_traits>

#include "freeform/document/operations.h"
#include "freeform/io/geometry_data.h"
#include "freeform/curve/aframe.h"
#include "freeform/curve/bezier_curve.h"
#include "freeform/curve/bezier_spline.h"
#include "freeform/io/mesh_io.h"
#include "freeform/subdivision/subdivision_surface.h"
#include "freeform/surface/bezier_surface.h"
#include "freeform/surface/patch_complex.h"
#include "freeform/tessellate/tessellate.h"
#include "scene/scene.h"

namespace freeform::editor {

namespace {

using Points3 = Eigen::Matrix<double, 3, Eigen::Dynamic>;

/// 2D or 3D points as 3D (z = 0 for 2D).
Points3 to3d(const PointColumns& p)
{
    Points3 out = Points3::Zero(3, p.cols());
    out.topRows(p.rows()) = p;
    return out;
}

/// Edges of a polygon through points first..first+count-1 (closed: back to first).
void polygonEdges(std::vector<std::pair<int, int>>& edges, int first, int count, bool closed)
{
    for (int i = 0; i + 1 < count; ++i) edges.emplace_back(first + i, first + i + 1);
    if (closed && count > 2) edges.emplace_back(first + count - 1, first);
}

/// Edges of a rows x cols grid of points (index i*cols + j).
void gridEdges(std::vector<std::pair<int, int>>& edges, int rows, int cols)
{
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j) {
            if (j + 1 < cols) edges.emplace_back(i * cols + j, i * cols + j + 1);
            if (i + 1 < rows) edges.emplace_back(i * cols + j, (i + 1) * cols + j);
        }
}

Points3 sampleSpline(const BezierSpline<double, 3>& spline, double tolerance)
{
    const std::vector<double> ts = spline.sampleAdaptive(tolerance);
    Points3 out(3, static_cast<Eigen::Index>(ts.size()));
    for (std::size_t k = 0; k < ts.size(); ++k) out.col(static_cast<Eigen::Index>(k)) = spline.evaluate(ts[k]);
    return out;
}

PolygonMesh tessellateItem(const PatchComplex& patches, const ObjectSettings& settings, double tolerance)
{
    const Tessellation& t = settings.tessellation;
    TessellationOptions options;
    if (t.mode == Tessellation::Mode::Uniform) {
        options.tolerance = 0;
        options.segmentsU = options.segmentsV = t.segments;
    } else {
        options.tolerance = t.tolerance > 0 ? t.tolerance : tolerance;
    }
    options.flipNormals = t.flip;
    return tessellate(patches, options);
}

struct Builder {
    const ObjectSettings& settings;
    double tolerance;
    ItemGeometry& g;
    const std::string& documentDirectory;

    void operator()(const BezierCurveData& d)
    {
        g.netPoints = to3d(d.points);
        polygonEdges(g.netEdges, 0, static_cast<int>(d.points.cols()), false);
        const BezierCurve<double, 3> curve(g.netPoints);
        const std::vector<double> ts = curve.sampleAdaptive(t());
        g.curve = curve.evaluateMany(ts);
    }

    void operator()(const BezierSplineData& d)
    {
        g.netPoints = to3d(d.points);
        polygonEdges(g.netEdges, 0, static_cast<int>(d.points.cols()), d.closed);
        const BezierSpline<double, 3> spline(d.degree, d.closed, g.netPoints, d.intervals);
        g.curve = sampleSpline(spline, t());
        g.curveClosed = d.closed;
    }

    void operator()(const DeBoorSplineData& d)
    {
        g.netPoints = to3d(d.points);
        const EndCondition end = parseEndCondition(d.end, "end");
        polygonEdges(g.netEdges, 0, static_cast<int>(d.points.cols()), end == EndCondition::Closed);
        const auto spline = BezierSpline<double, 3>::fromDeBoor(g.netPoints, end, d.intervals);
        g.curve = sampleSpline(spline, t());
        g.curveClosed = end == EndCondition::Closed;
    }

    void operator()(const BezierSurfaceData& d)
    {
        g.netPoints = d.points;
        gridEdges(g.netEdges, d.degree[0] + 1, d.degree[1] + 1);
        PatchComplex patches;
        patches.patches.emplace_back(d.degree[0], d.degree[1], PointMatrix<double, 3>(d.points));
        g.surface = tessellateItem(patches, settings, t());
    }

    void operator()(const DeBoorSurfaceData& d)
    {
        g.netPoints = d.points;
        gridEdges(g.netEdges, d.rows, d.cols);
        const PatchComplex patches = deboorSurfacePatches(PointMatrix<double, 3>(d.points), d.rows, d.cols,
                                                           parseEndCondition(d.end[0], "end[0]"),
                                                           parseEndCondition(d.end[1], "end[1]"));
        g.surface = tessellateItem(patches, settings, t());
    }

    void operator()(const LatticeData& d)
    {
        g.netPoints = d.points;
        const int a = d.degree[0] + 1, b = d.degree[1] + 1, c = d.degree[2] + 1;
        auto index = [&](int i, int j, int k) { return (i * b + j) * c + k; };
        for (int i = 0; i < a; ++i)
            for (int j = 0; j < b; ++j)
                for (int k = 0; k < c; ++k) {
                    if (i + 1 < a) g.netEdges.emplace_back(index(i, j, k), index(i + 1, j, k));
                    if (j + 1 < b) g.netEdges.emplace_back(index(i, j, k), index(i, j + 1, k));
                    if (k + 1 < c) g.netEdges.emplace_back(index(i, j, k), index(i, j, k + 1));
                }
    }

    void operator()(const SubdivisionSurfaceData& d)
    {
        // The cage (inline, or the mesh file beside the document) is the control net: its vertices
        // are the control points, its edges the net; the surface is the tessellated limit surface.
        const SubdivisionCage cage = cageFromData(d, documentDirectory, "subdivision surface");
        g.netPoints = cage.mesh.positions;
        std::set<std::pair<int, int>> edges;
        for (int f = 0; f < cage.mesh.faceCount(); ++f)
            for (int k = 0; k < cage.mesh.faceSize(f); ++k) {
                const int u = cage.mesh.face(f)[k], v = cage.mesh.face(f)[(k + 1) % cage.mesh.faceSize(f)];
                edges.insert({std::min(u, v), std::max(u, v)});
            }
        g.netEdges.assign(edges.begin(), edges.end());
        const SubdivisionSurface surface(cage, parseSubdivisionScheme(d.scheme, "scheme"),
                                         parseBoundaryInterpolation(d.boundary, "boundary"));
        const Tessellation& t = settings.tessellation;
        SubdivisionTessellationOptions options;
        if (t.mode == Tessellation::Mode::Uniform) options.level = std::clamp(t.segments, 1, options.maxLevel);
        else options.tolerance = this->t();
        PolygonMesh mesh = surface.tessellate(options);
        if (t.flip) {
            for (int f = 0; f < mesh.faceCount(); ++f) std::swap(mesh.faceVertices[3 * f + 1], mesh.faceVertices[3 * f + 2]);
            mesh.normals = -mesh.normals;
        }
        g.surface = std::move(mesh);
    }

    double t() const { return settings.tessellation.tolerance > 0 ? settings.tessellation.tolerance : tolerance; }

    // Rational Bézier and NURBS objects: through the document layer (document/operations.h).
    void operator()(const RationalBezierCurveData& d) { documentLayer(d); }
    void operator()(const RationalBezierSurfaceData& d) { documentLayer(d); }
    void operator()(const NurbsCurveData& d) { documentLayer(d); }
    void operator()(const NurbsSurfaceData& d) { documentLayer(d); }
    void documentLayer(const ObjectData& data)
    {
        TypedDocument doc;
        doc.source = "scene";
        const TypedObject& o = doc.object(doc.add("object", data));
        const ControlNet net = controlNet(o);
        g.netPoints = net.points;
        g.netEdges = net.edges;
        if (auto line = objectPolyline(o, t())) g.curve = *line;
        const Tessellation& s = settings.tessellation;
        ObjectTessellation options;
        options.tolerance = s.mode == Tessellation::Mode::Uniform ? 0 : t();
        options.segments = s.segments;
        options.flip = s.flip;
        if (auto mesh = tessellateObject(o, options)) g.surface = std::move(*mesh);
    }
};

} // namespace

PolygonMesh withNormals(PolygonMesh mesh)
{
    if (!mesh.isTriangleMesh()) {
        PolygonMesh triangles;
        triangles.positions = mesh.positions;
        triangles.normals = mesh.normals;
        triangles.texcoords = mesh.texcoords;
        for (int f = 0; f < mesh.faceCount(); ++f)
            for (int k = 1; k + 1 < mesh.faceSize(f); ++k)
                triangles.addFace({mesh.face(f)[0], mesh.face(f)[k], mesh.face(f)[k + 1]});
        mesh = std::move(triangles);
    }
    if (mesh.normals.cols() == mesh.positions.cols() && mesh.normals.cols() > 0) return mesh;
    // Area-weighted vertex normals: the sum of the unnormalised face normals (b - a) x (c - a).
    mesh.normals = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, mesh.positions.cols());
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const int* v = mesh.face(f);
        const Eigen::Vector3d n = (mesh.positions.col(v[1]) - mesh.positions.col(v[0]))
                                      .cross(mesh.positions.col(v[2]) - mesh.positions.col(v[0]));
        for (int k = 0; k < 3; ++k) mesh.normals.col(v[k]) += n;
    }
    for (Eigen::Index i = 0; i < mesh.normals.cols(); ++i) {
        const double length = mesh.normals.col(i).norm();
        mesh.normals.col(i) = length > 0 ? Eigen::Vector3d(mesh.normals.col(i) / length) : Eigen::Vector3d(0, 0, 1);
    }
    return mesh;
}

namespace {

void finishBounds(ItemGeometry& g)
{
    g.bounds.setEmpty();
    for (Eigen::Index i = 0; i < g.netPoints.cols(); ++i) g.bounds.extend(Eigen::Vector3d(g.netPoints.col(i)));
    for (Eigen::Index i = 0; i < g.curve.cols(); ++i) g.bounds.extend(Eigen::Vector3d(g.curve.col(i)));
    if (g.surface)
        for (Eigen::Index i = 0; i < g.surface->positions.cols(); ++i) g.bounds.extend(Eigen::Vector3d(g.surface->positions.col(i)));
}

} // namespace

ItemGeometry buildGeometry(const ObjectData& data, const ObjectSettings& settings, double tolerance,
                           const std::string& documentDirectory)
{
    ItemGeometry g;
    try {
        std::visit(Builder{settings, tolerance, g, documentDirectory}, data);
        if (g.surface) g.surface = withNormals(std::move(*g.surface));
    } catch (const Error& e) {
        g.surface.reset();
        g.curve.resize(3, 0);
        g.error = e.what();
    }
    finishBounds(g);
    return g;
}

ItemGeometry buildMeshGeometry(const std::string& path)
{
    ItemGeometry g;
    PolygonMesh mesh = readPolygonMesh(path);
    mesh.validate(path);
    g.surface = withNormals(std::move(mesh));
    finishBounds(g);
    return g;
}

} // namespace freeform::editor
