#pragma once
// The renderer interface: buffers are uploaded once and redrawn every frame until the scene marks
// them dirty and uploads again. Two backends: OpenGL 3.3 core (createGlRenderer, render/gl_renderer.cpp)
// and the recording backend (render/recording_renderer.h), which keeps the uploaded buffers and the
// draw calls of a frame without any graphics API, for the unit tests (editor/tests/test_drawer.cpp).
// The interface keeps the scene and the UI free of graphics API calls.
//
// A frame: beginFrame (clears, sets the camera) -> draw* calls in any order (depth-tested) ->
// endFrame (resolves multisampling into the target). readPixels returns the last frame.

#include <memory>
#include <string>

#include "render/render_types.h"

namespace freeform::editor {

class Renderer {
public:
    virtual ~Renderer() = default;

    /// Uploads a mesh (new handle when `handle` is empty, else replaces its contents).
    virtual BufferHandle uploadMesh(BufferHandle handle, const MeshData& mesh) = 0;
    /// Replaces the positions, normals and scalars of a mesh uploaded before with the same vertex
    /// count, keeping its triangles: the path of live deformation. The view's arrays are read
    /// during the call only (the scene's own float copies of a deformed mesh: no conversion).
    virtual void updateVertices(BufferHandle handle, const VertexView& vertices) = 0;
    /// The same from a MeshData (`mesh.triangles` is ignored).
    void updateVertices(BufferHandle handle, const MeshData& mesh) { updateVertices(handle, VertexView::of(mesh)); }
    /// Replaces only the per-vertex scalars of a mesh (size V, or empty to drop them).
    virtual void uploadScalars(BufferHandle handle, const std::vector<float>& scalars) = 0;
    virtual BufferHandle uploadLines(BufferHandle handle, const LineData& lines) = 0;
    virtual BufferHandle uploadPoints(BufferHandle handle, const PointData& points) = 0;
    virtual void release(BufferHandle handle) = 0;

    /// Sets the render target size (pixels) and the multisample count (0 or 1: none); the target
    /// is an off-screen framebuffer, shown in a window by presentToWindow().
    virtual void resizeTarget(int width, int height, int samples) = 0;

    virtual void beginFrame(const FrameInfo& frame, const EyeLights& lights) = 0;
    virtual void drawMesh(BufferHandle mesh, const Mat4f& model, const SurfaceStyle& style) = 0;
    virtual void drawLines(BufferHandle lines, const Mat4f& model, bool depthTested = true) = 0;
    /// Points as discs of `diameter` pixels, whatever their distance.
    virtual void drawPoints(BufferHandle points, const Mat4f& model, float diameter) = 0;
    virtual void endFrame() = 0;
    /// Binds the resolved (single-sample) target for drawing on top of the finished frame, e.g. the
    /// user interface, which then appears in the window and in readPixels alike.
    virtual void bindOverlayTarget() = 0;

    /// Copies the resolved frame to the default framebuffer (the window).
    virtual void presentToWindow(int windowWidth, int windowHeight) = 0;
    /// The resolved frame as RGBA, top row first.
    virtual Image readPixels() = 0;
    /// Blocks until the GPU has finished every command (for frame timing).
    virtual void finish() = 0;
    /// The renderer's name (OpenGL: GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)").
    virtual std::string name() const = 0;
    /// Whether this is a software rasteriser (isSoftwareRenderer(name())).
    bool software() const;
};

/// Whether a GL_RENDERER string names one of Mesa's software rasterisers: it contains "llvmpipe",
/// "softpipe", "swrast" or "Software Rasterizer" (case-insensitive; zink on lavapipe, "zink
/// (llvmpipe ...)", too). Everything else is taken for a GPU.
bool isSoftwareRenderer(const std::string& glRenderer);

/// The OpenGL 3.3 core backend; needs a current context with a loader (epoxy) ready.
std::unique_ptr<Renderer> createGlRenderer();

} // namespace freeform::editor
