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
// A second case reaches what the first does not, at the same three sizes: the menus (File with its
// Open recent list, Edit, View, Help), the dialogs (autosave recovery, Open with the recent files,
// Save as, Import, Export, error, unsaved changes), the help window and the world-tolerance slider;
// dialogs, menus and the help window are also checked against the screen (ui/fit.h, fitWindow).
//
// A last case checks that the check itself fails: a status line longer than any window, a panel
// made narrower than its rows and a dialog wider than the window are reported.

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "support/process.h"
#include "support/replay_session.h"

namespace test_render_layout_fit {

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

/// Runs `events` on `doc` at `size` (`environment` prepended: VAR=value ...) and returns the state.
Json runState(const std::string& name, const std::string& doc, const Json& events, const std::string& size, const std::string& environment = "")
{
    const std::string file = cat(kTmp, "/fit_", name, ".events.json"), state = cat(kTmp, "/fit_", name, ".state.json");
    test::writeText(file, Json{{"events", events}}.dump(1));
    fs::remove(state);
    const auto r = runEditor(cat("'", doc, "' --replay '", file, "' --state '", state, "' --size ", size), environment);
    INFO(r.err);
    REQUIRE(r.status == 0);
    REQUIRE(fs::exists(state));
    const Json s = Json::parse(test::slurp(state));
    REQUIRE(s.contains("overflows"));
    return s;
}

/// Runs `events` on `doc` at `size` and returns the state's overflows.
Json overflows(const std::string& name, const std::string& doc, const Json& events, const std::string& size)
{
    return runState(name, doc, events, size)["overflows"];
}

/// Where the tooltip audit (the replay event "tooltip_audit", editor/app/tooltip_audit.h) first
/// hovered the control whose ID path ends with `suffix`, not scrolled: a place to click it.
Eigen::Vector2d hovered(const Json& audit, const std::string& suffix)
{
    for (const Json& item : audit["items"]) {
        const std::string path = item["path"];
        if (path.size() >= suffix.size() && path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0 && item["scrolled"] == false)
            return {item["x"].get<double>(), item["y"].get<double>()};
    }
    FAIL("no control " << suffix << " in the audit of " << audit["windows"].dump());
    return {};
}

/// An audit only to see which windows are shown (a coarse grid: 40 px).
Json windowsShown(const Json& windows = Json::array())
{
    Json e = {{"type", "tooltip_audit"}, {"step", 40}};
    if (!windows.empty()) e["windows"] = windows;
    return e;
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

TEST_CASE("issue 12: nothing is clipped in the menus, the dialogs and the help window at 900 x 600, 1280 x 800 and 1600 x 1000",
          "[render][replay]")
{
    // The states the case above does not reach, one run per size: the autosave-recovery dialog at
    // start (an autosave in FREEFORM_AUTOSAVE_DIR), the world-tolerance slider (px tolerance set to
    // 0 by Ctrl+click and typing), the File menu with its Open recent list (a recent.json in
    // FREEFORM_CONFIG_DIR: a document and a file that is gone), the Edit, View and Help menus, the
    // Open (with the recent files), Save as, Import, Export, error and unsaved-changes dialogs, and
    // the help window (F1). Where to click (menu titles, Open recent, px tolerance) is taken from a
    // first audit at the same size. Audits on a coarse grid check that each state came about.
    const std::string doc = splitDocument("data/ffd_every_type.json", "dialogs").front();
    const std::string config = kTmp + "/fit_config", autosave = kTmp + "/fit_autosave", corrupt = kTmp + "/fit_corrupt.json";
    fs::remove_all(config);
    fs::create_directories(config);
    test::writeText(config + "/recent.json", Json{{"recent", {doc, kTmp + "/fit_gone.json"}}}.dump(1));
    test::writeText(corrupt, "{\"format\": \"freeform\", \"version\": 1, \"objects\": [");
    const std::string environment = cat("FREEFORM_AUTOSAVE_DIR='", autosave, "' FREEFORM_CONFIG_DIR='", config, "'");

    Json file; // the File menu's audit (the menu bar and its menus lie at the top left at every size)
    for (const std::string size : {"900x600", "1280x800", "1600x1000"}) {
        // The clicks' places: the menu titles and px tolerance, then Open recent in the File menu.
        const Json first = runState(cat("where_", size), doc, Json::array({frames(2), {{"type", "tooltip_audit"}, {"windows", {"##MainMenuBar", "Display"}}}}),
                                    size)["tooltip_audits"][0];
        if (file.is_null()) {
            Json fileMenu = Json::array();
            click(fileMenu, hovered(first, "\"File\""));
            fileMenu.push_back(frames(2));
            fileMenu.push_back({{"type", "tooltip_audit"}});
            file = runState("where_file", doc, fileMenu, size)["tooltip_audits"][0];
        }

        fs::remove_all(autosave);
        fs::create_directories(autosave);
        test::writeText(autosave + "/autosave.json", test::slurp(doc));
        test::writeText(autosave + "/autosave-path.txt", doc + "\n");
        std::vector<std::pair<std::string, std::vector<std::string>>> expected; // per audit: the state, the windows it must show
        Json events = Json::array({frames(2), windowsShown()});
        expected.push_back({"autosave recovery dialog", {"Recover unsaved changes"}});
        events.push_back(key("Escape")); // discarded
        events.push_back(frames(2));
        const Eigen::Vector2d tolerance = hovered(first, "Display > \"px tolerance\"") + Eigen::Vector2d(30, 0);
        events.push_back(move(tolerance));
        events.push_back({{"type", "press"}, {"button", "left"}, {"x", tolerance.x()}, {"y", tolerance.y()}, {"mods", {"ctrl"}}});
        events.push_back({{"type", "release"}, {"button", "left"}, {"x", tolerance.x()}, {"y", tolerance.y()}, {"mods", {"ctrl"}}});
        events.push_back({{"type", "text"}, {"text", "0"}});
        events.push_back(key("Enter"));
        events.push_back(frames(2));
        events.push_back({{"type", "tooltip_audit"}, {"windows", {"Display"}}}); // the fine grid: the slider must be found
        expected.push_back({"px tolerance 0", {"Display"}});
        click(events, hovered(first, "\"File\""));
        events.push_back(frames(2));
        events.push_back(move(hovered(file, "\"Open recent\"")));
        events.push_back(frames(3));
        events.push_back(windowsShown());
        expected.push_back({"File > Open recent", {"##Menu_01", "##Menu_00"}});
        for (const char* menu : {"Edit", "View", "Help"}) {
            events.push_back(move(hovered(first, cat("\"", menu, "\""))));
            events.push_back(frames(2));
            events.push_back(windowsShown());
            expected.push_back({cat(menu, " menu"), {"##Menu_00"}});
        }
        click(events, hovered(first, "\"Help\"")); // closes the menu
        events.push_back(frames(2));
        const std::vector<std::pair<std::string, Json>> dialogs = {{"Open", Json::array({key("O", {"ctrl"})})},
                                                                  {"Save as", Json::array({key("S", {"ctrl", "shift"})})},
                                                                  {"Import", Json::array({key("I", {"ctrl"})})},
                                                                  {"Export OBJ", Json::array({key("E", {"ctrl"})})},
                                                                  {"Error", Json::array({{{"type", "open"}, {"path", corrupt}}})},
                                                                  {"Unsaved changes", Json::array({key("W"), key("N", {"ctrl"})})}};
        for (const auto& [name, opening] : dialogs) {
            for (const Json& e : opening) events.push_back(e);
            events.push_back(frames(2));
            events.push_back(windowsShown());
            expected.push_back({name + " dialog", {name}});
            events.push_back(key("Escape"));
            events.push_back(frames(2));
        }
        events.push_back(key("F1"));
        events.push_back(frames(2));
        events.push_back(windowsShown(Json::array({"Controls"})));
        expected.push_back({"help window", {"Controls"}});

        const Json state = runState(cat("dialogs_", size), doc, events, size, environment);
        REQUIRE(state["tooltip_audits"].size() == expected.size());
        for (std::size_t k = 0; k < expected.size(); ++k) {
            INFO("at " << size << ", " << expected[k].first << ": windows " << state["tooltip_audits"][k]["windows"].dump());
            CHECK(state["tooltip_audits"][k]["windows"] == Json(expected[k].second));
        }
        bool worldTolerance = false;
        for (const Json& item : state["tooltip_audits"][1]["items"]) worldTolerance |= item["path"] == "Display > \"tolerance\"";
        CHECK(worldTolerance);
        INFO("at " << size << ", clipped:\n" << describe(state["overflows"]));
        CHECK(state["overflows"].empty());
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
    events.push_back(key("O", {"ctrl"})); // the Open dialog: its path field alone is 480 px wide
    events.push_back(frames(3));
    const Json list = overflows("check", doc, events, "120x400");
    INFO(describe(list));
    bool status = false, panel = false, dialog = false;
    for (const Json& o : list) {
        status |= o["panel"] == "##status";
        panel |= o["label"].get<std::string>().rfind("(widest row", 0) == 0;
        dialog |= o["panel"] == "Open";
        CHECK(o["needed"].get<double>() > o["available"].get<double>());
    }
    CHECK(status);
    CHECK(panel);
    CHECK(dialog);
}

} // namespace test_render_layout_fit
