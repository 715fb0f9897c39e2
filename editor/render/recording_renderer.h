#pragma once
// The recording backend: a Renderer without a graphics API that keeps what it was given (the
// uploaded meshes, lines and points, per handle) and what a frame would draw (one DrawCall per
// draw*, with the buffer's counts and colours at that moment). Unit tests of the scene drawer and
// the tools use it to check what would be drawn, and how often buffers are uploaded, without a GL
// context or a display. readPixels returns a target-sized image in the frame's background colour
// (no rasterisation: image tests use the OpenGL backend under xvfb).
//
// Invariants: a handle is live from its upload until release; drawing or updating a handle that
// is not live throws freeform::Error (the drawer's bookkeeping is wrong then); updateVertices
// requires the vertex count the handle has.

#include <map>
#include <string>
#include <vector>

#include "render/renderer.h"

namespace freeform::editor {

class RecordingRenderer final : public Renderer {
public:
    enum class Kind { Mesh, Lines, Points };

    /// One draw* call of the current (or last) frame.
    struct DrawCall {
        Kind kind = Kind::Mesh;
        int handle = 0;
        long vertices = 0;      // mesh vertices, line vertices (2 per segment) or points
        long triangles = 0;     // meshes only
        bool depthTested = true;
        float diameter = 0;     // points only
        SurfaceStyle style;     // meshes only
        std::vector<Vec3f> colors; // lines and points: the distinct colours, in first-use order
    };

    /// What a handle holds now.
    struct Buffer {
        Kind kind = Kind::Mesh;
        MeshData mesh;          // Kind::Mesh
        LineData lines;         // Kind::Lines
        PointData points;       // Kind::Points
    };

    /// Upload counters since construction (or clearCounters()).
    struct Counters {
        long meshUploads = 0, vertexUpdates = 0, scalarUploads = 0, lineUploads = 0, pointUploads = 0, releases = 0;
    };

    BufferHandle uploadMesh(BufferHandle handle, const MeshData& mesh) override;
    using Renderer::updateVertices;
    void updateVertices(BufferHandle handle, const VertexView& vertices) override;
    void uploadScalars(BufferHandle handle, const std::vector<float>& scalars) override;
    BufferHandle uploadLines(BufferHandle handle, const LineData& lines) override;
    BufferHandle uploadPoints(BufferHandle handle, const PointData& points) override;
    void release(BufferHandle handle) override;

    void resizeTarget(int width, int height, int samples) override;
    void beginFrame(const FrameInfo& frame, const EyeLights& lights) override;
    void drawMesh(BufferHandle mesh, const Mat4f& model, const SurfaceStyle& style) override;
    void drawLines(BufferHandle lines, const Mat4f& model, bool depthTested = true) override;
    void drawPoints(BufferHandle points, const Mat4f& model, float diameter) override;
    void endFrame() override;
    void bindOverlayTarget() override {}
    void presentToWindow(int, int) override {}
    Image readPixels() override;
    void finish() override {}
    /// rendererName: "recording" unless a test pretends to be another renderer.
    std::string name() const override { return rendererName; }
    std::string rendererName = "recording";

    /// The draw calls of the frame begun last (complete once endFrame was called).
    const std::vector<DrawCall>& calls() const { return calls_; }
    /// The draw calls of one kind in the last frame.
    std::vector<DrawCall> calls(Kind kind) const;
    /// The buffer behind a live handle (Error when it is not live).
    const Buffer& buffer(int handle) const;
    std::size_t liveBuffers() const { return buffers_.size(); }
    const Counters& counters() const { return counters_; }
    void clearCounters() { counters_ = {}; }
    int frames() const { return frames_; }
    const FrameInfo& frame() const { return frame_; }
    const EyeLights& lights() const { return lights_; }
    int samples() const { return samples_; }

private:
    Buffer& live(BufferHandle handle, Kind kind, const char* what);

    std::map<int, Buffer> buffers_;
    int next_ = 1;
    std::vector<DrawCall> calls_;
    Counters counters_;
    FrameInfo frame_;
    EyeLights lights_;
    int width_ = 1, height_ = 1, samples_ = 0, frames_ = 0;
    bool inFrame_ = false;
};

} // namespace freeform::editor
