#pragma once
// What the window-less tool tests share (test_tools.cpp, test_nurbs_tool.cpp): a Scene driven
// through the tools' entry points with the context the application would pass them, under a view
// whose pixels are worked out by hand. Header only.

#include <Eigen/Core>

#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <freeform/core/transform.h>

#include "freeform/document/operations.h"
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

} // namespace freeform::editor::tool_test
