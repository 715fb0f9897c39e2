// Issue 12, "tooltips on every control" (docs/editor.md): every control the user can reach at
// 1280 x 800 has a tooltip. Label "render" (an X display, Xvfb).
//
// Method: replayed sessions with the replay event "tooltip_audit" (editor/app/tooltip_audit.h):
// the editor moves the pointer over a grid of points covering every panel shown (a step of half a
// line height, 8.5 px; every scroll position of the panels and of their scrolling children) and,
// at each point where ImGui reports a hovered item (its HoveredId; plain text is no item, window
// chrome is skipped), checks that a tooltip window is open in that frame. --state reports every
// item hovered with its ID path (window > labels), and the ones without a tooltip. The states:
//   - nothing selected (Scene, Properties, Display, the main menu bar, the status bar);
//   - each object type selected from the Scene panel, then all its points selected (A; only the
//     Properties panel is swept where only it changes with the selection): Bezier
//     curve, spline with its joints table, de Boor spline, patch and patch complex (with the edge
//     continuity table), de Boor surface, subdivision cage, lattice bound to a mesh, the mesh
//     itself (up axis, fit lattice), NURBS and rational curves and surfaces: each brings its tool
//     panel; the Display panel with reflection lines and normals, and with the det J scalar map;
//   - the collapsed headers opened (editing, material, back faces), proportional editing (O) and
//     the curvature comb (V) on (their sliders show);
//   - the File, Edit, View and Help menus opened;
//   - the Open, Save as, Import (with its up axis), Export, unsaved-changes and error dialogs and
//     the help window (F1).
// The pointer positions to click (Scene rows, menu titles, headers, buttons) are taken from a
// first audit of the same state, never guessed: its items carry the point where each was hovered.

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "support/process.h"
#include "support/replay_session.h"

namespace test_render_tooltips {

using Json = nlohmann::ordered_json;
using namespace freeform::editor::replay_test;

namespace {

namespace fs = std::filesystem;

const std::string kSource = FREEFORM_SOURCE_DIR;

Json readJson(const std::string& path) { return Json::parse(freeform::test::slurp(path)); }

/// Document 1: one object of each kind of data/ffd_every_type.json that has its own panel (the
/// paths made absolute), the display with reflection lines and normals (their sliders show).
std::string typesDocument()
{
    Json d = readJson(kSource + "/data/ffd_every_type.json");
    Json objects = Json::array();
    for (Json o : d["objects"]) {
        const std::string name = o["name"];
        if (name != "curve3" && name != "spline3" && name != "deboor3" && name != "complex_a" && name != "complex_b" && name != "grid" &&
            name != "cage" && name != "L")
            continue;
        if (o.contains("mesh")) o["mesh"] = kSource + "/data/" + o["mesh"].get<std::string>();
        objects.push_back(o);
    }
    d["objects"] = objects;
    for (Json& m : d["editor"]["meshes"]) m["path"] = kSource + "/data/" + m["path"].get<std::string>();
    d["editor"]["display"] = {{"analysis", "reflection_lines"}, {"normals", true}};
    const std::string path = kTmp + "/tooltips_types.json";
    freeform::test::writeText(path, d.dump(1));
    return path;
}

/// Document 2: examples/data/nurbs.json (NURBS and rational curves and surfaces), the display with
/// the det J scalar map (its range controls show).
std::string nurbsDocument()
{
    Json d = readJson(kSource + "/examples/data/nurbs.json");
    d["editor"]["display"] = {{"analysis", "scalar_map"}};
    const std::string path = kTmp + "/tooltips_nurbs.json";
    freeform::test::writeText(path, d.dump(1));
    return path;
}

Json audit() { return {{"type", "tooltip_audit"}}; }
/// An audit of the Properties panel only (the other panels do not change with the selection and
/// are swept in the states without one).
Json auditProperties() { return {{"type", "tooltip_audit"}, {"windows", Json::array({"Properties"})}}; }

/// Runs the replay on `doc` at 1280 x 800 and returns its tooltip audits (--state).
/// `environment` is prepended to the command (VAR=value ...).
std::vector<Json> audits(const std::string& name, const std::string& doc, const Json& events, std::size_t expected,
                         const std::string& environment = "")
{
    const std::string file = cat(kTmp, "/tooltips_", name, ".events.json"), state = cat(kTmp, "/tooltips_", name, ".state.json");
    freeform::test::writeText(file, Json{{"events", events}}.dump(1));
    fs::remove(state);
    const auto r = runEditor(cat("'", doc, "' --replay '", file, "' --state '", state, "' --size ", kW, "x", kH), environment);
    INFO(r.err);
    REQUIRE(r.status == 0);
    const Json s = readJson(state);
    REQUIRE(s.contains("tooltip_audits"));
    REQUIRE(s["tooltip_audits"].size() == expected);
    return std::vector<Json>(s["tooltip_audits"].begin(), s["tooltip_audits"].end());
}

bool endsWith(const std::string& s, const std::string& suffix)
{
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// The item of the audit whose ID path ends with `suffix` (found without scrolling).
const Json* findItem(const Json& a, const std::string& suffix)
{
    for (const Json& item : a["items"])
        if (endsWith(item["path"].get<std::string>(), suffix)) return &item;
    return nullptr;
}

/// The item of the audit whose tooltip text begins with `prefix`.
const Json* findByTooltip(const Json& a, const std::string& prefix)
{
    for (const Json& item : a["items"])
        if (item["text"].get<std::string>().rfind(prefix, 0) == 0) return &item;
    return nullptr;
}

/// Where to click the item whose ID path ends with `suffix`: the point where the audit hovered it
/// (a panel not scrolled).
Eigen::Vector2d at(const Json& a, const std::string& suffix)
{
    const Json* item = findItem(a, suffix);
    INFO("no item " << suffix);
    REQUIRE(item);
    REQUIRE((*item)["scrolled"] == false);
    return {(*item)["x"].get<double>(), (*item)["y"].get<double>()};
}

/// The dropdowns opened by every audit checked (their ID paths), over the whole test.
std::set<std::string> dropdownsOpened;

/// Every hovered control has a tooltip; the audit hovered at least `least` controls, among them
/// those whose paths end with `expected` (so that a state that did not come about fails). Every
/// dropdown hovered was opened by the sweep and at least two of its choices were hovered in its
/// open list (each with its own tooltip: a choice without one is in "missing").
void checkComplete(const Json& a, const std::string& state, std::size_t least, const std::vector<std::string>& expected = {})
{
    INFO("state: " << state << ", " << a["points"] << " points, " << a["items"].size() << " controls hovered, windows " << a["windows"].dump());
    std::string missing;
    for (const Json& m : a["missing"]) missing += "\n  " + m.get<std::string>();
    INFO("controls without a tooltip:" << missing);
    CHECK(a["missing"].empty());
    CHECK(a["items"].size() >= least);
    for (const std::string& e : expected) {
        INFO("expected control " << e);
        CHECK(findItem(a, e) != nullptr);
    }
    for (const Json& item : a["items"])
        if (item["tooltip"] == true) {
            INFO(item["path"]);
            CHECK(item["hovered"].get<int>() >= 1);
        }
    for (const Json& d : a["dropdowns"]) {
        INFO("dropdown " << d["path"]);
        CHECK(d["opened"] == true);
        CHECK(d["choices"].get<int>() >= 2);
        dropdownsOpened.insert(d["path"].get<std::string>());
    }
}

/// A click at p with Ctrl held (a slider becomes a text field).
void ctrlClick(Json& events, const Eigen::Vector2d& p)
{
    events.push_back(move(p));
    events.push_back({{"type", "press"}, {"button", "left"}, {"x", p.x()}, {"y", p.y()}, {"mods", {"ctrl"}}});
    events.push_back({{"type", "release"}, {"button", "left"}, {"x", p.x()}, {"y", p.y()}, {"mods", {"ctrl"}}});
}

/// The Scene panel's row of `name` in an audit of the nothing-selected state.
Eigen::Vector2d row(const Json& a, const std::string& name, const std::string& type)
{
    return at(a, cat("\"", name, "  (", type, ")\""));
}

} // namespace

TEST_CASE("issue 12: every control of every panel, menu and dialog has a tooltip", "[render][replay][tooltips]")
{
    // Six editor runs (each replays several states): the run time stays well under a minute.
    const std::string doc = typesDocument();
    const Json start = audits("types_start", doc, Json::array({frames(2), audit()}), 1)[0];
    checkComplete(start, "nothing selected", 20,
                  {"\"File\"", "\"Edit\"", "\"View\"", "\"Help\"", "\"shading\"", "\"stripes\"", "\"normal length\"", "\"lights\"",
                   "\"add light\"", "\"##visible\"", "\"back faces, background\""});

    // Each object selected from its Scene row, then all its points (A); last, the patch complex in
    // a tall window, where the edge continuity button shows without scrolling.
    const std::vector<std::pair<std::string, std::string>> objects = {
        {"curve3", "bezier_curve"},  {"spline3", "bezier_spline"}, {"deboor3", "deboor_spline"}, {"complex_a", "bezier_surface"},
        {"grid", "deboor_surface"},  {"cage", "subdivision_surface"}, {"L", "lattice"},         {"cube", "mesh"}};
    Json events = Json::array();
    for (const auto& [name, type] : objects) {
        click(events, row(start, name, type));
        events.push_back(frames(2));
        events.push_back(name == objects.front().first ? audit() : auditProperties()); // the other panels once with a selection
        events.push_back(key("A"));
        if (name == "curve3") events.push_back(key("V")); // the curvature comb: its scale slider shows
        events.push_back(frames(2));
        events.push_back(auditProperties());
    }
    Json tall = Json::array();
    click(tall, row(start, "complex_a", "bezier_surface"));
    tall.push_back({{"type", "resize"}, {"width", kW}, {"height", 2000}});
    tall.push_back(frames(2));
    for (const Json& e : tall) events.push_back(e);
    events.push_back(auditProperties());
    const std::vector<Json> selected = audits("types_selected", doc, events, 2 * objects.size() + 1);
    const std::vector<std::vector<std::string>> expected = {
        {"\"elevate degree (E)\"", "\"de Casteljau at t (T)\"", "\"t\"", "\"control points (4)\""},
        {"\"all joints\"", "\"joints\" > \"#\"", "\"joints\" > \"mode\"", "\"joints\" > \"C / G\"", "\"joints\" > \"jump\"", "\"##mode\""},
        {"\"insert point (I)\"", "\"curvature comb (V)\""},
        {"\"edge continuity of all patches\"", "\"create patch (P)\"", "\"m, n\" > 0", "\"tessellation\"", "\"material\"", "\"editing\""},
        {"\"edge continuity of all patches\""},
        {"\"tessellation\"", "\"mode\""},
        {"\"reset lattice\"", "\"strength\"", "\"outside\"", "\"apply exactly to curves and patches\""},
        {"\"up axis\"", "\"fit lattice\"", "\"margin\""}};
    for (std::size_t k = 0; k < objects.size(); ++k) {
        checkComplete(selected[2 * k], objects[k].first + " selected", 15, expected[k]);
        checkComplete(selected[2 * k + 1], objects[k].first + " and all its points selected", 15,
                      objects[k].first == "cube"     ? std::vector<std::string>{}
                      : objects[k].first == "curve3" ? std::vector<std::string>{"0 > \"##selected\"", "\"comb scale\""}
                      // the grid's wide coordinates do not fit three to a row: one field per row, labelled
                      : objects[k].first == "grid" ? std::vector<std::string>{"0 > \"x\""}
                                                   : std::vector<std::string>{"0 > \"##selected\""});
    }

    // The patch complex's edge continuity table (the button clicked in the tall window, then back
    // to 1280 x 800) and the collapsed headers opened: Properties > editing and material (the
    // lower one first), Display > material and back faces. The edge table scrolls sideways with
    // its edge column frozen, so the sweep reaches the heads of the first three columns (the
    // fourth's tooltip comes from the same header loop).
    Json open = tall;
    open.push_back(key("O")); // proportional editing (before a panel has the keyboard): its radius slider shows
    click(open, at(selected.back(), "\"edge continuity of all patches\""));
    open.push_back({{"type", "resize"}, {"width", kW}, {"height", kH}});
    open.push_back(frames(2));
    const Json& patch = selected[6];
    click(open, at(patch, "Properties > \"editing\""));
    click(open, at(patch, "Properties > \"material\""));
    click(open, at(start, "Display > \"back faces, background\""));
    click(open, at(start, "Display > \"material\""));
    open.push_back(frames(2));
    open.push_back(audit());
    checkComplete(audits("types_open", doc, open, 1)[0], "patch complex with its edge table, headers open", 40,
                  {"\"edges\" > 0 > \"edge\"", "\"edges\" > 1 > \"level\"", "\"edges\" > 2 > \"angle (deg)\"",
                   "\"snap to grid (Shift+Tab)\"", "\"radius (+/-)\"", "\"own material\"", "\"back faces\" > \"##X\"", "\"shininess\""});

    // NURBS and rational objects (a second document, the Display panel with the det J scalar
    // map): the same Scene rows, checked against the run's own first audit.
    const std::string nurbs = nurbsDocument();
    const std::vector<std::pair<std::string, std::string>> nurbsObjects = {
        {"circle", "nurbs_curve"}, {"arc", "rational_bezier_curve"}, {"sphere", "nurbs_surface"}, {"cyl", "rational_bezier_surface"}};
    const std::vector<int> nurbsRows = {0, 1, 3, 4};
    const std::vector<std::string> typesRows = {"\"curve3  (bezier_curve)\"", "\"spline3  (bezier_spline)\"", "\"deboor3  (deboor_spline)\"",
                                                "\"complex_a  (bezier_surface)\"", "\"complex_b  (bezier_surface)\""};
    Json nurbsEvents = Json::array({frames(2), audit()});
    for (std::size_t k = 0; k < nurbsObjects.size(); ++k) {
        click(nurbsEvents, at(start, typesRows[static_cast<std::size_t>(nurbsRows[k])]));
        nurbsEvents.push_back(frames(2));
        nurbsEvents.push_back(auditProperties());
        nurbsEvents.push_back(key("A"));
        nurbsEvents.push_back(frames(2));
        nurbsEvents.push_back(auditProperties());
    }
    const std::vector<Json> n = audits("nurbs", nurbs, nurbsEvents, 1 + 2 * nurbsObjects.size());
    checkComplete(n[0], "NURBS document, nothing selected, scalar map", 20, {"\"auto range\"", "\"min, max\" > 0"});
    for (std::size_t k = 0; k < nurbsObjects.size(); ++k) {
        // The row clicked is this object's (the Scene panel lays out both documents alike).
        const std::string label = cat("\"", nurbsObjects[k].first, "  (", nurbsObjects[k].second, ")\"");
        REQUIRE(at(n[0], label) == at(start, typesRows[static_cast<std::size_t>(nurbsRows[k])]));
        checkComplete(n[1 + 2 * k], nurbsObjects[k].first + " selected", 15,
                      k < 2 ? std::vector<std::string>{"\"circle (Shift+O)\"", "\"de Boor construction at t (T)\""}
                            : std::vector<std::string>{"\"circle (Shift+O)\"", "\"tessellation\""});
        checkComplete(n[2 + 2 * k], nurbsObjects[k].first + " and all its points selected", 15, {"\"##weight\""});
    }
    checkComplete(n[1], "circle selected", 15, {"\"insert knot at u (K)\"", "\"t\""});
    checkComplete(n[5], "sphere selected", 15, {"\"in u\"", "\"in v\""});

    // The menus: File opened by a click, the others by moving over their titles (as in any menu
    // bar); a curve selected first, so that Edit's items are enabled.
    const std::vector<std::pair<std::string, std::vector<std::string>>> menus = {
        {"File", {"\"New\"", "\"Open...\"", "\"Open recent\"", "\"Quit\""}},
        {"Edit", {"\"Undo\"", "\"Snap to grid\"", "\"Translate gizmo\""}},
        {"View", {"\"flat\"", "\"iso\"", "\"Fit all\"", "\"Frame statistics\""}},
        {"Help", {"\"Controls\""}}};
    Json menuEvents = Json::array();
    click(menuEvents, row(start, "curve3", "bezier_curve"));
    click(menuEvents, at(start, "\"File\""));
    for (const auto& [menu, items] : menus) {
        menuEvents.push_back(move(at(start, cat("\"", menu, "\""))));
        menuEvents.push_back(frames(2));
        menuEvents.push_back(audit());
    }
    const std::vector<Json> m = audits("menus", doc, menuEvents, menus.size());
    for (std::size_t k = 0; k < menus.size(); ++k) {
        INFO(menus[k].first << " menu, windows " << m[k]["windows"].dump());
        REQUIRE(m[k]["windows"].size() == 1); // the menu's popup only
        checkComplete(m[k], menus[k].first + " menu open", menus[k].second.size(), menus[k].second);
    }

    // The dialogs, one after the other (Escape closes each), and the help window (F1).
    const std::string corrupt = kTmp + "/tooltips_corrupt.json";
    freeform::test::writeText(corrupt, "{\"format\": \"freeform\", \"version\": 1, \"objects\": [");
    const std::vector<std::tuple<std::string, Json, std::vector<std::string>>> dialogs = {
        {"Open", Json::array({key("O", {"ctrl"})}), {"\"##path\"", "\"OK\"", "\"Cancel\""}},
        {"Save as", Json::array({key("S", {"ctrl", "shift"})}), {"\"##path\"", "\"OK\"", "\"Cancel\""}},
        {"Import", Json::array({key("I", {"ctrl"})}), {"\"##path\"", "\"up axis of OBJ, PLY, STL, OFF\"", "\"OK\""}},
        {"Export OBJ", Json::array({key("E", {"ctrl"})}), {"\"##path\"", "\"OK\""}},
        {"Error", Json::array({{{"type", "open"}, {"path", corrupt}}}), {"\"OK\""}},
        {"Unsaved changes", Json::array({key("W"), key("N", {"ctrl"})}), {"\"Save\"", "\"Discard changes\"", "\"Cancel\""}},
        {"Controls", Json::array({key("F1")}), {"\"First steps\""}}};
    Json dialogEvents = Json::array();
    for (const auto& [name, opening, items] : dialogs) {
        for (const Json& e : opening) dialogEvents.push_back(e);
        dialogEvents.push_back(frames(2));
        dialogEvents.push_back(audit());
        dialogEvents.push_back(key("Escape"));
        dialogEvents.push_back(frames(2));
    }
    const std::vector<Json> d = audits("dialogs", doc, dialogEvents, dialogs.size());
    for (std::size_t k = 0; k < dialogs.size(); ++k) {
        const auto& [name, opening, items] = dialogs[k];
        bool shown = false;
        for (const Json& w : d[k]["windows"]) shown = shown || w.get<std::string>() == name;
        INFO(name << ": windows " << d[k]["windows"].dump());
        CHECK(shown);
        checkComplete(d[k], name + " dialog", items.size(), items);
    }

    // The states the runs above cannot reach. The autosave-recovery dialog at start (an autosave in
    // FREEFORM_AUTOSAVE_DIR); File > Open recent's entries and the Open dialog's recent list (a
    // recent.json in FREEFORM_CONFIG_DIR: this document and a file that is gone, shown greyed); the
    // world-tolerance slider, shown when the pixel tolerance is 0 (set as a user does: Ctrl+click
    // on "px tolerance", type 0, Enter).
    const std::string config = kTmp + "/tooltips_config", autosave = kTmp + "/tooltips_autosave";
    for (const std::string& folder : {config, autosave}) {
        fs::remove_all(folder);
        fs::create_directories(folder);
    }
    // A recent file whose path is long (over 200 characters, a space and a non-ASCII letter in a
    // folder name): its entry is shortened in the menu and found by its tooltip, which names it in full.
    // (The folder name is padded so that the path reaches 200 characters whatever the checkout's.)
    const std::string folderStart = kTmp + "/tooltips recent \xC3\xBC ", name = "/tooltips_long_recent.json";
    const std::size_t pad = std::max<std::size_t>(120, 200 - std::min<std::size_t>(200, folderStart.size() + name.size()));
    const std::string longFolder = folderStart + std::string(pad, 'f');
    fs::create_directories(fs::u8path(longFolder));
    const std::string longDoc = longFolder + name, gone = kTmp + "/tooltips_gone.json";
    REQUIRE(longDoc.size() >= 200);
    freeform::test::writeText(longDoc, freeform::test::slurp(doc));
    freeform::test::writeText(config + "/recent.json", Json{{"recent", {doc, longDoc, gone}}}.dump(1));
    freeform::test::writeText(autosave + "/autosave.json", freeform::test::slurp(doc));
    freeform::test::writeText(autosave + "/autosave-path.txt", doc + "\n");
    Json more = Json::array({frames(2), audit(), key("Escape"), frames(2)}); // the recovery dialog, discarded
    click(more, at(start, "\"File\""));
    more.push_back(frames(2));
    more.push_back(move(at(m[0], "\"Open recent\"")));
    more.push_back(frames(3));
    more.push_back(audit());
    click(more, at(start, "\"File\"")); // closes the menu
    more.push_back(frames(2));
    more.push_back(key("O", {"ctrl"}));
    more.push_back(frames(2));
    more.push_back(audit());
    more.push_back(key("Escape"));
    more.push_back(frames(2));
    ctrlClick(more, at(start, "Display > \"px tolerance\"") + Eigen::Vector2d(30, 0));
    more.push_back({{"type", "text"}, {"text", "0"}});
    more.push_back(key("Enter"));
    more.push_back(frames(2));
    more.push_back({{"type", "tooltip_audit"}, {"windows", Json::array({"Display"})}});
    const std::vector<Json> r =
        audits("more", doc, more, 4, cat("FREEFORM_AUTOSAVE_DIR='", autosave, "' FREEFORM_CONFIG_DIR='", config, "'"));
    const std::vector<std::string> states = {"autosave recovery dialog", "File > Open recent", "Open dialog with the recent files",
                                             "px tolerance 0"};
    const std::vector<std::vector<std::string>> expectedMore = {{"\"Recover (Enter)\"", "\"Discard (Escape)\""},
                                                                {"\"Open recent\""},
                                                                {"\"OK\""},
                                                                {"Display > \"px tolerance\"", "Display > \"tolerance\""}};
    for (std::size_t k = 0; k < states.size(); ++k) checkComplete(r[k], states[k], expectedMore[k].size(), expectedMore[k]);
    CHECK(r[0]["windows"] == Json::array({"Recover unsaved changes"}));
    CHECK(r[1]["windows"].size() == 2); // the File menu and its Open recent submenu
    // Each recent file has its entry, with its own tooltip naming it, in the submenu and in the Open
    // dialog (the entries' ID paths hold no path: ImGui's stack tool cuts long labels).
    for (const auto& [k, window, action] : {std::tuple{1, std::string("##Menu_"), std::string("Open this document")},
                                            std::tuple{2, std::string("Open"), std::string("Put this path in the field")}})
        for (const auto& [path, exists] : {std::pair{doc, true}, std::pair{longDoc, true}, std::pair{gone, false}}) {
            const Json* item = findByTooltip(r[k], path + "\n");
            INFO(states[k] << ": the entry of " << path);
            REQUIRE(item);
            CHECK((*item)["window"].get<std::string>().rfind(window, 0) == 0); // a menu's window: "##Menu_" and its number
            CHECK((*item)["tooltip"] == true);
            CHECK((*item)["text"].get<std::string>().find(exists ? action : std::string("This file no longer exists")) != std::string::npos);
        }

    // Every dropdown of the panels and dialogs was opened in some state above, and each choice in it
    // had its own tooltip.
    std::string opened;
    for (const std::string& path : dropdownsOpened) opened += "\n  " + path;
    INFO("dropdowns opened:" << opened);
    for (const char* dropdown : {"Display > \"shading\"", "Display > \"specular\"", "Display > \"analysis\"", "Display > \"anti-alias\"",
                                 "Properties > \"mode\"", "Properties > \"up axis\"", "Properties > \"scheme\"", "Properties > \"boundary\"",
                                 "Properties > \"all joints\"", "Properties > \"joints\" > 1 > \"##mode\"", "Properties > \"mesh\"",
                                 "Properties > \"outside\"", "Import > \"up axis of OBJ, PLY, STL, OFF\""}) {
        INFO("dropdown " << dropdown);
        CHECK(dropdownsOpened.count(dropdown) == 1);
    }
}

} // namespace test_render_tooltips
