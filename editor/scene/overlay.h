#pragma once
// Construction geometry drawn on top of the scene for one frame: de Casteljau polygons, de Boor
// points, curvature combs, the translate gizmo, the box-select rectangle's world lines, hover and
// selection highlights. Tools fill it every frame (it is cheap and never saved); SceneDrawer draws
// it after the scene: `lines` depth-tested, `linesOnTop` and `points` over everything.

#include "render/render_types.h"

namespace freeform::editor {

struct Overlay {
    LineData lines;        // pairs of vertices, depth-tested
    LineData linesOnTop;   // pairs of vertices, drawn over the scene (gizmo, constructions)
    PointData points;      // discs of `pointDiameter` pixels, drawn over the scene
    float pointDiameter = 8.0f;

    void clear() { *this = Overlay{}; }
    bool empty() const { return lines.positions.cols() == 0 && linesOnTop.positions.cols() == 0 && points.positions.cols() == 0; }

    void addLine(const Vec3f& a, const Vec3f& b, const Vec3f& color, bool onTop = false)
    {
        LineData& d = onTop ? linesOnTop : lines;
        const Eigen::Index n = d.positions.cols();
        d.positions.conservativeResize(3, n + 2);
        d.colors.conservativeResize(3, n + 2);
        d.positions.col(n) = a;
        d.positions.col(n + 1) = b;
        d.colors.col(n) = color;
        d.colors.col(n + 1) = color;
    }
    void addPoint(const Vec3f& p, const Vec3f& color)
    {
        const Eigen::Index n = points.positions.cols();
        points.positions.conservativeResize(3, n + 1);
        points.colors.conservativeResize(3, n + 1);
        points.positions.col(n) = p;
        points.colors.col(n) = color;
    }
};

} // namespace freeform::editor
