#pragma once
// Draws a Scene through the Renderer interface: uploads each item's geometry when its revision
// changed (and only then), builds the frame's camera and lights, and issues the draw calls for
// surfaces, curves, control nets and points, normals, the ground grid and the axes.

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "render/renderer.h"
#include "scene/overlay.h"
#include "scene/scene.h"

namespace freeform::editor {

/// The scalar colour map's range in this frame: the display's fixed range, or with
/// `display.scalarAuto` the range of the scalars of the visible items; nullopt when no visible
/// item carries scalars. (The map and its legend are drawn only with the analysis "scalar map".)
std::optional<std::pair<float, float>> scalarRange(const Scene& scene);

class SceneDrawer {
public:
    explicit SceneDrawer(Renderer& renderer) : renderer_(renderer), software_(renderer.software()) {}
    ~SceneDrawer();
    SceneDrawer(const SceneDrawer&) = delete;
    SceneDrawer& operator=(const SceneDrawer&) = delete;

    /// The camera matrices for a viewport of this size (near/far planes from the scene bounds).
    static FrameInfo frameInfo(const Scene& scene, int width, int height);

    /// Draws the whole scene into the renderer's target (updateGeometry first). `selected` is the
    /// highlighted item or -1; `overlay` (may be null) is drawn last: its lines depth-tested, its
    /// on-top lines and points over everything. `stillImage`: a screenshot rather than a frame of
    /// an interactive view (multisampled under Antialiasing::Auto even by a software renderer).
    /// Returns the number of triangles drawn.
    long draw(Scene& scene, int width, int height, int selected = -1, const Overlay* overlay = nullptr,
              bool stillImage = false);
    /// The multisample count of the last frame drawn (effectiveSamples of its display settings).
    int samples() const { return samples_; }

    /// Forgets every GPU buffer (after the scene was replaced).
    void clear();

private:
    struct Gpu {
        int revision = -1;
        int topology = -1;                 // SceneItem::topology of the uploaded triangles
        long vertices = 0, faces = 0;
        BufferHandle mesh, curve, net, points, normals;
        std::size_t scalarCount = 0;
        bool selected = false;
        double normalLength = 0;
        long triangles = 0;
    };
    void upload(const SceneItem& item, Gpu& gpu, bool selected, double normalLength);
    void releaseAll(Gpu& gpu);

    Renderer& renderer_;
    bool software_ = false;                 // renderer_.software(), asked once
    int samples_ = 0;
    std::map<long, Gpu> gpu_;               // by stable item id (SceneItem::id)
    BufferHandle grid_, axes_;
    BufferHandle overlayLines_, overlayTop_, overlayPoints_;
    double gridScale_ = 0;
    std::vector<std::pair<double, int>> drawOrder_; // this frame's surfaces, nearest first
};

} // namespace freeform::editor
