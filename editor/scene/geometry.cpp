// Derived geometry of scene items: curves sampled to polylines, surfaces tessellated to triangle
// meshes with normals, control nets as edge lists, all through the document layer
// (freeform/document/operations.h: controlNet, AnyCurve::polyline, tessellateObject). Nothing
// here touches the GPU.

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <type_traits>

#include "freeform/document/object_data.h"
#include "freeform/document/document.h"
#include "freeform/document/operations.h"
#include "freeform/io/geometry_data.h"
#include "freeform/io/mesh_io.h"
#include "scene/scene.h"

namespace freeform::editor {

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

std::string faceSummary(const PartData& part, int face)
{
    if (face < 0 || static_cast<std::size_t>(face) >= part.faces.size()) return {};
    const PartFaceData& f = part.faces[static_cast<std::size_t>(face)];
    const std::size_t loops = f.surface.loops.size();
    return "face " + std::to_string(face + 1) + ": " + (f.kind.empty() ? std::string("nurbs") : f.kind) + ", degree " +
           std::to_string(f.surface.surface.degree[0]) + " x " + std::to_string(f.surface.surface.degree[1]) + ", " +
           std::to_string(loops) + (loops == 1 ? " trim loop" : " trim loops");
}

bool isFfdTarget(const SceneItem& item)
{
    const KindInfo* info = item.info();
    return item.kind == SceneItem::Kind::ImportedMesh || (info && info->supports(KindOperation::Part));
}

std::vector<std::pair<int, int>> faceOutline(const PolygonMesh& mesh)
{
    // Each face has vertices of its own (splitFaces), so its trims are the edges of one triangle.
    std::map<std::pair<int, int>, int> uses;
    for (int f = 0; f < mesh.faceCount(); ++f)
        for (int k = 0, n = mesh.faceSize(f); k < n; ++k) {
            const int a = mesh.face(f)[k], b = mesh.face(f)[(k + 1) % n];
            ++uses[{std::min(a, b), std::max(a, b)}];
        }
    std::vector<std::pair<int, int>> outline;
    for (const auto& [edge, count] : uses)
        if (count == 1) outline.push_back(edge);
    return outline;
}

namespace {

/// The control points of an object the document layer refuses, as stored (2D with z = 0; a cage's
/// vertices as read from its file, none when the file cannot be read): still shown, so that the
/// object can be mended by moving them.
Eigen::Matrix<double, 3, Eigen::Dynamic> storedPoints(const ObjectData& data, const std::string& documentDirectory)
{
    Eigen::Matrix<double, 3, Eigen::Dynamic> out(3, 0);
    if (const auto* sub = std::get_if<SubdivisionSurfaceData>(&data)) {
        try {
            out = cageFromData(*sub, documentDirectory, "subdivision surface").mesh.positions;
        } catch (const Error&) {
        }
        return out;
    }
    if (const PointColumns* p = dataPoints(data)) {
        out = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, p->cols());
        out.topRows(std::min<Eigen::Index>(3, p->rows())) = p->topRows(std::min<Eigen::Index>(3, p->rows()));
    }
    return out;
}

void finishBounds(ItemGeometry& g)
{
    g.bounds.setEmpty();
    for (Eigen::Index i = 0; i < g.netPoints.cols(); ++i) g.bounds.extend(Eigen::Vector3d(g.netPoints.col(i)));
    for (Eigen::Index i = 0; i < g.curve.cols(); ++i) g.bounds.extend(Eigen::Vector3d(g.curve.col(i)));
    if (g.surface)
        for (Eigen::Index i = 0; i < g.surface->positions.cols(); ++i) g.bounds.extend(Eigen::Vector3d(g.surface->positions.col(i)));
}

} // namespace

double PixelScale::tolerance(const Eigen::AlignedBox3d& box) const
{
    double z = distance;
    if (perspective) {
        z = std::numeric_limits<double>::infinity();
        for (int c = 0; c < 8; ++c) z = std::min(z, (box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)) - eye).dot(forward));
        z = std::max(z, distance / 20);
    }
    return span * (z / distance) / height;
}

bool withinTwice(const std::vector<double>& built, const std::vector<double>& wanted)
{
    if (built.size() != wanted.size()) return false;
    for (std::size_t p = 0; p < built.size(); ++p)
        if (wanted[p] > 2 * built[p] || wanted[p] < built[p] / 2) return false;
    return true;
}

ItemGeometry invalidGeometry(const ObjectData& data, const std::string& error, const std::string& documentDirectory)
{
    ItemGeometry g;
    g.curve.resize(3, 0);
    g.error = error;
    g.netPoints = storedPoints(data, documentDirectory);
    finishBounds(g);
    return g;
}

ItemGeometry buildGeometry(const Scene& scene, int i, double tolerance, const PixelScale& view)
{
    if (const TypedObject* object = scene.typed(i)) return buildGeometry(*object, scene.item(i).settings, tolerance, view);
    return invalidGeometry(scene.object(i).data, scene.item(i).invalid, scene.documentDirectory());
}

ItemGeometry buildGeometry(const TypedObject& object, const ObjectSettings& settings, double tolerance, const PixelScale& view)
{
    // Every object -> geometry mapping is the document layer's (document/operations.h): the control
    // net, the polyline of a curve or spline, the tessellation of a surface or subdivision surface.
    ItemGeometry g;
    const ControlNet net = controlNet(object);
    g.netPoints = net.points;
    try {
        g.netEdges = net.edges;
        const Tessellation& t = settings.tessellation;
        const double tol = t.tolerance > 0 ? t.tolerance : tolerance;
        if (const auto curve = AnyCurve::of(object)) {
            g.curve = curve->polyline(tol);
            g.curveClosed = curve->closed(); // a closed NURBS (the circle) ends where it starts by itself
        }
        ObjectTessellation options;
        options.tolerance = t.mode == Tessellation::Mode::Uniform ? 0 : tol;
        options.segments = t.segments;
        options.flip = t.flip;
        options.splitFaces = true; // a part's faces shaded apart (creases stay sharp)
        if (view.on() && t.mode == Tessellation::Mode::Adaptive && !(t.tolerance > 0)) {
            // Per patch to the view: each patch's tolerance from its own control-point box.
            const auto surface = AnySurface::of(object);
            if (surface && surface->patches()) {
                for (const Patch& p : surface->patches()->patches.patches) {
                    Eigen::AlignedBox3d box;
                    box.setEmpty();
                    for (Eigen::Index k = 0; k < p.controlPoints().cols(); ++k) box.extend(Eigen::Vector3d(p.controlPoints().col(k)));
                    g.patchBoxes.push_back(box);
                    g.patchTolerance.push_back(view.tolerance(box));
                }
                options.patchTolerance = g.patchTolerance;
            } else if (const auto* sub = std::get_if<SubdivisionObject>(&object.geometry())) {
                // Per region to the view (SubdivisionTessellationOptions::toleranceOf): every cell
                // to the pixel size at its own nearest depth. For the staleness test one box per
                // cage face: its vertices and their neighbours (the faces around its vertices),
                // which hold the face's limit surface.
                const PolygonMesh& cage = sub->cage().mesh;
                std::vector<std::vector<int>> facesAt(static_cast<std::size_t>(cage.vertexCount()));
                for (int f = 0; f < cage.faceCount(); ++f)
                    for (int k = 0; k < cage.faceSize(f); ++k) facesAt[static_cast<std::size_t>(cage.face(f)[k])].push_back(f);
                for (int f = 0; f < cage.faceCount(); ++f) {
                    Eigen::AlignedBox3d box;
                    box.setEmpty();
                    for (int k = 0; k < cage.faceSize(f); ++k)
                        for (int n : facesAt[static_cast<std::size_t>(cage.face(f)[k])])
                            for (int j = 0; j < cage.faceSize(n); ++j) box.extend(Eigen::Vector3d(cage.positions.col(cage.face(n)[j])));
                    g.patchBoxes.push_back(box);
                    g.patchTolerance.push_back(view.tolerance(box));
                }
                // No cell gets more than the coarsest face asks for (the tolerance caps toleranceOf).
                if (!g.patchTolerance.empty()) options.tolerance = *std::max_element(g.patchTolerance.begin(), g.patchTolerance.end());
                options.toleranceOf = [view](const Eigen::AlignedBox3d& box) { return view.tolerance(box); };
            }
        }
        TessellationReport report;
        if (auto mesh = tessellateObject(object, options, &report)) g.surface = withNormals(std::move(*mesh));
        if (g.surface && object.info().supports(KindOperation::Part)) {
            g.outline = faceOutline(*g.surface);
            if (report.triangleFace.size() == static_cast<std::size_t>(g.surface->faceCount())) {
                g.vertexFace.assign(static_cast<std::size_t>(g.surface->vertexCount()), -1);
                for (int t = 0; t < g.surface->faceCount(); ++t)
                    for (int k = 0; k < 3; ++k) g.vertexFace[static_cast<std::size_t>(g.surface->face(t)[k])] = report.triangleFace[static_cast<std::size_t>(t)];
            }
        }
    } catch (const Error& e) {
        // A valid object the tessellation refuses (over a limit): its net without edges, the message.
        g.netEdges.clear();
        g.surface.reset();
        g.patchBoxes.clear();
        g.patchTolerance.clear();
        g.curve.resize(3, 0);
        g.error = e.what();
    }
    finishBounds(g);
    return g;
}

ItemGeometry buildMeshGeometry(const std::string& path, UpAxis up)
{
    ItemGeometry g;
    PolygonMesh mesh = readPolygonMesh(path);
    mesh.validate(path);
    meshToWorld(mesh, up); // a Y-up file into the Z-up world (exact: a signed permutation)
    g.surface = withNormals(std::move(mesh));
    finishBounds(g);
    return g;
}

} // namespace freeform::editor
