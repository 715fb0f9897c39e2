#include "tools/cage_tool.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "freeform/core/error.h"
#include "freeform/document/model.h"
#include "freeform/io/geometry_data.h"
#include "tools/tool_util.h"

namespace freeform::editor {

using namespace tool_util;

namespace {

const Vec3f kCrease{1.0f, 0.55f, 0.1f};   // a finite crease
const Vec3f kSharp{1.0f, 0.2f, 0.15f};    // an infinitely sharp one (>= 10)
const Vec3f kPicked{1.0f, 1.0f, 0.3f};    // the picked edge

bool sameEdge(double a, double b, int v0, int v1)
{
    const int x = static_cast<int>(a), y = static_cast<int>(b);
    return (x == v0 && y == v1) || (x == v1 && y == v0);
}

/// The distance in pixels from q to the segment a-b.
double segmentDistance(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& q)
{
    const Eigen::Vector2d d = b - a;
    const double l2 = d.squaredNorm();
    const double t = l2 > 0 ? std::clamp((q - a).dot(d) / l2, 0.0, 1.0) : 0.0;
    return (a + t * d - q).norm();
}

} // namespace

bool CageTool::isCage(const Scene& scene, int item) const
{
    return item >= 0 && item < scene.itemCount() && scene.item(item).kind == SceneItem::Kind::DocumentObject &&
           std::holds_alternative<SubdivisionSurfaceData>(scene.object(item).data);
}

std::optional<SubdivisionCage> CageTool::cageOf(const Scene& scene, int item)
{
    if (item < 0 || item >= scene.itemCount() || scene.item(item).kind != SceneItem::Kind::DocumentObject) return std::nullopt;
    const auto* d = std::get_if<SubdivisionSurfaceData>(&scene.object(item).data);
    if (!d) return std::nullopt;
    if (const TypedObject* o = scene.typed(item)) return std::get<SubdivisionObject>(o->geometry()).cage();
    // An object the document layer refuses (a crease off the cage's edges, ...): its cage as
    // stored, so that it can be mended.
    try {
        return cageFromData(*d, scene.documentDirectory(), "\"" + scene.item(item).name + "\"");
    } catch (const Error&) {
        return std::nullopt;
    }
}

double CageTool::edgeSharpness(const SubdivisionCage& cage, int v0, int v1)
{
    double s = 0;
    for (const EdgeCrease& c : cage.creases)
        if ((c.v0 == v0 && c.v1 == v1) || (c.v0 == v1 && c.v1 == v0)) s = c.sharpness;
    return s;
}

SubdivisionSurfaceData CageTool::inlineData(const Scene& scene, int item) const
{
    return inlineCage(std::get<SubdivisionSurfaceData>(scene.object(item).data), scene.documentDirectory(),
                      "\"" + scene.item(item).name + "\"");
}

bool CageTool::replaceCage(ToolContext& c, int item, const SubdivisionSurfaceData& data, const std::string& label)
{
    // The document layer builds the surface (validateCage: creases on edges, Loop on triangles,
    // ...), so a refused edit never reaches the document.
    try {
        (void)freeform::buildGeometry(data, c.scene.documentDirectory(), "\"" + c.scene.item(item).name + "\""); // validation only
    } catch (const Error& e) {
        status() = e.what();
        return false;
    }
    DocumentObject next = c.scene.object(item);
    next.data = data;
    try {
        c.scene.replaceObject(item, next, label);
    } catch (const Error& e) {
        status() = e.what();
        return false;
    }
    return true;
}

bool CageTool::setText(ToolContext& c, int item, std::string SubdivisionSurfaceData::*field, const std::string& value,
                       const std::string& name)
{
    if (!isCage(c.scene, item)) return status() = "select a subdivision surface", false;
    SubdivisionSurfaceData d = std::get<SubdivisionSurfaceData>(c.scene.object(item).data);
    if (d.*field == value) return true;
    d.*field = value;
    if (!replaceCage(c, item, d, "subdivision " + name)) return false;
    status() = name + " " + value;
    return true;
}

bool CageTool::setScheme(ToolContext& c, int item, const std::string& scheme)
{
    return setText(c, item, &SubdivisionSurfaceData::scheme, scheme, "scheme");
}

bool CageTool::setBoundary(ToolContext& c, int item, const std::string& boundary)
{
    return setText(c, item, &SubdivisionSurfaceData::boundary, boundary, "boundary");
}

bool CageTool::setLevel(ToolContext& c, int item, int level)
{
    if (!isCage(c.scene, item)) return status() = "select a subdivision surface", false;
    const int maxLevel = SubdivisionTessellationOptions{}.maxLevel;
    if (level < 0 || level > maxLevel) return status() = "level must be 0 (adaptive) to " + std::to_string(maxLevel), false;
    ObjectSettings settings = c.scene.item(item).settings;
    if (level == 0) {
        settings.tessellation.mode = Tessellation::Mode::Adaptive;
    } else {
        settings.tessellation.mode = Tessellation::Mode::Uniform;
        settings.tessellation.segments = level;
    }
    c.scene.setSettings(item, settings, "subdivision level");
    return true;
}

bool CageTool::pickEdge(ToolContext& c, int item, int v0, int v1)
{
    if (!isCage(c.scene, item)) return status() = "select a subdivision surface", false;
    const std::optional<SubdivisionCage> cage = cageOf(c.scene, item);
    bool found = false;
    if (cage)
        for (int f = 0; f < cage->mesh.faceCount() && !found; ++f) {
            const int n = cage->mesh.faceSize(f);
            for (int k = 0; k < n && !found; ++k) {
                const int a = cage->mesh.face(f)[k], b = cage->mesh.face(f)[(k + 1) % n];
                found = (a == v0 && b == v1) || (a == v1 && b == v0);
            }
        }
    if (!found) {
        status() = "\"" + c.scene.item(item).name + "\" has no cage edge " + std::to_string(v0) + "-" + std::to_string(v1);
        return false;
    }
    picked_ = std::array<int, 2>{std::min(v0, v1), std::max(v0, v1)};
    pickedItem_ = c.scene.item(item).id;
    status() = "edge " + std::to_string((*picked_)[0]) + "-" + std::to_string((*picked_)[1]) + ", sharpness " +
               std::to_string(edgeSharpness(*cage, v0, v1)).substr(0, 6) + " (S: set, Shift+S: clear)";
    return true;
}

bool CageTool::pickEdgeAt(ToolContext& c, double x, double y, double radius)
{
    const int item = c.selection.item;
    if (!isCage(c.scene, item)) return false;
    const ItemGeometry& g = c.scene.item(item).geometry;
    const Eigen::Vector2d q(x, y);
    double best = radius;
    std::optional<std::pair<int, int>> hit;
    for (const auto& [a, b] : g.netEdges) {
        const auto pa = toPixel(c, g.netPoints.col(a)), pb = toPixel(c, g.netPoints.col(b));
        if (!pa || !pb) continue;
        const double d = segmentDistance(*pa, *pb, q);
        if (d <= best) best = d, hit = std::make_pair(a, b);
    }
    return hit && pickEdge(c, item, hit->first, hit->second);
}

bool CageTool::setCrease(ToolContext& c, int item, int v0, int v1, double s)
{
    if (!isCage(c.scene, item)) return status() = "select a subdivision surface", false;
    if (!std::isfinite(s) || s < 0) return status() = "a crease's sharpness must be finite and >= 0", false;
    try {
        SubdivisionSurfaceData d = inlineData(c.scene, item);
        const std::size_t before = d.creases.size();
        d.creases.erase(std::remove_if(d.creases.begin(), d.creases.end(),
                                       [&](const std::array<double, 3>& e) { return sameEdge(e[0], e[1], v0, v1); }),
                        d.creases.end());
        if (s > 0) d.creases.push_back({double(std::min(v0, v1)), double(std::max(v0, v1)), s});
        const std::string edge = std::to_string(std::min(v0, v1)) + "-" + std::to_string(std::max(v0, v1));
        if (s == 0 && d.creases.size() == before) return status() = "edge " + edge + " has no crease", true; // no change
        if (!replaceCage(c, item, d, s > 0 ? "set crease" : "clear crease")) return false;
        status() = s > 0 ? "crease " + edge + " sharpness " + std::to_string(s).substr(0, 6) : "crease " + edge + " cleared";
        return true;
    } catch (const Error& e) {
        status() = e.what();
        return false;
    }
}

bool CageTool::setCorners(ToolContext& c, int item, const std::vector<int>& vertices, double s)
{
    if (!isCage(c.scene, item)) return status() = "select a subdivision surface", false;
    if (vertices.empty()) return status() = "select cage vertices first", false;
    if (!std::isfinite(s) || s < 0) return status() = "a corner's sharpness must be finite and >= 0", false;
    try {
        SubdivisionSurfaceData d = inlineData(c.scene, item);
        for (int v : vertices) {
            if (v < 0 || v >= d.vertices.cols())
                return status() = "\"" + c.scene.item(item).name + "\" has no cage vertex " + std::to_string(v), false;
            d.corners.erase(std::remove_if(d.corners.begin(), d.corners.end(),
                                           [&](const std::array<double, 2>& e) { return static_cast<int>(e[0]) == v; }),
                            d.corners.end());
            if (s > 0) d.corners.push_back({double(v), s});
        }
        if (!replaceCage(c, item, d, s > 0 ? "set corner" : "clear corner")) return false;
        status() = std::to_string(vertices.size()) + (s > 0 ? " corner(s) sharpness " + std::to_string(s).substr(0, 6) : " corner(s) cleared");
        return true;
    } catch (const Error& e) {
        status() = e.what();
        return false;
    }
}

bool CageTool::onKey(ToolContext& c, KeyAction action)
{
    const int item = c.selection.item;
    if (!isCage(c.scene, item)) return false;
    const bool pickedHere = picked_ && pickedItem_ == c.scene.item(item).id;
    switch (action) {
    case KeyAction::CageEdgeMode:
        edgeMode = !edgeMode;
        status() = edgeMode ? "edge mode: click a cage edge to pick it (E again: off)" : "";
        return true;
    case KeyAction::SetCrease:
    case KeyAction::ClearCrease:
        if (!pickedHere) return status() = "pick a cage edge first (E, then click it)", true;
        return setCrease(c, item, (*picked_)[0], (*picked_)[1], action == KeyAction::SetCrease ? sharpness : 0), true;
    case KeyAction::SetCorner:
    case KeyAction::ClearCorner:
        return setCorners(c, item, c.selection.points, action == KeyAction::SetCorner ? sharpness : 0), true;
    default: return false;
    }
}

bool CageTool::onPointer(ToolContext& c, const PointerEvent& e)
{
    if (!edgeMode || e.type != PointerEvent::Type::Press || e.button != 0) return false;
    return pickEdgeAt(c, e.x, e.y);
}

void CageTool::update(ToolContext& c, Overlay& o)
{
    const int item = c.selection.item;
    if (!isCage(c.scene, item)) return;
    const long id = c.scene.item(item).id;
    if (picked_ && pickedItem_ != id) picked_.reset();
    if (!showCage) return;
    if (cacheItem_ != id || cacheChange_ != c.scene.changeCount()) {
        cache_ = cageOf(c.scene, item);
        cacheItem_ = id;
        cacheChange_ = c.scene.changeCount();
    }
    if (!cache_) return;
    const auto& p = cache_->mesh.positions;
    const auto inRange = [&](int v) { return v >= 0 && v < p.cols(); };
    for (const EdgeCrease& e : cache_->creases)
        if (e.sharpness > 0 && inRange(e.v0) && inRange(e.v1))
            o.addLine(f3(p.col(e.v0)), f3(p.col(e.v1)), e.sharpness >= kInfiniteSharpness ? kSharp : kCrease, true);
    for (const VertexCorner& v : cache_->corners)
        if (v.sharpness > 0 && inRange(v.vertex)) o.addPoint(f3(p.col(v.vertex)), v.sharpness >= kInfiniteSharpness ? kSharp : kCrease);
    if (picked_ && inRange((*picked_)[0]) && inRange((*picked_)[1]))
        o.addLine(f3(p.col((*picked_)[0])), f3(p.col((*picked_)[1])), kPicked, true);
}

void CageTool::reset()
{
    picked_.reset();
    pickedItem_ = 0;
    edgeMode = false;
    sharpness = kInfiniteSharpness;
    cache_.reset();
    cacheItem_ = 0;
    cacheChange_ = -1;
}

} // namespace freeform::editor
