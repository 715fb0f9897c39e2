#include "scene/scene_drawer.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "scene/grid.h"

namespace freeform::editor {

namespace {

const Vec3f kCurveColor(0.95f, 0.8f, 0.25f);
const Vec3f kNetColor(0.62f, 0.64f, 0.68f);
const Vec3f kOutlineColor(0.12f, 0.12f, 0.14f); // a part's edges on its shading
const Vec3f kPointColor(0.95f, 0.55f, 0.2f);
const Vec3f kSelectedNet(1.0f, 1.0f, 1.0f);
const Vec3f kSelectedPoint(1.0f, 0.9f, 0.3f);
const Vec3f kNormalColor(0.3f, 0.85f, 0.95f);

/// The mesh's vertex data for the GPU; with `triangles`, its index list too.
MeshData meshData(const PolygonMesh& mesh, const std::vector<float>& scalars, bool triangles = true)
{
    MeshData d;
    d.positions = mesh.positions.cast<float>();
    d.normals = mesh.normals.cast<float>();
    d.scalars = scalars;
    if (!triangles) return d;
    d.triangles.reserve(static_cast<std::size_t>(mesh.faceCount()) * 3);
    for (int f = 0; f < mesh.faceCount(); ++f)
        for (int k = 0; k < 3; ++k) d.triangles.push_back(static_cast<std::uint32_t>(mesh.face(f)[k]));
    return d;
}

/// A line segment list of `segments` pairs.
class LineBuilder {
public:
    void add(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Vec3f& color)
    {
        points_.push_back(a.cast<float>());
        points_.push_back(b.cast<float>());
        colors_.push_back(color);
        colors_.push_back(color);
    }
    LineData data() const
    {
        LineData d;
        d.positions.resize(3, static_cast<Eigen::Index>(points_.size()));
        d.colors.resize(3, static_cast<Eigen::Index>(points_.size()));
        for (std::size_t i = 0; i < points_.size(); ++i) {
            d.positions.col(static_cast<Eigen::Index>(i)) = points_[i];
            d.colors.col(static_cast<Eigen::Index>(i)) = colors_[i];
        }
        return d;
    }

private:
    std::vector<Vec3f> points_, colors_;
};

} // namespace

SceneDrawer::~SceneDrawer()
{
    clear();
}

void SceneDrawer::clear()
{
    for (auto& [id, gpu] : gpu_) releaseAll(gpu);
    gpu_.clear();
    for (BufferHandle* h : {&grid_, &axes_, &overlayLines_, &overlayTop_, &overlayPoints_})
        if (*h) renderer_.release(*h), *h = {};
    gridScale_ = 0;
}

void SceneDrawer::releaseAll(Gpu& gpu)
{
    for (BufferHandle* h : {&gpu.mesh, &gpu.curve, &gpu.net, &gpu.points, &gpu.normals})
        if (*h) renderer_.release(*h), *h = {};
}

FrameInfo SceneDrawer::frameInfo(const Scene& scene, int width, int height)
{
    FrameInfo f;
    f.width = std::max(width, 1);
    f.height = std::max(height, 1);
    const Eigen::AlignedBox3d box = scene.bounds();
    // The grid reaches a little beyond the scene; keep it inside the clipping range too.
    const double radius = 0.5 * box.diagonal().norm() * 1.6 + 1e-9;
    double near = 0, far = 0;
    scene.camera.clipPlanes(box.center(), radius, near, far);
    f.view = scene.camera.viewMatrix().cast<float>();
    f.projection = scene.camera.projectionMatrix(double(f.width) / double(f.height), near, far).cast<float>();
    f.background = scene.display.background;
    return f;
}

void SceneDrawer::upload(const SceneItem& item, Gpu& gpu, bool selected, double normalLength)
{
    const ItemGeometry& g = item.geometry;
    const bool geometryChanged = gpu.revision != item.revision;
    if (geometryChanged) {
        if (g.surface && g.surface->faceCount() > 0) {
            // Same triangles as on the GPU (only the vertices moved, e.g. a lattice drag): upload
            // the vertex data alone.
            if (gpu.mesh && gpu.topology == item.topology && gpu.vertices == g.surface->vertexCount() &&
                gpu.faces == g.surface->faceCount()) {
                if (g.drawn.revision == item.revision && g.drawn.positions.cols() == g.surface->positions.cols() &&
                    g.drawn.normals.cols() == g.surface->positions.cols()) {
                    // The deformation's own float copies (a lattice drag): nothing to convert.
                    renderer_.updateVertices(gpu.mesh, VertexView{g.drawn.positions.data(), g.drawn.normals.data(),
                                                                  static_cast<std::size_t>(g.drawn.positions.cols()),
                                                                  item.scalars.data(), item.scalars.size()});
                } else {
                    renderer_.updateVertices(gpu.mesh, meshData(*g.surface, item.scalars, false));
                }
            } else {
                gpu.mesh = renderer_.uploadMesh(gpu.mesh, meshData(*g.surface, item.scalars));
                gpu.topology = item.topology;
                gpu.vertices = g.surface->vertexCount();
                gpu.faces = g.surface->faceCount();
            }
            gpu.triangles = g.surface->faceCount();
        } else if (gpu.mesh) {
            renderer_.release(gpu.mesh);
            gpu.mesh = {};
            gpu.triangles = 0;
        }
        LineBuilder curve;
        for (Eigen::Index i = 0; i + 1 < g.curve.cols(); ++i) curve.add(g.curve.col(i), g.curve.col(i + 1), kCurveColor);
        if (g.surface)
            for (const auto& [a, b] : g.outline) curve.add(g.surface->positions.col(a), g.surface->positions.col(b), kOutlineColor);
        gpu.curve = renderer_.uploadLines(gpu.curve, curve.data());
    }
    if (geometryChanged || gpu.selected != selected) {
        LineBuilder net;
        for (const auto& [a, b] : g.netEdges) net.add(g.netPoints.col(a), g.netPoints.col(b), selected ? kSelectedNet : kNetColor);
        gpu.net = renderer_.uploadLines(gpu.net, net.data());
        PointData points;
        points.positions = g.netPoints.cast<float>();
        points.colors.resize(3, g.netPoints.cols());
        points.colors.colwise() = selected ? kSelectedPoint : kPointColor;
        gpu.points = renderer_.uploadPoints(gpu.points, points);
    }
    if (geometryChanged || gpu.normalLength != normalLength) {
        LineBuilder normals;
        if (normalLength > 0 && g.surface && g.surface->normals.cols() == g.surface->positions.cols())
            for (Eigen::Index i = 0; i < g.surface->positions.cols(); ++i)
                normals.add(g.surface->positions.col(i), g.surface->positions.col(i) + normalLength * g.surface->normals.col(i),
                            kNormalColor);
        gpu.normals = renderer_.uploadLines(gpu.normals, normals.data());
    }
    gpu.revision = item.revision;
    gpu.selected = selected;
    gpu.normalLength = normalLength;
}

std::optional<std::pair<float, float>> scalarRange(const Scene& scene)
{
    const DisplaySettings& d = scene.display;
    bool any = false;
    float lo = 0, hi = 0;
    for (int i = 0; i < scene.itemCount(); ++i) {
        const SceneItem& item = scene.item(i);
        if (!item.settings.visible || item.scalars.empty()) continue;
        if (!d.scalarAuto) return std::make_pair(d.scalarMin, d.scalarMax); // fixed: no pass over the scalars
        const auto [a, b] = std::minmax_element(item.scalars.begin(), item.scalars.end());
        lo = any ? std::min(lo, *a) : *a;
        hi = any ? std::max(hi, *b) : *b;
        any = true;
    }
    if (!any) return std::nullopt;
    return std::make_pair(lo, hi);
}

long SceneDrawer::draw(Scene& scene, int width, int height, int selected, const Overlay* overlay, bool stillImage)
{
    scene.updateGeometry();
    const DisplaySettings& d = scene.display;
    const FrameInfo frame = frameInfo(scene, width, height);
    const Eigen::AlignedBox3d box = scene.bounds();
    const double diameter = box.diagonal().norm();

    // Lights in eye space: the headlight at the eye, the others carried by the view matrix.
    EyeLights lights;
    if (d.headlight) {
        lights.positions.push_back(Vec3f::Zero());
        lights.colors.push_back(d.headlightColor);
    }
    for (const PointLight& l : d.lights) {
        if (!l.enabled || static_cast<int>(lights.positions.size()) >= kMaxLights) continue;
        lights.positions.push_back((frame.view * l.position.homogeneous()).head<3>());
        lights.colors.push_back(l.color);
    }

    // Upload what changed; forget items that are gone.
    std::set<long> present;
    for (int i = 0; i < scene.itemCount(); ++i) {
        const SceneItem& item = scene.item(i);
        present.insert(item.id);
        // The normals overlay's lines only while it is shown (length 0: none built): a lattice
        // drag changes a mesh every frame, and its lines were a pass over every vertex.
        upload(item, gpu_[item.id], i == selected, d.normals ? d.normalLength * diameter : 0.0);
    }
    for (auto it = gpu_.begin(); it != gpu_.end();) {
        if (present.count(it->first)) {
            ++it;
        } else {
            releaseAll(it->second);
            it = gpu_.erase(it);
        }
    }

    // Ground grid in the plane z = 0 and the axes, sized to the scene.
    const double extent = std::max({std::abs(box.min().x()), std::abs(box.max().x()), std::abs(box.min().y()),
                                    std::abs(box.max().y()), 0.5 * diameter, 1e-6});
    if (!grid_ || gridScale_ != extent) {
        const double step = gridStep(box); // the step snapping uses
        const int lines = static_cast<int>(std::ceil(extent / step));
        const double reach = lines * step;
        LineBuilder grid;
        const Vec3f minor(0.3f, 0.31f, 0.33f);
        for (int k = -lines; k <= lines; ++k) {
            const double t = k * step;
            grid.add({t, -reach, 0}, {t, reach, 0}, k == 0 ? Vec3f(0.4f, 0.4f, 0.42f) : minor);
            grid.add({-reach, t, 0}, {reach, t, 0}, k == 0 ? Vec3f(0.4f, 0.4f, 0.42f) : minor);
        }
        LineBuilder axes;
        axes.add({0, 0, 0}, {reach, 0, 0}, Vec3f(0.9f, 0.25f, 0.25f));
        axes.add({0, 0, 0}, {0, reach, 0}, Vec3f(0.3f, 0.85f, 0.3f));
        axes.add({0, 0, 0}, {0, 0, reach}, Vec3f(0.3f, 0.45f, 0.95f));
        grid_ = renderer_.uploadLines(grid_, grid.data());
        axes_ = renderer_.uploadLines(axes_, axes.data());
        gridScale_ = extent;
    }

    samples_ = effectiveSamples(d, software_, stillImage);
    renderer_.resizeTarget(frame.width, frame.height, samples_);
    renderer_.beginFrame(frame, lights);
    const Mat4f identity = Mat4f::Identity();
    if (d.grid) renderer_.drawLines(grid_, identity);
    if (d.axes) renderer_.drawLines(axes_, identity);

    const std::optional<std::pair<float, float>> range = scalarRange(scene);
    // Surfaces front to back (by the depth of their bounding box's nearest point along the view
    // direction, ties by index): with the depth test before shading, a fragment hidden by a nearer
    // surface drawn earlier is never shaded, and per-fragment lighting is most of a frame under a
    // software rasteriser (docs/performance.md, "Editor frame time"). Surfaces are opaque, so the
    // picture does not depend on the order (except where two surfaces meet at equal depth).
    const Eigen::Vector3d eye = scene.camera.eye(), forward = -scene.camera.back();
    drawOrder_.clear();
    for (int i = 0; i < scene.itemCount(); ++i) {
        const SceneItem& item = scene.item(i);
        if (!item.settings.visible || item.geometry.bounds.isEmpty()) continue;
        const Eigen::AlignedBox3d& b = item.geometry.bounds;
        const Eigen::Vector3d nearest(forward.x() >= 0 ? b.min().x() : b.max().x(), forward.y() >= 0 ? b.min().y() : b.max().y(),
                                      forward.z() >= 0 ? b.min().z() : b.max().z());
        drawOrder_.emplace_back((nearest - eye).dot(forward), i);
    }
    std::sort(drawOrder_.begin(), drawOrder_.end());
    long triangles = 0;
    for (const auto& [depth, i] : drawOrder_) {
        const SceneItem& item = scene.item(i);
        const Gpu& gpu = gpu_[item.id];
        if (gpu.mesh) {
            SurfaceStyle style;
            style.shading = d.shading;
            style.specular = d.specular;
            style.material = item.settings.ownMaterial ? item.settings.material : d.material;
            style.backColor = d.backColor;
            style.wireframe = d.wireframe;
            style.flipNormals = d.flipNormals;
            style.analysis = d.analysis;
            style.stripes = d.stripes;
            if (!item.scalars.empty() && range) {
                style.scalarMin = range->first;
                style.scalarMax = range->second;
            }
            renderer_.drawMesh(gpu.mesh, identity, style);
            triangles += gpu.triangles;
        }
        renderer_.drawLines(gpu.curve, identity);
        if (d.normals && gpu.normals) renderer_.drawLines(gpu.normals, identity);
    }
    // Control structures on top of the surfaces they steer.
    for (int i = 0; i < scene.itemCount(); ++i) {
        const SceneItem& item = scene.item(i);
        if (!item.settings.visible) continue;
        const Gpu& gpu = gpu_[item.id];
        if (d.controlNets || i == selected) renderer_.drawLines(gpu.net, identity, false);
        if (d.controlPoints || i == selected) renderer_.drawPoints(gpu.points, identity, d.pointSize);
    }
    if (overlay && !overlay->empty()) {
        overlayLines_ = renderer_.uploadLines(overlayLines_, overlay->lines);
        overlayTop_ = renderer_.uploadLines(overlayTop_, overlay->linesOnTop);
        overlayPoints_ = renderer_.uploadPoints(overlayPoints_, overlay->points);
        if (overlay->lines.positions.cols() > 0) renderer_.drawLines(overlayLines_, identity, true);
        if (overlay->linesOnTop.positions.cols() > 0) renderer_.drawLines(overlayTop_, identity, false);
        if (overlay->points.positions.cols() > 0) renderer_.drawPoints(overlayPoints_, identity, overlay->pointDiameter);
    }
    renderer_.endFrame();
    return triangles;
}

} // namespace freeform::editor
