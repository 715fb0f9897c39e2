// The editor's own JSON readers (replay files, display and object settings) pass the library's
// one JSON gate (freeform/io/json_check.h; docs/mesh-io.md, "Hostile input") before nlohmann
// builds a tree: a text nested 100,000 deep is refused with an error naming the source (no stack
// overflow: the tree's construction and destruction would recurse 100,000 deep), and an object
// that repeats a key (also written with an escape) is refused rather than letting the last win.

#include <catch2/catch.hpp>

#include <freeform/core/error.h>

#include <string>

#include "interaction/replay.h"
#include "scene/settings.h"

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
