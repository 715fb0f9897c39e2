#pragma once
// Display settings of the whole view and per-object settings, with their JSON form (the "display"
// member of the document's "editor" object and each object's own "editor" member; docs/format.md).
// Plain data: the UI edits them, the scene draws with them, the document saves them.

#include <string>
#include <vector>

#include "render/render_types.h"
#include "scene/camera.h"

namespace freeform::editor {

/// When multisampling is used (docs/editor.md, "Anti-aliasing"): Auto uses `samples` on a hardware
/// renderer and in still images (screenshots), and none for the frames of a software rasteriser
/// (Mesa's llvmpipe, softpipe), where 4x multisampling costs about 4x the frame time; Always uses
/// `samples` everywhere.
enum class Antialiasing { Auto, Always };

struct DisplaySettings {
    Shading shading = Shading::Phong;
    SpecularModel specular = SpecularModel::Phong;
    Material material;                 // surfaces without a material of their own
    Vec3f backColor{0.35f, 0.45f, 0.75f};
    bool wireframe = false;
    bool flipNormals = false;
    SurfaceAnalysis analysis = SurfaceAnalysis::None;
    float stripes = 12.0f;
    bool controlNets = false;          // of every object (the selected one always shows its own)
    bool controlPoints = false;
    bool normals = false;
    float normalLength = 0.03f;        // fraction of the scene's diameter
    bool grid = true;
    bool axes = true;
    float pointSize = 7.0f;            // control point discs, pixels
    bool headlight = true;
    Vec3f headlightColor{0.55f, 0.55f, 0.55f};
    std::vector<PointLight> lights{{Vec3f(6, -8, 10), Vec3f(0.45f, 0.45f, 0.45f), true},
                                   {Vec3f(-8, 4, 3), Vec3f(0.2f, 0.2f, 0.25f), true}};
    Vec3f background{0.19f, 0.2f, 0.22f};
    int samples = 4;                   // multisampling (0: off)
    Antialiasing antialiasing = Antialiasing::Auto; // where `samples` applies
    double tolerance = 1e-3;           // adaptive tessellation of surfaces and curves (world units)
    // The scalar colour map's range (det J of a lattice; docs/editor.md, "Lattices and FFD"): fixed
    // by default, so that colours do not rescale while a lattice point is dragged (det J = 1, the
    // volume kept, in the middle); `scalarAuto` takes the range of the scalars drawn in each frame.
    bool scalarAuto = false;
    float scalarMin = 0.0f, scalarMax = 2.0f;

    Json toJson() const;
    static DisplaySettings fromJson(const Json& json);
    /// The same from JSON text, through checkJsonText first (depth limit, duplicate keys; see
    /// docs/mesh-io.md, "Hostile input"); errors name source.
    static DisplaySettings fromText(const std::string& text, const std::string& source);
    bool operator==(const DisplaySettings&) const = default;
};

/// The multisample count to render with: display.samples, or 0 under Antialiasing::Auto for the
/// frames (not the still images) of a software renderer.
int effectiveSamples(const DisplaySettings& display, bool softwareRenderer, bool stillImage);

/// How a surface object is turned into triangles.
struct Tessellation {
    enum class Mode { Adaptive, Uniform } mode = Mode::Adaptive;
    double tolerance = 0;              // 0: the display setting
    int segments = 8;                  // per patch side, uniform mode
    bool flip = false;                 // reverse the orientation (triangles and normals)
    bool operator==(const Tessellation&) const = default;
};

/// Handle mode of a spline joint (docs/editor.md, "Curves and splines"): what the editor keeps
/// when a handle next to the joint moves. Free: nothing (C0); Aligned: the handles and the joint on
/// one line (G1); Mirrored: C1 (the opposite handle mirrored, scaled by the interval ratio);
/// C2: the A-frame condition of cubics (C2).
enum class JointMode { Free, Aligned, Mirrored, C2 };
const char* toString(JointMode mode);

/// A lattice's binding to an imported mesh it deforms (the lattice object's editor member "ffd").
struct FfdSettings {
    std::string mesh;                  // name of the imported mesh item; empty: none
    double strength = 1;               // w of volume/deform.h
    bool operator==(const FfdSettings&) const = default;
};

struct ObjectSettings {
    bool visible = true;
    bool ownMaterial = false;          // use `material` rather than the display default
    Material material;
    Tessellation tessellation;
    std::vector<JointMode> joints;     // bezier_spline: one mode per joint (empty: all free)
    FfdSettings ffd;                   // lattice: the mesh it deforms

    bool isDefault() const { return *this == ObjectSettings{}; }
    Json toJson() const;
    /// path names the object in messages ("object \"spout\".editor").
    static ObjectSettings fromJson(const Json& json, const std::string& path);
    /// The same from JSON text, through checkJsonText first; errors name path.
    static ObjectSettings fromText(const std::string& text, const std::string& path);
    bool operator==(const ObjectSettings&) const = default;
};

Json materialToJson(const Material& m);
Material materialFromJson(const Json& json, const std::string& path);

} // namespace freeform::editor
