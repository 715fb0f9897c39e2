#include "scene/settings.h"

#include <cmath>
#include <set>

#include "freeform/core/error.h"
#include "freeform/io/json_check.h"
#include "scene/json_read.h"

namespace freeform::editor {

namespace {

// Text to tree through the library's one JSON gate (docs/mesh-io.md, "Hostile input"): nesting
// deeper than kMaxJsonDepth or a repeated key is refused before nlohmann builds (recursively) a tree.
Json parseGated(const std::string& text, const std::string& source)
{
    checkJsonText(text, source);
    try {
        return Json::parse(text);
    } catch (const Json::exception& e) {
        throw Error(source + ": not valid JSON: " + e.what());
    }
}

void onlyKnown(const Json& j, const std::string& path, std::initializer_list<const char*> known)
{
    const std::set<std::string> names(known.begin(), known.end());
    for (const auto& [key, value] : j.items())
        if (!names.count(key)) json::fail(path + "." + key, "unknown field");
}

} // namespace

const char* toString(JointMode mode)
{
    switch (mode) {
    case JointMode::Free: return "free";
    case JointMode::Aligned: return "aligned";
    case JointMode::Mirrored: return "mirrored";
    case JointMode::C2: return "c2";
    }
    return "free";
}

Json materialToJson(const Material& m)
{
    Json j;
    j["ambient"] = json::array(m.ambient);
    j["diffuse"] = json::array(m.diffuse);
    j["specular"] = json::array(m.specular);
    j["shininess"] = json::tidy(m.shininess);
    return j;
}

Material materialFromJson(const Json& j, const std::string& path)
{
    json::requireObject(j, path);
    onlyKnown(j, path, {"ambient", "diffuse", "specular", "shininess"});
    Material m;
    json::readVector(j, "ambient", path, m.ambient);
    json::readVector(j, "diffuse", path, m.diffuse);
    json::readVector(j, "specular", path, m.specular);
    json::read(j, "shininess", path, m.shininess);
    if (!(m.shininess >= 0.0f)) json::fail(path + ".shininess", "must not be negative");
    return m;
}

Json DisplaySettings::toJson() const
{
    Json j;
    j["shading"] = shading == Shading::Flat ? "flat" : shading == Shading::Gouraud ? "gouraud" : "phong";
    j["lighting"] = specular == SpecularModel::Phong ? "phong" : "blinn";
    j["material"] = materialToJson(material);
    j["back_color"] = json::array(backColor);
    j["wireframe"] = wireframe;
    j["flip_normals"] = flipNormals;
    j["analysis"] = analysis == SurfaceAnalysis::None ? "none" : analysis == SurfaceAnalysis::ReflectionLines ? "reflection_lines" : "scalar_map";
    j["stripes"] = json::tidy(stripes);
    j["control_nets"] = controlNets;
    j["control_points"] = controlPoints;
    j["normals"] = normals;
    j["normal_length"] = json::tidy(normalLength);
    j["grid"] = grid;
    j["axes"] = axes;
    j["point_size"] = json::tidy(pointSize);
    j["headlight"] = headlight;
    j["headlight_color"] = json::array(headlightColor);
    Json lightArray = Json::array();
    for (const PointLight& l : lights) {
        Json lj;
        lj["position"] = json::array(l.position);
        lj["color"] = json::array(l.color);
        lj["enabled"] = l.enabled;
        lightArray.push_back(std::move(lj));
    }
    j["lights"] = std::move(lightArray);
    j["background"] = json::array(background);
    j["samples"] = samples;
    j["antialiasing"] = antialiasing == Antialiasing::Auto ? "auto" : "always";
    j["tolerance"] = tolerance;
    if (scalarAuto) j["scalar_range"] = "auto";
    else j["scalar_range"] = {json::tidy(scalarMin), json::tidy(scalarMax)};
    return j;
}

DisplaySettings DisplaySettings::fromJson(const Json& j)
{
    const std::string path = "editor.display";
    json::requireObject(j, path);
    onlyKnown(j, path, {"shading", "lighting", "material", "back_color", "wireframe", "flip_normals", "analysis", "stripes",
                        "control_nets", "control_points", "normals", "normal_length", "grid", "axes", "point_size",
                        "headlight", "headlight_color", "lights", "background", "samples", "antialiasing", "tolerance", "scalar_range"});
    DisplaySettings s;
    s.shading = static_cast<Shading>(json::choice(j, "shading", path, {"flat", "gouraud", "phong"}, static_cast<int>(s.shading)));
    s.specular = static_cast<SpecularModel>(json::choice(j, "lighting", path, {"phong", "blinn"}, static_cast<int>(s.specular)));
    if (j.contains("material")) s.material = materialFromJson(j["material"], path + ".material");
    json::readVector(j, "back_color", path, s.backColor);
    json::read(j, "wireframe", path, s.wireframe);
    json::read(j, "flip_normals", path, s.flipNormals);
    s.analysis = static_cast<SurfaceAnalysis>(
        json::choice(j, "analysis", path, {"none", "reflection_lines", "scalar_map"}, static_cast<int>(s.analysis)));
    json::read(j, "stripes", path, s.stripes);
    json::read(j, "control_nets", path, s.controlNets);
    json::read(j, "control_points", path, s.controlPoints);
    json::read(j, "normals", path, s.normals);
    json::read(j, "normal_length", path, s.normalLength);
    json::read(j, "grid", path, s.grid);
    json::read(j, "axes", path, s.axes);
    json::read(j, "point_size", path, s.pointSize);
    json::read(j, "headlight", path, s.headlight);
    json::readVector(j, "headlight_color", path, s.headlightColor);
    if (j.contains("lights")) {
        const Json& a = j["lights"];
        if (!a.is_array()) json::fail(path + ".lights", "expected an array");
        if (a.size() > static_cast<std::size_t>(kMaxLights - 1))
            json::fail(path + ".lights", "at most " + std::to_string(kMaxLights - 1) + " lights (the headlight is one more)");
        s.lights.clear();
        for (std::size_t i = 0; i < a.size(); ++i) {
            const std::string lp = path + ".lights[" + std::to_string(i) + "]";
            json::requireObject(a[i], lp);
            onlyKnown(a[i], lp, {"position", "color", "enabled"});
            PointLight l;
            json::readVector(a[i], "position", lp, l.position);
            json::readVector(a[i], "color", lp, l.color);
            json::read(a[i], "enabled", lp, l.enabled);
            s.lights.push_back(l);
        }
    }
    json::readVector(j, "background", path, s.background);
    json::read(j, "samples", path, s.samples);
    if (s.samples < 0 || s.samples > 16) json::fail(path + ".samples", "must lie in 0..16");
    s.antialiasing = static_cast<Antialiasing>(json::choice(j, "antialiasing", path, {"auto", "always"}, static_cast<int>(s.antialiasing)));
    json::read(j, "tolerance", path, s.tolerance);
    if (!(s.tolerance > 0)) json::fail(path + ".tolerance", "must be positive");
    if (!(s.stripes > 0)) json::fail(path + ".stripes", "must be positive");
    if (j.contains("scalar_range")) {
        const Json& r = j["scalar_range"];
        if (r.is_string()) {
            if (r.get<std::string>() != "auto") json::fail(path + ".scalar_range", "expected \"auto\" or [min, max]");
            s.scalarAuto = true;
        } else {
            Eigen::Vector2f range;
            json::readVector(j, "scalar_range", path, range);
            if (!std::isfinite(range[0]) || !std::isfinite(range[1]) || !(range[0] < range[1]))
                json::fail(path + ".scalar_range", "expected finite [min, max] with min < max");
            s.scalarAuto = false;
            s.scalarMin = range[0];
            s.scalarMax = range[1];
        }
    }
    return s;
}

int effectiveSamples(const DisplaySettings& display, bool softwareRenderer, bool stillImage)
{
    if (display.antialiasing == Antialiasing::Auto && softwareRenderer && !stillImage) return 0;
    return display.samples;
}

Json ObjectSettings::toJson() const
{
    Json j = Json::object();
    if (!visible) j["visible"] = false;
    if (ownMaterial) j["material"] = materialToJson(material);
    if (!(tessellation == Tessellation{})) {
        Json t;
        t["mode"] = tessellation.mode == Tessellation::Mode::Adaptive ? "adaptive" : "uniform";
        if (tessellation.tolerance > 0) t["tolerance"] = tessellation.tolerance;
        t["segments"] = tessellation.segments;
        if (tessellation.flip) t["flip"] = true;
        j["tessellation"] = std::move(t);
    }
    if (!joints.empty()) {
        Json a = Json::array();
        for (JointMode m : joints) a.push_back(toString(m));
        j["joints"] = std::move(a);
    }
    if (!(ffd == FfdSettings{})) {
        Json f;
        f["mesh"] = ffd.mesh;
        f["strength"] = ffd.strength;
        j["ffd"] = std::move(f);
    }
    return j;
}

ObjectSettings ObjectSettings::fromJson(const Json& j, const std::string& path)
{
    json::requireObject(j, path);
    onlyKnown(j, path, {"visible", "material", "tessellation", "joints", "ffd"});
    ObjectSettings s;
    json::read(j, "visible", path, s.visible);
    if (j.contains("material")) {
        s.ownMaterial = true;
        s.material = materialFromJson(j["material"], path + ".material");
    }
    if (j.contains("tessellation")) {
        const std::string tp = path + ".tessellation";
        const Json& t = j["tessellation"];
        json::requireObject(t, tp);
        onlyKnown(t, tp, {"mode", "tolerance", "segments", "flip"});
        s.tessellation.mode = json::choice(t, "mode", tp, {"adaptive", "uniform"}, 0) == 0 ? Tessellation::Mode::Adaptive
                                                                                          : Tessellation::Mode::Uniform;
        json::read(t, "tolerance", tp, s.tessellation.tolerance);
        json::read(t, "segments", tp, s.tessellation.segments);
        json::read(t, "flip", tp, s.tessellation.flip);
        if (s.tessellation.tolerance < 0) json::fail(tp + ".tolerance", "must not be negative");
        if (s.tessellation.segments < 1 || s.tessellation.segments > 1000) json::fail(tp + ".segments", "must lie in 1..1000");
    }
    if (j.contains("joints")) {
        const Json& a = j["joints"];
        const std::string jp = path + ".joints";
        if (!a.is_array()) json::fail(jp, "expected an array");
        for (std::size_t i = 0; i < a.size(); ++i) {
            const std::string ip = jp + "[" + std::to_string(i) + "]";
            if (!a[i].is_string()) json::fail(ip, "expected a string");
            const std::string v = a[i].get<std::string>();
            int m = 0;
            while (m < 4 && v != toString(static_cast<JointMode>(m))) ++m;
            if (m == 4) json::fail(ip, "\"" + v + "\" is not one of free, aligned, mirrored, c2");
            s.joints.push_back(static_cast<JointMode>(m));
        }
    }
    if (j.contains("ffd")) {
        const std::string fp = path + ".ffd";
        const Json& f = j["ffd"];
        json::requireObject(f, fp);
        onlyKnown(f, fp, {"mesh", "strength"});
        if (f.contains("mesh")) {
            if (!f["mesh"].is_string()) json::fail(fp + ".mesh", "expected a string");
            s.ffd.mesh = f["mesh"].get<std::string>();
        }
        json::read(f, "strength", fp, s.ffd.strength);
        if (!std::isfinite(s.ffd.strength)) json::fail(fp + ".strength", "must be finite");
    }
    return s;
}

DisplaySettings DisplaySettings::fromText(const std::string& text, const std::string& source)
{
    const Json j = parseGated(text, source);
    try {
        return fromJson(j);
    } catch (const Error& e) {
        throw Error(source + ": " + e.what());
    }
}

ObjectSettings ObjectSettings::fromText(const std::string& text, const std::string& path)
{
    return fromJson(parseGated(text, path), path);
}

} // namespace freeform::editor
