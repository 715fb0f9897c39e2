// Nothing clipped (issue 12, "no truncated labels"; docs/editor.md, "Nothing clipped"): replayed
// sessions at 900 x 600, 1280 x 800 and 1600 x 1000 open a document of each object type in turn
// (every type of data/ffd_every_type.json and examples/data/nurbs.json, a lattice bound to a mesh,
// the mesh alone, a cage whose file is missing: its error), select the object in the Scene panel, select all its points (the numeric fields
// of the selection, the NURBS weight field), and start a spline and a circle (the longest status
// lines). The editor records every text it draws in a table cell, a numeric field or the status
// bar, and every panel as a whole, that gets less width than CalcTextSize says it needs (ui/fit.h);
// --state lists them as "overflows", and each run must list none. Each offender is printed with
// its panel, label, needed and available pixels.
//
// A second case checks that the check itself fails: a status line longer than any window and a
// panel made narrower than its rows are reported.

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "support/process.h"
#include "support/replay_session.h"

using namespace freeform;
using namespace freeform::editor::replay_test;
using Json = nlohmann::ordered_json;

namespace {

namespace fs = std::filesystem;

const std::string kSource = FREEFORM_SOURCE_DIR;

/// One document per object of `file` (the object alone; a lattice keeps the document's meshes,
/// their paths made absolute, and is bound to the first). Returns the paths written.
std::vector<std::string> splitDocument(const std::string& file, const std::string& prefix)
{
    const Json whole = Json::parse(test::slurp(kSource + "/" + file));
    const fs::path folder = fs::path(kSource + "/" + file).parent_path();
    std::vector<std::string> out;
    for (Json o : whole["objects"]) {
        if (o.contains("mesh")) { // a subdivision cage read from a file: that file, wherever the copy is
            // The cage as the document has it, and as a document whose cage file is missing (the
            // object's error is shown in Properties).
            Json missing = {{"format", "freeform"}, {"version", 1}, {"objects", Json::array({o})}};
            missing["objects"][0]["mesh"] = (folder / "no-such-folder" / o["mesh"].get<std::string>()).string();
            const std::string path = cat(kTmp, "/fit_", prefix, "_missing_cage.json");
            test::writeText(path, missing.dump(1));
            out.push_back(path);
            o["mesh"] = (folder / o["mesh"].get<std::string>()).string();
        }
        Json doc = {{"format", "freeform"}, {"version", 1}, {"objects", Json::array({o})}};
        if (o["type"] == "lattice" && whole.contains("editor") && whole["editor"].contains("meshes")) {
            Json meshes = whole["editor"]["meshes"];
            for (Json& m : meshes) m["path"] = (folder / m["path"].get<std::string>()).string();
            doc["editor"] = {{"meshes", meshes}};
            doc["objects"][0]["editor"] = {{"ffd", {{"mesh", meshes[0]["name"]}}}};
            // The mesh alone too (its panel: "Fit a lattice").
            Json mesh = {{"format", "freeform"}, {"version", 1}, {"objects", Json::array()}, {"editor", {{"meshes", meshes}}}};
            const std::string path = cat(kTmp, "/fit_", prefix, "_mesh.json");
            test::writeText(path, mesh.dump(1));
            out.push_back(path);
        }
        const std::string path = cat(kTmp, "/fit_", prefix, "_", o["name"].get<std::string>(), ".json");
        test::writeText(path, doc.dump(1));
        out.push_back(path);
    }
    return out;
}

/// The first row of the Scene panel (ui/ui.cpp: 8 px from the left, below the 19-px menu bar and
/// 8 px; its title bar 19 px and padding 8 px; the row's text after the 19-px visibility box).
const Eigen::Vector2d kFirstRow(8 + 8 + 19 + 4 + 30, 19 + 8 + 19 + 8 + 9);

/// Runs `events` on `doc` at `size` and returns the state's overflows.
Json overflows(const std::string& name, const std::string& doc, const Json& events, const std::string& size)
{
    const std::string file = cat(kTmp, "/fit_", name, ".events.json"), state = cat(kTmp, "/fit_", name, ".state.json");
    test::writeText(file, Json{{"events", events}}.dump(1));
    fs::remove(state);
    const auto r = runEditor(cat("'", doc, "' --replay '", file, "' --state '", state, "' --size ", size));
    INFO(r.err);
    REQUIRE(r.status == 0);
    REQUIRE(fs::exists(state));
    const Json s = Json::parse(test::slurp(state));
    REQUIRE(s.contains("overflows"));
    return s["overflows"];
}

std::string describe(const Json& list)
{
    std::string text;
    for (const Json& o : list)
        text += cat("  ", o["panel"].get<std::string>(), ": \"", o["label"].get<std::string>(), "\" needs ", o["needed"].get<double>(),
                    " px, has ", o["available"].get<double>(), " px\n");
    return text;
}

} // namespace

TEST_CASE("issue 12: no text is clipped at 900 x 600, 1280 x 800 and 1600 x 1000 with each object type selected", "[render][replay]")
{
    std::vector<std::string> docs = splitDocument("data/ffd_every_type.json", "every");
    for (const std::string& d : splitDocument("examples/data/nurbs.json", "nurbs")) docs.push_back(d);
    REQUIRE(docs.size() == 19); // 12 + 5 objects, the mesh alone, a cage whose file is missing

    Json events = Json::array();
    // Nothing selected, then a spline and a circle being drawn (the status bar's longest hints).
    events.push_back(frames(2));
    events.push_back(key("C", {"shift"}));
    events.push_back(frames(2));
    events.push_back(key("Escape"));
    events.push_back(key("O", {"shift"}));
    events.push_back(frames(2));
    events.push_back(key("Escape"));
    for (const std::string& doc : docs) {
        events.push_back({{"type", "open"}, {"path", doc}});
        events.push_back(frames(2));
        click(events, kFirstRow);
        events.push_back(frames(2));
        events.push_back(key("A")); // every point selected: the selection's fields, weights
        events.push_back(frames(3));
    }
    // The Display panel with reflection lines (its stripes slider).
    events.push_back(key("R"));
    events.push_back(frames(2));

    for (const std::string size : {"900x600", "1280x800", "1600x1000"}) {
        const Json list = overflows(cat("types_", size), docs.front(), events, size);
        INFO("at " << size << ", clipped:\n" << describe(list));
        CHECK(list.empty());
    }
}

TEST_CASE("issue 12: the clipping check reports a cut status line and a panel narrower than its rows", "[render][replay]")
{
    // A status line is cut when the window is narrower than it: at 120 x 400 even the shortest hint
    // ("Select: click an object ...") is, and the panels are narrower than their rows.
    const std::string doc = splitDocument("examples/data/nurbs.json", "check").front();
    Json events = Json::array({frames(2)});
    click(events, kFirstRow); // the circle selected: Properties shows its rows
    events.push_back(frames(3));
    const Json list = overflows("check", doc, events, "120x400");
    INFO(describe(list));
    bool status = false, panel = false;
    for (const Json& o : list) {
        status |= o["panel"] == "##status";
        panel |= o["label"].get<std::string>().rfind("(widest row", 0) == 0;
        CHECK(o["needed"].get<double>() > o["available"].get<double>());
    }
    CHECK(status);
    CHECK(panel);
}
