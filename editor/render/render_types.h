#pragma once
// Plain data the renderer draws and the settings it draws with. No graphics API and no UI here:
// the scene fills these structs, a Renderer backend (render/renderer.h) turns them into pixels.

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace freeform::editor {

using Vec3f = Eigen::Vector3f;
using Mat4f = Eigen::Matrix4f;
using Mat3f = Eigen::Matrix3f;

/// How surfaces are lit (docs/math.md, "Lighting and shading"; docs/editor.md says how each is realised on the GPU).
enum class Shading { Flat, Gouraud, Phong };
/// The specular term: Phong (v . r) or Blinn-Phong (n . h).
enum class SpecularModel { Phong, Blinn };
/// What colours a surface: the lit material, reflection lines, or a lit scalar colour map.
enum class SurfaceAnalysis { None, ReflectionLines, ScalarMap };

/// Per-channel material colours and the shininess exponent s of L = sum (Ca + Cd l.n + Cs (v.r)^s) c_y.
struct Material {
    Vec3f ambient{0.08f, 0.08f, 0.09f};
    Vec3f diffuse{0.72f, 0.55f, 0.32f};
    Vec3f specular{0.45f, 0.45f, 0.45f};
    float shininess = 40.0f;
    bool operator==(const Material&) const = default;
};

/// A point light in world coordinates.
struct PointLight {
    Vec3f position{0, 0, 0};
    Vec3f color{1, 1, 1};
    bool enabled = true;
    bool operator==(const PointLight&) const = default;
};

/// The maximum number of lights a shader takes (scene lights plus the headlight).
inline constexpr int kMaxLights = 8;

/// The lights of a frame, in eye space (the renderer's caller transforms world lights; the
/// headlight sits at the eye, the eye-space origin).
struct EyeLights {
    std::vector<Vec3f> positions;
    std::vector<Vec3f> colors;
};

/// A triangle mesh in vertex and index buffers (shared vertices): 3 x V positions and normals,
/// optional per-vertex scalars (empty or V values), 3 x T vertex indices.
struct MeshData {
    Eigen::Matrix<float, 3, Eigen::Dynamic> positions;
    Eigen::Matrix<float, 3, Eigen::Dynamic> normals;
    std::vector<float> scalars;
    std::vector<std::uint32_t> triangles;
};

/// Vertex data its caller keeps, for Renderer::updateVertices: 3 x count positions and normals
/// (column-major, as MeshData's), and count per-vertex scalars or none (scalarCount 0). The
/// renderer copies what it needs before the call returns.
struct VertexView {
    const float* positions = nullptr;
    const float* normals = nullptr;
    std::size_t count = 0;
    const float* scalars = nullptr;
    std::size_t scalarCount = 0;
    /// A view of a MeshData's vertices (its triangles are not part of it).
    static VertexView of(const MeshData& mesh)
    {
        return {mesh.positions.data(), mesh.normals.data(), static_cast<std::size_t>(mesh.positions.cols()), mesh.scalars.data(),
                mesh.scalars.size()};
    }
};

/// Coloured line segments: 3 x 2S positions, one RGB colour per vertex.
struct LineData {
    Eigen::Matrix<float, 3, Eigen::Dynamic> positions;
    Eigen::Matrix<float, 3, Eigen::Dynamic> colors;
};

/// Coloured points drawn as screen-space discs.
struct PointData {
    Eigen::Matrix<float, 3, Eigen::Dynamic> positions;
    Eigen::Matrix<float, 3, Eigen::Dynamic> colors;
};

/// How one mesh is drawn.
struct SurfaceStyle {
    Shading shading = Shading::Phong;
    SpecularModel specular = SpecularModel::Phong;
    Material material;
    Vec3f backColor{0.35f, 0.45f, 0.75f};  // diffuse colour of back faces
    bool wireframe = false;
    Vec3f wireColor{0.1f, 0.1f, 0.1f};
    bool flipNormals = false;               // draw with negated normals (meshes with inward normals)
    SurfaceAnalysis analysis = SurfaceAnalysis::None;
    float stripes = 12.0f;                  // reflection lines across the sphere map
    float scalarMin = 0.0f, scalarMax = 1.0f;
};

/// The camera of a frame and the target size in pixels.
struct FrameInfo {
    Mat4f view = Mat4f::Identity();
    Mat4f projection = Mat4f::Identity();
    int width = 1, height = 1;
    Vec3f background{0.19f, 0.2f, 0.22f};
};

/// An opaque handle of buffers on the GPU; 0 is "none".
struct BufferHandle {
    int id = 0;
    explicit operator bool() const { return id != 0; }
};

/// RGBA pixels, top row first.
struct Image {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;
};

} // namespace freeform::editor
