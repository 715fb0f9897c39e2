// The editor's own JSON readers (replay files, display and object settings) pass the library's
// one JSON gate (freeform/io/json_check.h; docs/mesh-io.md, "Hostile input") before nlohmann
// builds a tree: a text nested 100,000 deep is refused with an error naming the source (no stack
// overflow: the tree's construction and destruction would recurse 100,000 deep), and an object
// that repeats a key (also written with an escape) is refused rather than letting the last win.

#include <catch2/catch.hpp>

#include <freeform/core/error.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "interaction/replay.h"
#include "scene/scene.h"
#include "scene/settings.h"

namespace test_json_gate {

using namespace freeform;
using namespace freeform::editor;

namespace {

// {"events": [[[[ ... ]]]]} nested `depth` arrays deep inside the events member.
std::string deepEvents(int depth)
{
    return "{\"events\": " + std::string(static_cast<std::size_t>(depth), '[') + std::string(static_cast<std::size_t>(depth), ']') + "}";
}

// {"a":{"a":{ ... }}} nested `depth` objects deep.
std::string deepObject(int depth)
{
    std::string s;
    for (int i = 0; i < depth; ++i) s += "{\"a\":";
    s += "1";
    s += std::string(static_cast<std::size_t>(depth), '}');
    return s;
}

template <class F>
std::string message(F&& f)
{
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

} // namespace

TEST_CASE("parseReplay refuses a file nested 100,000 deep and a repeated key, naming the file", "[replay][hardening]")
{
    const std::string deep = message([&] { parseReplay(deepEvents(100000), "deep.json"); });
    INFO(deep);
    CHECK(has(deep, "deep.json"));
    CHECK(has(deep, "nested deeper than 256"));

    const std::string twice = message([&] { parseReplay(R"({"events": [{"type": "frame", "count": 1, "count": 2}]})", "twice.json"); });
    INFO(twice);
    CHECK(has(twice, "twice.json"));
    CHECK(has(twice, "\"count\" appears twice"));
    // The same key spelled with an escape ("\u0065vents" is "events") is the same key.
    const std::string escaped = message([&] { parseReplay(R"({"events": [], "\u0065vents": []})", "esc.json"); });
    INFO(escaped);
    CHECK(has(escaped, "\"events\" appears twice"));

    // Below the limit the gate lets the text through to the reader's own checks.
    const std::string shallow = message([&] { parseReplay(deepEvents(200), "shallow.json"); });
    INFO(shallow);
    CHECK(has(shallow, "events[0]"));
    CHECK(parseReplay(R"({"events": [{"type": "frame", "count": 2}]})").size() == 1);
}

TEST_CASE("Settings from text refuse deep nesting and repeated keys, naming the source", "[settings][hardening]")
{
    const std::string deep = message([&] { DisplaySettings::fromText(deepObject(100000), "display.json"); });
    INFO(deep);
    CHECK(has(deep, "display.json"));
    CHECK(has(deep, "nested deeper than 256"));

    const std::string deepObj = message([&] { ObjectSettings::fromText("{\"material\": " + deepObject(100000) + "}", "object \"a\".editor"); });
    INFO(deepObj);
    CHECK(has(deepObj, "object \"a\".editor"));
    CHECK(has(deepObj, "nested deeper than 256"));

    const std::string twice = message([&] { DisplaySettings::fromText(R"({"wireframe": true, "wireframe": false})", "display.json"); });
    INFO(twice);
    CHECK(has(twice, "\"wireframe\" appears twice"));
    const std::string twiceObj = message([&] { ObjectSettings::fromText(R"({"visible": false, "visibl\u0065": true})", "object \"a\".editor"); });
    INFO(twiceObj);
    CHECK(has(twiceObj, "\"visible\" appears twice"));

    // Valid texts still read: the values arrive (defaults are wireframe off, visible on).
    CHECK(DisplaySettings::fromText(R"({"wireframe": true})", "display.json").wireframe);
    CHECK_FALSE(ObjectSettings::fromText(R"({"visible": false})", "object \"a\".editor").visible);
    CHECK(has(message([&] { DisplaySettings::fromText("{\"wireframe\": ", "display.json"); }), "display.json: not valid JSON"));
}

namespace {

// A document of one curve "c" whose editor member is `editor` (JSON text), written to the test's
// temporary folder.
std::string documentWithEditor(const std::string& name, const std::string& objectEditor, const std::string& documentEditor = "")
{
    const std::string path = std::string(FREEFORM_TEST_TMP) + "/" + name;
    std::filesystem::create_directories(FREEFORM_TEST_TMP);
    std::ofstream out(path, std::ios::binary);
    out << R"({"format": "freeform", "version": 1, "objects": [{"name": "c", "type": "bezier_curve", "points": [[0,0],[1,2],[4,0]])";
    if (!objectEditor.empty()) out << ", \"editor\": " << objectEditor;
    out << "}]";
    if (!documentEditor.empty()) out << ", \"editor\": " << documentEditor;
    out << "}\n";
    return path;
}

} // namespace

TEST_CASE("The scene refuses an editor member nested 100,000 deep or repeating a key, naming the object, and keeps its document", "[scene][hardening]")
{
    // The scene the editor holds before it tries to open the bad files (app_files.cpp opens into a
    // new Scene and swaps it in only on success).
    Scene scene = Scene::load(documentWithEditor("gate_good.json", R"({"visible": false})"));
    REQUIRE(scene.itemCount() == 1);
    REQUIRE_FALSE(scene.item(0).settings.visible);
    const std::string before = scene.text();

    const std::string deepPath = documentWithEditor("gate_deep.json", "{\"material\": " + deepObject(100000) + "}");
    const std::string deep = message([&] { scene = Scene::load(deepPath); });
    INFO(deep);
    CHECK(has(deep, "gate_deep.json"));
    CHECK(has(deep, "nested deeper than 256"));
    CHECK(has(deep, "objects[0].editor.material"));

    const std::string twicePath = documentWithEditor("gate_twice.json", R"({"visible": false, "visibl\u0065": true})");
    const std::string twice = message([&] { scene = Scene::load(twicePath); });
    INFO(twice);
    CHECK(has(twice, "gate_twice.json"));
    CHECK(has(twice, "\"visible\" appears twice"));
    CHECK(has(twice, "objects[0].editor"));

    // The document's own editor member (camera, display, meshes) likewise.
    const std::string displayPath = documentWithEditor("gate_display.json", "", R"({"display": {"wireframe": true, "wireframe": false}})");
    const std::string display = message([&] { scene = Scene::load(displayPath); });
    INFO(display);
    CHECK(has(display, "gate_display.json"));
    CHECK(has(display, "\"wireframe\" appears twice"));
    CHECK(has(display, "editor.display"));

    // An object built in memory (a tool, a paste) carries its editor member as text: it passes the
    // same gate, the error names the object, and nothing changes (no object, no undo step).
    const std::size_t steps = scene.history().size();
    DocumentObject o = scene.object(0);
    o.name = "d";
    o.editor = "{\"material\": " + deepObject(100000) + "}";
    const std::string added = message([&] { scene.addObject(o); });
    INFO(added);
    CHECK(has(added, "object \"d\".editor"));
    CHECK(has(added, "nested deeper than 256"));
    DocumentObject c = scene.object(0);
    c.editor = R"({"visible": false, "visible": true})";
    const std::string replaced = message([&] { scene.replaceObject(0, c); });
    INFO(replaced);
    CHECK(has(replaced, "object \"c\".editor"));
    CHECK(has(replaced, "\"visible\" appears twice"));

    CHECK(scene.itemCount() == 1);
    CHECK(scene.history().size() == steps);
    CHECK_FALSE(scene.item(0).settings.visible);
    CHECK(scene.text() == before);
}

TEST_CASE("Settings refuse numbers a float cannot hold instead of storing infinity (fuzz_editor_settings finding)", "[settings][hardening][regressions]")
{
    // Found by fuzz_editor_settings in CI: a material colour of 0.61e308 was cast to float (undefined;
    // infinity in practice), written back as null, and the written settings no longer read back.
    const std::string text = R"({"visible": false, "material": {"ambient": [0.1, 0.1, 0.1], "diffuse": [0.7, 0.61e308, 0.5],
                                 "specular": [0.3, 0.3, 0.3], "shininess": 32}})";
    CHECK_THROWS_WITH(ObjectSettings::fromText(text, "objects[0].editor"),
                      Catch::Contains("objects[0].editor.material.diffuse[1]") && Catch::Contains("out of range"));
    // The largest float itself is kept, and reads back after a write.
    const std::string edge = R"({"material": {"diffuse": [0.7, 3.4028234663852886e38, 0.5]}})";
    const ObjectSettings s = ObjectSettings::fromText(edge, "o");
    CHECK(s.material.diffuse[1] == std::numeric_limits<float>::max());
    // A display setting stored as float (the headlight colour) is refused the same way.
    CHECK_THROWS_WITH(DisplaySettings::fromText(R"({"headlight_color": [1e39, 0, 0]})", "doc.editor.display"),
                      Catch::Contains("headlight_color[0]") && Catch::Contains("out of range"));
}

} // namespace test_json_gate
