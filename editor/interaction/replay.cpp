#include "interaction/replay.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <set>

#include "freeform/core/error.h"
#include "freeform/io/file.h"
#include "freeform/io/json_check.h"
#include "interaction/picking.h"
#include "scene/scene.h"

namespace freeform::editor {

namespace {

using Json = nlohmann::ordered_json;

[[noreturn]] void fail(const std::string& where, const std::string& what)
{
    std::string message = where;
    message += ": ";
    message += what;
    throw Error(message);
}

double number(const Json& e, const char* field, const std::string& where)
{
    if (!e.contains(field)) fail(where, std::string("missing \"") + field + "\"");
    const Json& v = e[field];
    if (!v.is_number() || !std::isfinite(v.get<double>())) fail(where + "." + field, "expected a finite number");
    return v.get<double>();
}

std::string string(const Json& e, const char* field, const std::string& where)
{
    if (!e.contains(field)) fail(where, std::string("missing \"") + field + "\"");
    if (!e[field].is_string()) fail(where + "." + field, "expected a string");
    return e[field].get<std::string>();
}

int mods(const Json& e, const std::string& where)
{
    if (!e.contains("mods")) return 0;
    const Json& m = e["mods"];
    if (!m.is_array()) fail(where + ".mods", "expected an array of \"shift\", \"ctrl\", \"alt\", \"super\"");
    int bits = 0;
    for (const Json& v : m) {
        const std::string s = v.is_string() ? v.get<std::string>() : std::string();
        if (s == "shift") bits |= GLFW_MOD_SHIFT;
        else if (s == "ctrl") bits |= GLFW_MOD_CONTROL;
        else if (s == "alt") bits |= GLFW_MOD_ALT;
        else if (s == "super") bits |= GLFW_MOD_SUPER;
        else {
            std::string message = "unknown modifier ";
            message += v.dump();
            message += " (shift, ctrl, alt, super)";
            fail(where + ".mods", message);
        }
    }
    return bits;
}

void onlyFields(const Json& e, const std::string& where, const std::set<std::string>& allowed)
{
    for (const auto& [key, value] : e.items())
        if (!allowed.count(key)) fail(where + "." + key, "unknown field for this event type");
}

} // namespace

int keyCode(const std::string& name)
{
    if (name.size() == 1 && name[0] >= 'A' && name[0] <= 'Z') return GLFW_KEY_A + (name[0] - 'A');
    if (name.size() == 1 && name[0] >= 'a' && name[0] <= 'z') return GLFW_KEY_A + (name[0] - 'a');
    if (name.size() == 1 && name[0] >= '0' && name[0] <= '9') return GLFW_KEY_0 + (name[0] - '0');
    if (name.size() >= 2 && name.size() <= 3 && name[0] == 'F') {
        int n = 0;
        for (std::size_t i = 1; i < name.size(); ++i) {
            if (name[i] < '0' || name[i] > '9') return -1;
            n = 10 * n + (name[i] - '0');
        }
        return n >= 1 && n <= 12 ? GLFW_KEY_F1 + (n - 1) : -1;
    }
    static const std::pair<const char*, int> named[] = {
        {"Enter", GLFW_KEY_ENTER},   {"Escape", GLFW_KEY_ESCAPE}, {"Delete", GLFW_KEY_DELETE}, {"Backspace", GLFW_KEY_BACKSPACE},
        {"Tab", GLFW_KEY_TAB},       {"Space", GLFW_KEY_SPACE},   {"Left", GLFW_KEY_LEFT},     {"Right", GLFW_KEY_RIGHT},
        {"Up", GLFW_KEY_UP},         {"Down", GLFW_KEY_DOWN},     {"Plus", GLFW_KEY_KP_ADD},   {"Minus", GLFW_KEY_MINUS},
        {"Home", GLFW_KEY_HOME},     {"End", GLFW_KEY_END}};
    for (const auto& [n, code] : named)
        if (name == n) return code;
    return -1;
}

std::vector<ReplayEvent> parseReplay(const std::string& text, const std::string& source)
{
    // Depth limit and duplicate keys first (docs/mesh-io.md, "Hostile input"): nlohmann's tree
    // recurses on depth, and a repeated key must not silently win.
    checkJsonText(text, source);
    Json root;
    try {
        root = Json::parse(text);
    } catch (const Json::exception& e) {
        fail(source, std::string("not valid JSON: ") + e.what());
    }
    if (!root.is_object() || !root.contains("events") || !root["events"].is_array())
        fail(source, "expected an object {\"events\": [...]}");
    for (const auto& [key, value] : root.items())
        if (key != "events") fail(source + "." + key, "unknown field");
    std::vector<ReplayEvent> events;
    const Json& list = root["events"];
    for (std::size_t i = 0; i < list.size(); ++i) {
        const std::string where = source + ": events[" + std::to_string(i) + "]";
        const Json& e = list[i];
        if (!e.is_object()) fail(where, "expected an object");
        const std::string type = string(e, "type", where);
        ReplayEvent ev;
        auto position = [&] {
            ev.x = number(e, "x", where);
            ev.y = number(e, "y", where);
            ev.hasPosition = true;
        };
        auto button = [&] {
            const std::string b = string(e, "button", where);
            if (b == "left") ev.button = GLFW_MOUSE_BUTTON_LEFT;
            else if (b == "right") ev.button = GLFW_MOUSE_BUTTON_RIGHT;
            else if (b == "middle") ev.button = GLFW_MOUSE_BUTTON_MIDDLE;
            else fail(where + ".button", "unknown button \"" + b + "\" (left, right, middle)");
        };
        auto key = [&] {
            const std::string k = string(e, "key", where);
            ev.key = keyCode(k);
            if (ev.key < 0) fail(where + ".key", "unknown key \"" + k + "\"");
        };
        if (type == "move") {
            onlyFields(e, where, {"type", "x", "y", "mods"});
            ev.type = ReplayEvent::Type::Move;
            position();
        } else if (type == "press" || type == "release") {
            onlyFields(e, where, {"type", "button", "x", "y", "mods"});
            ev.type = type == "press" ? ReplayEvent::Type::Press : ReplayEvent::Type::Release;
            button();
            position();
        } else if (type == "key" || type == "key_press" || type == "key_release") {
            onlyFields(e, where, {"type", "key", "mods"});
            ev.type = type == "key" ? ReplayEvent::Type::Key : type == "key_press" ? ReplayEvent::Type::KeyPress : ReplayEvent::Type::KeyRelease;
            key();
        } else if (type == "text") {
            onlyFields(e, where, {"type", "text"});
            ev.type = ReplayEvent::Type::Text;
            ev.text = string(e, "text", where);
        } else if (type == "scroll") {
            onlyFields(e, where, {"type", "dy", "x", "y", "mods"});
            ev.type = ReplayEvent::Type::Scroll;
            ev.dy = number(e, "dy", where);
            if (e.contains("x") || e.contains("y")) position();
        } else if (type == "frame") {
            onlyFields(e, where, {"type", "count"});
            ev.type = ReplayEvent::Type::Frame;
            if (e.contains("count")) {
                const Json& c = e["count"];
                if (!c.is_number_integer() || c.get<long long>() < 1 || c.get<long long>() > 100000)
                    fail(where + ".count", "expected an integer in 1..100000");
                ev.count = c.get<int>();
            }
        } else if (type == "open") {
            onlyFields(e, where, {"type", "path"});
            ev.type = ReplayEvent::Type::Open;
            ev.text = string(e, "path", where);
        } else if (type == "drop") {
            onlyFields(e, where, {"type", "paths"});
            ev.type = ReplayEvent::Type::Drop;
            if (!e.contains("paths")) fail(where, "missing \"paths\"");
            const Json& list = e["paths"];
            if (!list.is_array() || list.empty()) fail(where + ".paths", "expected a non-empty array of paths");
            for (const Json& path : list) {
                if (!path.is_string()) fail(where + ".paths", "expected a non-empty array of paths");
                ev.paths.push_back(path.get<std::string>());
            }
        } else if (type == "resize") {
            onlyFields(e, where, {"type", "width", "height"});
            ev.type = ReplayEvent::Type::Resize;
            for (const char* field : {"width", "height"}) {
                if (!e.contains(field) || !e[field].is_number_integer() || e[field].get<long long>() < 16 || e[field].get<long long>() > 8192)
                    fail(where + "." + field, "expected an integer in 16..8192");
            }
            ev.width = e["width"].get<int>();
            ev.height = e["height"].get<int>();
        } else if (type == "tooltip_audit") {
            onlyFields(e, where, {"type", "step", "windows"});
            ev.type = ReplayEvent::Type::TooltipAudit;
            if (e.contains("windows")) {
                const Json& w = e["windows"];
                if (!w.is_array() || w.empty()) fail(where + ".windows", "expected a non-empty array of window names");
                for (const Json& name : w) {
                    if (!name.is_string()) fail(where + ".windows", "expected a non-empty array of window names");
                    ev.windows.push_back(name.get<std::string>());
                }
            }
            if (e.contains("step")) {
                ev.step = number(e, "step", where);
                if (!(ev.step >= 1 && ev.step <= 100)) fail(where + ".step", "expected a number of pixels in 1..100");
            }
        } else {
            fail(where + ".type", "unknown event type \"" + type + "\" (move, press, release, key, key_press, key_release, text, scroll, frame, open, drop, resize, tooltip_audit)");
        }
        ev.mods = mods(e, where);
        events.push_back(std::move(ev));
    }
    return events;
}

std::vector<ReplayEvent> readReplay(const std::string& path)
{
    return parseReplay(readFile(path), path);
}

Eigen::Vector2d worldToPixel(const Scene& scene, int width, int height, const Eigen::Vector3d& p)
{
    const ViewTransform view = ViewTransform::of(scene, width, height);
    const auto q = view.toPixel(p);
    if (!q) throw Error("worldToPixel: the point lies behind the camera");
    return q->head<2>();
}

} // namespace freeform::editor
