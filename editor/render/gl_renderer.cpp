// The OpenGL 3.3 core backend of render/renderer.h (functions loaded by libepoxy).
//
// Every frame is drawn into an off-screen framebuffer (multisampled when the driver offers it),
// resolved into a single-sample one, and from there blitted to the window or read back for a
// screenshot: the window and --screenshot go through exactly the same path.

#include <epoxy/gl.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "freeform/core/error.h"
#include "freeform/core/transform.h"
#include "render/renderer.h"
#include "render/shaders.h"

namespace freeform::editor {
namespace {

GLuint compile(GLenum type, const std::string& source, const std::string& name)
{
    const GLuint shader = glCreateShader(type);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
        glGetShaderInfoLog(shader, length, nullptr, log.data());
        glDeleteShader(shader);
        throw Error("shader " + name + " does not compile: " + log);
    }
    return shader;
}

/// A linked program with its uniform locations looked up on first use.
class Program {
public:
    Program() = default;
    Program(const std::string& name, const std::string& prelude, const std::string& vertex, const std::string& geometry,
            const std::string& fragment)
    {
        const std::string head = "#version 330 core\n" + prelude;
        std::vector<GLuint> shaders;
        shaders.push_back(compile(GL_VERTEX_SHADER, head + vertex, name + " (vertex)"));
        if (!geometry.empty()) shaders.push_back(compile(GL_GEOMETRY_SHADER, head + geometry, name + " (geometry)"));
        shaders.push_back(compile(GL_FRAGMENT_SHADER, head + fragment, name + " (fragment)"));
        id_ = glCreateProgram();
        for (GLuint s : shaders) glAttachShader(id_, s);
        glLinkProgram(id_);
        for (GLuint s : shaders) glDeleteShader(s);
        GLint ok = 0;
        glGetProgramiv(id_, GL_LINK_STATUS, &ok);
        if (!ok) {
            GLint length = 0;
            glGetProgramiv(id_, GL_INFO_LOG_LENGTH, &length);
            std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
            glGetProgramInfoLog(id_, length, nullptr, log.data());
            throw Error("shader program " + name + " does not link: " + log);
        }
    }

    void use() const { glUseProgram(id_); }
    GLint at(const char* uniform)
    {
        const auto it = locations_.find(uniform);
        if (it != locations_.end()) return it->second;
        const GLint location = glGetUniformLocation(id_, uniform);
        locations_.emplace(uniform, location);
        return location;
    }
    void set(const char* u, int v) { glUniform1i(at(u), v); }
    void set(const char* u, float v) { glUniform1f(at(u), v); }
    void set(const char* u, const Vec3f& v) { glUniform3fv(at(u), 1, v.data()); }
    void set(const char* u, const Mat4f& m) { glUniformMatrix4fv(at(u), 1, GL_FALSE, m.data()); }
    void set(const char* u, const Mat3f& m) { glUniformMatrix3fv(at(u), 1, GL_FALSE, m.data()); }
    GLuint id() const { return id_; }
    void destroy()
    {
        if (id_) glDeleteProgram(id_);
        id_ = 0;
    }

private:
    GLuint id_ = 0;
    std::map<std::string, GLint> locations_;
};

/// One vertex array with its buffers.
struct Buffers {
    enum class Kind { Mesh, Lines, Points } kind = Kind::Mesh;
    GLuint vao = 0;
    GLuint positions = 0, normals = 0, scalars = 0, colors = 0, indices = 0;
    GLsizei count = 0;      // indices (mesh) or vertices (lines, points)
    bool hasScalars = false;
};

void upload(GLuint& buffer, GLenum target, const void* data, std::size_t bytes)
{
    if (!buffer) glGenBuffers(1, &buffer);
    glBindBuffer(target, buffer);
    glBufferData(target, static_cast<GLsizeiptr>(bytes), data, GL_STATIC_DRAW);
}

void attribute(GLuint location, GLuint buffer, int size)
{
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glEnableVertexAttribArray(location);
    glVertexAttribPointer(location, size, GL_FLOAT, GL_FALSE, 0, nullptr);
}

class GlRenderer final : public Renderer {
public:
    GlRenderer()
    {
        const std::string lighting = shaders::kLighting;
        flat_ = Program("mesh (flat)", std::string("#define FLAT\n") + lighting, shaders::kMeshVertex,
                        shaders::kMeshGeometryFlat, shaders::kMeshFragment);
        gouraud_ = Program("mesh (Gouraud)", std::string("#define GOURAUD\n") + lighting, shaders::kMeshVertex, "",
                           shaders::kMeshFragment);
        phong_ = Program("mesh (Phong)", std::string("#define PHONG\n") + lighting, shaders::kMeshVertex, "",
                         shaders::kMeshFragment);
        solid_ = Program("solid", "", shaders::kSolidVertex, "", shaders::kSolidFragment);
        lines_ = Program("lines", "", shaders::kColorVertex, "", shaders::kLineFragment);
        discs_ = Program("discs", "", shaders::kColorVertex, "", shaders::kDiscFragment);
        glGetIntegerv(GL_MAX_SAMPLES, &maxSamples_);
        if (const GLubyte* n = glGetString(GL_RENDERER)) name_ = reinterpret_cast<const char*>(n);
    }

    ~GlRenderer() override
    {
        for (auto& [id, b] : buffers_) destroy(b);
        destroyTarget();
        for (Program* p : {&flat_, &gouraud_, &phong_, &solid_, &lines_, &discs_}) p->destroy();
    }

    BufferHandle uploadMesh(BufferHandle handle, const MeshData& mesh) override
    {
        if (mesh.normals.cols() != mesh.positions.cols()) throw Error("renderer: a mesh needs one normal per vertex");
        Buffers& b = acquire(handle, Buffers::Kind::Mesh);
        glBindVertexArray(b.vao);
        upload(b.positions, GL_ARRAY_BUFFER, mesh.positions.data(), sizeof(float) * static_cast<std::size_t>(mesh.positions.size()));
        attribute(0, b.positions, 3);
        upload(b.normals, GL_ARRAY_BUFFER, mesh.normals.data(), sizeof(float) * static_cast<std::size_t>(mesh.normals.size()));
        attribute(1, b.normals, 3);
        upload(b.indices, GL_ELEMENT_ARRAY_BUFFER, mesh.triangles.data(), sizeof(std::uint32_t) * mesh.triangles.size());
        b.count = static_cast<GLsizei>(mesh.triangles.size());
        glBindVertexArray(0);
        uploadScalars(handle, mesh.scalars);
        return handle;
    }

    using Renderer::updateVertices;
    void updateVertices(BufferHandle handle, const VertexView& vertices) override
    {
        if (!vertices.positions || !vertices.normals) throw Error("renderer: a mesh needs one normal per vertex");
        Buffers& b = buffers_.at(handle.id);
        const auto bytes = static_cast<GLsizeiptr>(sizeof(float) * 3 * vertices.count);
        glBindBuffer(GL_ARRAY_BUFFER, b.positions);
        glBufferSubData(GL_ARRAY_BUFFER, 0, bytes, vertices.positions);
        glBindBuffer(GL_ARRAY_BUFFER, b.normals);
        glBufferSubData(GL_ARRAY_BUFFER, 0, bytes, vertices.normals);
        glBindBuffer(GL_ARRAY_BUFFER, 0);
        scalars(handle, vertices.scalars, vertices.scalarCount);
    }

    void uploadScalars(BufferHandle handle, const std::vector<float>& values) override { scalars(handle, values.data(), values.size()); }

    BufferHandle uploadLines(BufferHandle handle, const LineData& lines) override
    {
        return uploadColored(handle, Buffers::Kind::Lines, lines.positions, lines.colors);
    }

    BufferHandle uploadPoints(BufferHandle handle, const PointData& points) override
    {
        return uploadColored(handle, Buffers::Kind::Points, points.positions, points.colors);
    }

    void release(BufferHandle handle) override
    {
        const auto it = buffers_.find(handle.id);
        if (it == buffers_.end()) return;
        destroy(it->second);
        buffers_.erase(it);
    }

    void resizeTarget(int width, int height, int samples) override
    {
        width = std::max(width, 1);
        height = std::max(height, 1);
        samples = std::clamp(samples, 0, static_cast<int>(maxSamples_));
        if (samples == 1) samples = 0;
        if (width == width_ && height == height_ && samples == samples_ && resolveFbo_) return;
        destroyTarget();
        width_ = width;
        height_ = height;
        samples_ = samples;
        auto storage = [&](GLuint& rb, GLenum format, int s) {
            glGenRenderbuffers(1, &rb);
            glBindRenderbuffer(GL_RENDERBUFFER, rb);
            if (s > 0) glRenderbufferStorageMultisample(GL_RENDERBUFFER, s, format, width_, height_);
            else glRenderbufferStorage(GL_RENDERBUFFER, format, width_, height_);
        };
        glGenFramebuffers(1, &resolveFbo_);
        glBindFramebuffer(GL_FRAMEBUFFER, resolveFbo_);
        storage(resolveColor_, GL_RGBA8, 0);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolveColor_);
        storage(resolveDepth_, GL_DEPTH24_STENCIL8, 0);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, resolveDepth_);
        checkFramebuffer("the resolve target");
        if (samples_ > 0) {
            glGenFramebuffers(1, &msFbo_);
            glBindFramebuffer(GL_FRAMEBUFFER, msFbo_);
            storage(msColor_, GL_RGBA8, samples_);
            glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msColor_);
            storage(msDepth_, GL_DEPTH24_STENCIL8, samples_);
            glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, msDepth_);
            checkFramebuffer("the multisample target");
        }
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }

    void beginFrame(const FrameInfo& frame, const EyeLights& lights) override
    {
        if (!resolveFbo_) resizeTarget(frame.width, frame.height, 0);
        frame_ = frame;
        lights_ = lights;
        orthographic_ = frame.projection(3, 3) != 0.0f && frame.projection(3, 2) == 0.0f;
        glBindFramebuffer(GL_FRAMEBUFFER, samples_ > 0 ? msFbo_ : resolveFbo_);
        glViewport(0, 0, width_, height_);
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LEQUAL);
        glDepthMask(GL_TRUE);
        glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        if (samples_ > 0) glEnable(GL_MULTISAMPLE);
        glEnable(GL_PROGRAM_POINT_SIZE);
        glClearColor(frame.background.x(), frame.background.y(), frame.background.z(), 1.0f);
        glClearDepth(1.0);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    }

    void drawMesh(BufferHandle handle, const Mat4f& model, const SurfaceStyle& style) override
    {
        const Buffers& b = buffers_.at(handle.id);
        Program& p = style.analysis == SurfaceAnalysis::ReflectionLines ? phong_
                     : style.shading == Shading::Flat                  ? flat_
                     : style.shading == Shading::Gouraud               ? gouraud_
                                                                         : phong_;
        const Mat4f modelView = frame_.view * model;
        p.use();
        p.set("uModelView", modelView);
        p.set("uProjection", frame_.projection);
        p.set("uNormalMatrix", Mat3f(normalMatrix<float>(modelView)));
        p.set("uNormalSign", style.flipNormals ? -1.0f : 1.0f);
        const int count = std::min(static_cast<int>(lights_.positions.size()), kMaxLights);
        p.set("uLightCount", count);
        for (int i = 0; i < count; ++i) {
            char name[32];
            std::snprintf(name, sizeof name, "uLightPosition[%d]", i);
            glUniform3fv(p.at(name), 1, lights_.positions[static_cast<std::size_t>(i)].data());
            std::snprintf(name, sizeof name, "uLightColor[%d]", i);
            glUniform3fv(p.at(name), 1, lights_.colors[static_cast<std::size_t>(i)].data());
        }
        p.set("uAmbient", style.material.ambient);
        p.set("uDiffuse", style.material.diffuse);
        p.set("uSpecular", style.material.specular);
        p.set("uShininess", style.material.shininess);
        p.set("uBackDiffuse", style.backColor);
        p.set("uBlinn", style.specular == SpecularModel::Blinn ? 1 : 0);
        p.set("uOrthographic", orthographic_ ? 1 : 0);
        const bool scalars = style.analysis == SurfaceAnalysis::ScalarMap && b.hasScalars;
        p.set("uAnalysis", style.analysis == SurfaceAnalysis::ReflectionLines ? 1 : scalars ? 2 : 0);
        p.set("uScalarMin", style.scalarMin);
        p.set("uScalarMax", style.scalarMax);
        p.set("uStripes", style.stripes);
        glBindVertexArray(b.vao);
        if (!b.hasScalars) glVertexAttrib1f(2, 0.0f);
        if (style.wireframe) {
            glEnable(GL_POLYGON_OFFSET_FILL);
            glPolygonOffset(1.0f, 1.0f);
        }
        glDrawElements(GL_TRIANGLES, b.count, GL_UNSIGNED_INT, nullptr);
        glDisable(GL_POLYGON_OFFSET_FILL);
        if (style.wireframe) {
            solid_.use();
            solid_.set("uMVP", Mat4f(frame_.projection * modelView));
            solid_.set("uColor", style.wireColor);
            glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
            glDrawElements(GL_TRIANGLES, b.count, GL_UNSIGNED_INT, nullptr);
            glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        }
        glBindVertexArray(0);
    }

    void drawLines(BufferHandle handle, const Mat4f& model, bool depthTested) override
    {
        const Buffers& b = buffers_.at(handle.id);
        if (b.count == 0) return;
        lines_.use();
        lines_.set("uMVP", Mat4f(frame_.projection * frame_.view * model));
        lines_.set("uPointSize", 1.0f);
        if (!depthTested) glDisable(GL_DEPTH_TEST);
        glBindVertexArray(b.vao);
        glDrawArrays(GL_LINES, 0, b.count);
        glBindVertexArray(0);
        glEnable(GL_DEPTH_TEST);
    }

    void drawPoints(BufferHandle handle, const Mat4f& model, float diameter) override
    {
        const Buffers& b = buffers_.at(handle.id);
        if (b.count == 0) return;
        discs_.use();
        discs_.set("uMVP", Mat4f(frame_.projection * frame_.view * model));
        discs_.set("uPointSize", diameter);
        glDisable(GL_DEPTH_TEST);
        glBindVertexArray(b.vao);
        glDrawArrays(GL_POINTS, 0, b.count);
        glBindVertexArray(0);
        glEnable(GL_DEPTH_TEST);
    }

    void endFrame() override
    {
        if (samples_ > 0) {
            glBindFramebuffer(GL_READ_FRAMEBUFFER, msFbo_);
            glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolveFbo_);
            glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        }
        glBindFramebuffer(GL_FRAMEBUFFER, resolveFbo_);
    }

    void bindOverlayTarget() override
    {
        glBindFramebuffer(GL_FRAMEBUFFER, resolveFbo_);
        glViewport(0, 0, width_, height_);
    }

    void presentToWindow(int windowWidth, int windowHeight) override
    {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, resolveFbo_);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        glBlitFramebuffer(0, 0, width_, height_, 0, 0, windowWidth, windowHeight, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }

    Image readPixels() override
    {
        Image image;
        image.width = width_;
        image.height = height_;
        image.rgba.resize(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * 4);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, resolveFbo_);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        std::vector<std::uint8_t> bottomUp(image.rgba.size());
        glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, bottomUp.data());
        const std::size_t row = static_cast<std::size_t>(width_) * 4;
        for (int y = 0; y < height_; ++y)
            std::copy_n(bottomUp.data() + static_cast<std::size_t>(height_ - 1 - y) * row, row,
                        image.rgba.data() + static_cast<std::size_t>(y) * row);
        return image;
    }

    void finish() override { glFinish(); }
    std::string name() const override { return name_; }

private:
    Buffers& acquire(BufferHandle& handle, Buffers::Kind kind)
    {
        if (!handle) {
            handle.id = nextId_++;
            Buffers b;
            b.kind = kind;
            glGenVertexArrays(1, &b.vao);
            buffers_.emplace(handle.id, b);
        }
        Buffers& b = buffers_.at(handle.id);
        if (b.kind != kind) throw Error("renderer: a buffer handle was reused for another kind of data");
        return b;
    }

    /// The mesh's scalars (count values), or none (count 0).
    void scalars(BufferHandle handle, const float* values, std::size_t count)
    {
        Buffers& b = buffers_.at(handle.id);
        glBindVertexArray(b.vao);
        if (count == 0) {
            glDisableVertexAttribArray(2);
            b.hasScalars = false;
        } else {
            upload(b.scalars, GL_ARRAY_BUFFER, values, sizeof(float) * count);
            attribute(2, b.scalars, 1);
            b.hasScalars = true;
        }
        glBindVertexArray(0);
    }

    BufferHandle uploadColored(BufferHandle handle, Buffers::Kind kind, const Eigen::Matrix<float, 3, Eigen::Dynamic>& positions,
                               const Eigen::Matrix<float, 3, Eigen::Dynamic>& colors)
    {
        if (colors.cols() != positions.cols()) throw Error("renderer: lines and points need one colour per vertex");
        Buffers& b = acquire(handle, kind);
        glBindVertexArray(b.vao);
        upload(b.positions, GL_ARRAY_BUFFER, positions.data(), sizeof(float) * static_cast<std::size_t>(positions.size()));
        attribute(0, b.positions, 3);
        upload(b.colors, GL_ARRAY_BUFFER, colors.data(), sizeof(float) * static_cast<std::size_t>(colors.size()));
        attribute(1, b.colors, 3);
        b.count = static_cast<GLsizei>(positions.cols());
        glBindVertexArray(0);
        return handle;
    }

    static void destroy(Buffers& b)
    {
        for (GLuint* buffer : {&b.positions, &b.normals, &b.scalars, &b.colors, &b.indices})
            if (*buffer) glDeleteBuffers(1, buffer);
        if (b.vao) glDeleteVertexArrays(1, &b.vao);
        b = Buffers{};
    }

    static void checkFramebuffer(const char* what)
    {
        const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE)
            throw Error(std::string("renderer: ") + what + " is incomplete (status " + std::to_string(status) + ")");
    }

    void destroyTarget()
    {
        for (GLuint* fbo : {&msFbo_, &resolveFbo_})
            if (*fbo) glDeleteFramebuffers(1, fbo), *fbo = 0;
        for (GLuint* rb : {&msColor_, &msDepth_, &resolveColor_, &resolveDepth_})
            if (*rb) glDeleteRenderbuffers(1, rb), *rb = 0;
    }

    Program flat_, gouraud_, phong_, solid_, lines_, discs_;
    std::map<int, Buffers> buffers_;
    int nextId_ = 1;
    GLint maxSamples_ = 0;
    std::string name_;
    int width_ = 0, height_ = 0, samples_ = 0;
    GLuint msFbo_ = 0, msColor_ = 0, msDepth_ = 0;
    GLuint resolveFbo_ = 0, resolveColor_ = 0, resolveDepth_ = 0;
    FrameInfo frame_;
    EyeLights lights_;
    bool orthographic_ = false;
};

} // namespace

std::unique_ptr<Renderer> createGlRenderer()
{
    return std::make_unique<GlRenderer>();
}

} // namespace freeform::editor
