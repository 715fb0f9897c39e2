#include "render/recording_renderer.h"

#include <algorithm>

#include "freeform/core/error.h"

namespace freeform::editor {

namespace {

const char* kindName(RecordingRenderer::Kind k)
{
    switch (k) {
    case RecordingRenderer::Kind::Mesh: return "mesh";
    case RecordingRenderer::Kind::Lines: return "lines";
    case RecordingRenderer::Kind::Points: return "points";
    }
    return "buffer";
}

std::vector<Vec3f> distinctColors(const Eigen::Matrix<float, 3, Eigen::Dynamic>& colors)
{
    std::vector<Vec3f> out;
    for (Eigen::Index i = 0; i < colors.cols(); ++i) {
        const Vec3f c = colors.col(i);
        if (std::find(out.begin(), out.end(), c) == out.end()) out.push_back(c);
    }
    return out;
}

} // namespace

RecordingRenderer::Buffer& RecordingRenderer::live(BufferHandle handle, Kind kind, const char* what)
{
    const auto it = buffers_.find(handle.id);
    if (it == buffers_.end())
        throw Error(std::string("recording renderer: ") + what + " of buffer " + std::to_string(handle.id) + ", which is not live");
    if (it->second.kind != kind)
        throw Error(std::string("recording renderer: ") + what + " of buffer " + std::to_string(handle.id) + ", which holds " +
                    kindName(it->second.kind) + ", not " + kindName(kind));
    return it->second;
}

BufferHandle RecordingRenderer::uploadMesh(BufferHandle handle, const MeshData& mesh)
{
    if (!handle) handle.id = next_++, buffers_[handle.id].kind = Kind::Mesh;
    live(handle, Kind::Mesh, "uploadMesh").mesh = mesh;
    ++counters_.meshUploads;
    return handle;
}

void RecordingRenderer::updateVertices(BufferHandle handle, const VertexView& vertices)
{
    Buffer& b = live(handle, Kind::Mesh, "updateVertices");
    const auto count = static_cast<Eigen::Index>(vertices.count);
    if (count != b.mesh.positions.cols())
        throw Error("recording renderer: updateVertices with " + std::to_string(count) + " vertices for a mesh of " +
                    std::to_string(b.mesh.positions.cols()));
    if (vertices.scalarCount != 0 && vertices.scalarCount != vertices.count)
        throw Error("recording renderer: updateVertices with " + std::to_string(vertices.scalarCount) + " scalars for " +
                    std::to_string(count) + " vertices");
    // Copied, as a driver copies them (the same size: no new memory).
    b.mesh.positions = Eigen::Map<const Eigen::Matrix<float, 3, Eigen::Dynamic>>(vertices.positions, 3, count);
    b.mesh.normals = Eigen::Map<const Eigen::Matrix<float, 3, Eigen::Dynamic>>(vertices.normals, 3, count);
    b.mesh.scalars.assign(vertices.scalars, vertices.scalars + vertices.scalarCount);
    ++counters_.vertexUpdates;
}

void RecordingRenderer::uploadScalars(BufferHandle handle, const std::vector<float>& scalars)
{
    live(handle, Kind::Mesh, "uploadScalars").mesh.scalars = scalars;
    ++counters_.scalarUploads;
}

BufferHandle RecordingRenderer::uploadLines(BufferHandle handle, const LineData& lines)
{
    if (!handle) handle.id = next_++, buffers_[handle.id].kind = Kind::Lines;
    live(handle, Kind::Lines, "uploadLines").lines = lines;
    ++counters_.lineUploads;
    return handle;
}

BufferHandle RecordingRenderer::uploadPoints(BufferHandle handle, const PointData& points)
{
    if (!handle) handle.id = next_++, buffers_[handle.id].kind = Kind::Points;
    live(handle, Kind::Points, "uploadPoints").points = points;
    ++counters_.pointUploads;
    return handle;
}

void RecordingRenderer::release(BufferHandle handle)
{
    if (buffers_.erase(handle.id) == 0)
        throw Error("recording renderer: release of buffer " + std::to_string(handle.id) + ", which is not live");
    ++counters_.releases;
}

void RecordingRenderer::resizeTarget(int width, int height, int samples)
{
    width_ = std::max(1, width);
    height_ = std::max(1, height);
    samples_ = samples;
}

void RecordingRenderer::beginFrame(const FrameInfo& frame, const EyeLights& lights)
{
    frame_ = frame;
    lights_ = lights;
    calls_.clear();
    inFrame_ = true;
}

void RecordingRenderer::drawMesh(BufferHandle mesh, const Mat4f&, const SurfaceStyle& style)
{
    const Buffer& b = live(mesh, Kind::Mesh, "drawMesh");
    DrawCall call;
    call.kind = Kind::Mesh;
    call.handle = mesh.id;
    call.vertices = b.mesh.positions.cols();
    call.triangles = static_cast<long>(b.mesh.triangles.size() / 3);
    call.style = style;
    calls_.push_back(std::move(call));
}

void RecordingRenderer::drawLines(BufferHandle lines, const Mat4f&, bool depthTested)
{
    const Buffer& b = live(lines, Kind::Lines, "drawLines");
    DrawCall call;
    call.kind = Kind::Lines;
    call.handle = lines.id;
    call.vertices = b.lines.positions.cols();
    call.depthTested = depthTested;
    call.colors = distinctColors(b.lines.colors);
    calls_.push_back(std::move(call));
}

void RecordingRenderer::drawPoints(BufferHandle points, const Mat4f&, float diameter)
{
    const Buffer& b = live(points, Kind::Points, "drawPoints");
    DrawCall call;
    call.kind = Kind::Points;
    call.handle = points.id;
    call.vertices = b.points.positions.cols();
    call.depthTested = false;
    call.diameter = diameter;
    call.colors = distinctColors(b.points.colors);
    calls_.push_back(std::move(call));
}

void RecordingRenderer::endFrame()
{
    if (inFrame_) ++frames_;
    inFrame_ = false;
}

Image RecordingRenderer::readPixels()
{
    Image image;
    image.width = width_;
    image.height = height_;
    image.rgba.resize(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * 4);
    auto byte = [](float v) { return static_cast<std::uint8_t>(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f); };
    for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
        image.rgba[i] = byte(frame_.background.x());
        image.rgba[i + 1] = byte(frame_.background.y());
        image.rgba[i + 2] = byte(frame_.background.z());
        image.rgba[i + 3] = 255;
    }
    return image;
}

std::vector<RecordingRenderer::DrawCall> RecordingRenderer::calls(Kind kind) const
{
    std::vector<DrawCall> out;
    for (const DrawCall& c : calls_)
        if (c.kind == kind) out.push_back(c);
    return out;
}

const RecordingRenderer::Buffer& RecordingRenderer::buffer(int handle) const
{
    const auto it = buffers_.find(handle);
    if (it == buffers_.end()) throw Error("recording renderer: buffer " + std::to_string(handle) + " is not live");
    return it->second;
}

} // namespace freeform::editor
