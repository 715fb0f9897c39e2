#pragma once
// What the user has selected and what the pointer hovers: one scene item at a time, and within it a
// set of control points (indices as in ItemGeometry::netPoints, i.e. the order of Scene's
// setControlPoint). Plain data shared by the interaction code (picking, dragging, the gizmo) and the
// tools (curve, spline, surface and lattice panels); never saved in the document.

#include <algorithm>
#include <vector>

namespace freeform::editor {

struct Selection {
    int item = -1;                 // scene item index, -1: none
    std::vector<int> points;       // selected control points of `item`, sorted, unique
    int hoverItem = -1;            // under the pointer this frame (-1: none)
    int hoverPoint = -1;           // control point of hoverItem under the pointer (-1: none)
    int face = -1;                 // a part's face picked in the view or the face table (-1: none)

    bool has(int k) const { return std::binary_search(points.begin(), points.end(), k); }
    void selectItem(int i)
    {
        if (i != item) {
            points.clear();
            face = -1;
        }
        item = i;
    }
    void setPoints(std::vector<int> ks)
    {
        std::sort(ks.begin(), ks.end());
        ks.erase(std::unique(ks.begin(), ks.end()), ks.end());
        points = std::move(ks);
    }
    void togglePoint(int k)
    {
        auto it = std::lower_bound(points.begin(), points.end(), k);
        if (it != points.end() && *it == k) points.erase(it);
        else points.insert(it, k);
    }
    void clear()
    {
        item = -1;
        face = -1;
        points.clear();
    }
};

} // namespace freeform::editor
