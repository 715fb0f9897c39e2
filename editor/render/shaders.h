#pragma once
// GLSL 330 core shaders of the OpenGL backend, as raw strings. Each program is listed with its
// uniforms. The mesh programs share one source compiled three times with a define in front
// (FLAT, GOURAUD or PHONG); docs/math.md ("Lighting and shading") gives the formulas, docs/editor.md the choices.
//
// Eye space throughout: the camera at the origin looking down -z, lights given in eye space.

namespace freeform::editor::shaders {

// ------------------------------------------------------------------------------------------------
// Lighting, shared by every mesh program.
//   uniform int   uLightCount;                 // lights in use (<= 8), the headlight included
//   uniform vec3  uLightPosition[8];           // eye space
//   uniform vec3  uLightColor[8];              // c_y
//   uniform vec3  uAmbient, uSpecular;         // C_a, C_s (C_d is an argument: material or colour map)
//   uniform float uShininess;                  // s
//   uniform int   uBlinn;                      // 1: Blinn-Phong n.h, 0: Phong v.r
//   uniform int   uOrthographic;               // 1: view vector (0,0,1) everywhere
//   uniform int   uAnalysis;                   // 0 none, 1 reflection lines, 2 scalar map
//   uniform vec3  uDiffuse, uBackDiffuse;      // C_d of front and back faces
//   uniform float uScalarMin, uScalarMax;      // colour map range
inline constexpr const char* kLighting = R"GLSL(
uniform int uLightCount;
uniform vec3 uLightPosition[8];
uniform vec3 uLightColor[8];
uniform vec3 uAmbient;
uniform vec3 uSpecular;
uniform float uShininess;
uniform int uBlinn;
uniform int uOrthographic;
uniform int uAnalysis;
uniform vec3 uDiffuse;
uniform vec3 uBackDiffuse;
uniform float uScalarMin;
uniform float uScalarMax;

vec3 viewVector(vec3 x) { return uOrthographic == 1 ? vec3(0.0, 0.0, 1.0) : normalize(-x); }

// L(x, v) = sum_y (C_a + C_d max(0, l.n) + C_s max(0, v.r)^s) c_y, r = 2 n n^T l - l
// (Blinn-Phong: n.h, h = (v + l)/|v + l|). n must be unit length.
vec3 lighting(vec3 x, vec3 n, vec3 diffuse) {
    vec3 v = viewVector(x);
    vec3 sum = vec3(0.0);
    for (int i = 0; i < uLightCount; ++i) {
        vec3 l = normalize(uLightPosition[i] - x);
        float s;
        if (uBlinn == 1) s = max(0.0, dot(n, normalize(v + l)));
        else s = max(0.0, dot(v, 2.0 * dot(n, l) * n - l));
        sum += (uAmbient + diffuse * max(0.0, dot(l, n)) + uSpecular * pow(s, uShininess)) * uLightColor[i];
    }
    return sum;
}

// A perceptually ordered colour map (dark blue - teal - green - yellow) of t in [0, 1]; the stops
// are those of render/colour_map.h (colourMapStops), which the legend draws.
vec3 colorMap(float value) {
    float t = clamp((value - uScalarMin) / max(uScalarMax - uScalarMin, 1e-30), 0.0, 1.0);
    const vec3 c0 = vec3(0.267, 0.005, 0.329);
    const vec3 c1 = vec3(0.231, 0.322, 0.545);
    const vec3 c2 = vec3(0.129, 0.569, 0.549);
    const vec3 c3 = vec3(0.369, 0.788, 0.384);
    const vec3 c4 = vec3(0.993, 0.906, 0.144);
    if (t < 0.25) return mix(c0, c1, t * 4.0);
    if (t < 0.5) return mix(c1, c2, t * 4.0 - 1.0);
    if (t < 0.75) return mix(c2, c3, t * 4.0 - 2.0);
    return mix(c3, c4, t * 4.0 - 3.0);
}

vec3 frontDiffuse(float scalar) { return uAnalysis == 2 ? colorMap(scalar) : uDiffuse; }
)GLSL";

// ------------------------------------------------------------------------------------------------
// Mesh vertex shader.
//   uniform mat4 uModelView, uProjection;
//   uniform mat3 uNormalMatrix;   // inverse transpose of uModelView's linear part
//   uniform float uNormalSign;    // -1 draws with flipped normals
// GOURAUD: lights both sides of each vertex here (vFront, vBack), the fragment shader interpolates.
inline constexpr const char* kMeshVertex = R"GLSL(
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in float aScalar;
uniform mat4 uModelView;
uniform mat4 uProjection;
uniform mat3 uNormalMatrix;
uniform float uNormalSign;
out vec3 vPosition;
out vec3 vNormal;
out float vScalar;
#ifdef GOURAUD
out vec3 vFront;
out vec3 vBack;
#endif
void main() {
    vec4 x = uModelView * vec4(aPosition, 1.0);
    vPosition = x.xyz;
    vNormal = uNormalSign * (uNormalMatrix * aNormal);
    vScalar = aScalar;
#ifdef GOURAUD
    vec3 n = normalize(vNormal);
    vFront = lighting(vPosition, n, frontDiffuse(aScalar));
    vBack = lighting(vPosition, -n, uBackDiffuse);
#endif
    gl_Position = uProjection * x;
}
)GLSL";

// FLAT: a geometry shader lights each triangle once, at its centroid with its face normal
// ((b - a) x (c - a), oriented like the mean of its vertex normals), and passes one colour per side
// with the `flat` qualifier.
inline constexpr const char* kMeshGeometryFlat = R"GLSL(
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
in vec3 vPosition[];
in vec3 vNormal[];
in float vScalar[];
flat out vec3 gFront;
flat out vec3 gBack;
void main() {
    vec3 a = vPosition[0], b = vPosition[1], c = vPosition[2];
    vec3 face = cross(b - a, c - a);
    float len = length(face);
    vec3 n = len > 0.0 ? face / len : normalize(vNormal[0] + vNormal[1] + vNormal[2] + vec3(0.0, 0.0, 1e-30));
    if (dot(n, vNormal[0] + vNormal[1] + vNormal[2]) < 0.0) n = -n;
    vec3 center = (a + b + c) / 3.0;
    float scalar = (vScalar[0] + vScalar[1] + vScalar[2]) / 3.0;
    vec3 front = lighting(center, n, frontDiffuse(scalar));
    vec3 back = lighting(center, -n, uBackDiffuse);
    for (int i = 0; i < 3; ++i) {
        gFront = front;
        gBack = back;
        gl_Position = gl_in[i].gl_Position;
        EmitVertex();
    }
    EndPrimitive();
}
)GLSL";

// Mesh fragment shader.
//   uniform float uStripes;       // reflection lines: stripes across the sphere map
// PHONG: interpolated normal renormalised, lit per fragment; reflection lines from the reflected
// view vector r_e through the sphere map: coordinate = xy of (r_e + z)/|r_e + z|.
inline constexpr const char* kMeshFragment = R"GLSL(
uniform float uStripes;
#ifdef FLAT
flat in vec3 gFront;
flat in vec3 gBack;
#else
in vec3 vPosition;
in vec3 vNormal;
in float vScalar;
#endif
#ifdef GOURAUD
in vec3 vFront;
in vec3 vBack;
#endif
out vec4 fragColor;
void main() {
#if defined(FLAT)
    vec3 color = gl_FrontFacing ? gFront : gBack;
#elif defined(GOURAUD)
    vec3 color = gl_FrontFacing ? vFront : vBack;
#else
    vec3 n = normalize(vNormal);
    if (!gl_FrontFacing) n = -n;
    vec3 color;
    if (uAnalysis == 1) {
        vec3 v = viewVector(vPosition);
        vec3 r = reflect(-v, n);
        vec3 m = r + vec3(0.0, 0.0, 1.0);
        float len = length(m);
        vec2 st = len > 1e-6 ? m.xy / len : vec2(1.0, 0.0);
        float phase = st.x * uStripes;
        float w = max(fwidth(phase), 1e-4) * 2.0;
        float wave = abs(fract(phase) - 0.5) * 2.0; // triangle wave, 0..1
        float stripe = smoothstep(0.5 - w, 0.5 + w, wave);
        vec3 base = gl_FrontFacing ? vec3(0.95) : uBackDiffuse;
        color = mix(base, vec3(0.05), stripe);
    } else {
        color = lighting(vPosition, n, gl_FrontFacing ? frontDiffuse(vScalar) : uBackDiffuse);
    }
#endif
    fragColor = vec4(clamp(color, 0.0, 1.0), 1.0);
}
)GLSL";

// ------------------------------------------------------------------------------------------------
// One colour for everything (wireframe overlay).
//   uniform mat4 uMVP; uniform vec3 uColor;
inline constexpr const char* kSolidVertex = R"GLSL(
layout(location = 0) in vec3 aPosition;
uniform mat4 uMVP;
void main() { gl_Position = uMVP * vec4(aPosition, 1.0); }
)GLSL";
inline constexpr const char* kSolidFragment = R"GLSL(
uniform vec3 uColor;
out vec4 fragColor;
void main() { fragColor = vec4(uColor, 1.0); }
)GLSL";

// Per-vertex coloured lines and points.
//   uniform mat4 uMVP; uniform float uPointSize (pixels; points only)
inline constexpr const char* kColorVertex = R"GLSL(
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aColor;
uniform mat4 uMVP;
uniform float uPointSize;
out vec3 vColor;
void main() {
    vColor = aColor;
    gl_Position = uMVP * vec4(aPosition, 1.0);
    gl_PointSize = uPointSize;
}
)GLSL";
inline constexpr const char* kLineFragment = R"GLSL(
in vec3 vColor;
out vec4 fragColor;
void main() { fragColor = vec4(vColor, 1.0); }
)GLSL";
// A disc with a dark rim, cut out of the point sprite: the same size in pixels at any distance.
inline constexpr const char* kDiscFragment = R"GLSL(
in vec3 vColor;
out vec4 fragColor;
void main() {
    float r = length(gl_PointCoord - vec2(0.5)) * 2.0;
    if (r > 1.0) discard;
    fragColor = vec4(r > 0.7 ? vColor * 0.3 : vColor, 1.0);
}
)GLSL";

} // namespace freeform::editor::shaders
