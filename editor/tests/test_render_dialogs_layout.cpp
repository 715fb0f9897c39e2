// Replayed sessions for issue 12, bugs 2 and 3 (label "render": they need an X display), checked
// through the state the editor writes on exit (--state: the error dialog's message, the window and
// the panels' rectangles, the camera):
//   - File > Open (Ctrl+O), the path of a corrupt document typed, Enter: the error dialog is up
//     afterwards with the file's error (before the fix the same Enter closed it in the frame it
//     appeared); also with Enter held over several frames before it is released; Escape in a
//     later frame closes it;
//   - the window resized (replay event "resize") to 900 x 600 and to 1600 x 1000: every panel lies
//     inside the window, Properties against its right edge and the Display panel above its bottom
//     edge (before the fix they kept the places computed for the first size: at 900 x 600
//     Properties started at x = 982, outside the window);
//   - a scroll over a panel leaves the camera alone, a scroll over the view zooms it.

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "support/editor_process.h"
#include "support/process.h"

namespace test_render_dialogs_layout {

using Json = nlohmann::ordered_json;

namespace {

namespace fs = std::filesystem;

const std::string kTmp = FREEFORM_TEST_TMP;

template <typename... Parts>
std::string cat(const Parts&... parts)
{
    std::ostringstream s;
    (s << ... << parts);
    return s.str();
}

std::string document()
{
    const std::string doc = kTmp + "/dialogs.json";
    freeform::test::writeText(doc, R"({"format": "freeform", "version": 1, "objects": [
      {"name": "c", "type": "bezier_curve", "points": [[-2, 0, 0], [-1, 0, 1.5], [1, 0, 1.5], [2, 0, 0]]}]})");
    return doc;
}

/// Runs a replay and returns the state written on exit.
Json replayState(const std::string& name, const Json& events, const std::string& size = "1280x800", std::string doc = "")
{
    const std::string file = cat(kTmp, "/dialogs_", name, ".events.json"), state = cat(kTmp, "/dialogs_", name, ".state.json"),
                      out = cat(kTmp, "/dialogs_", name, ".out.json");
    freeform::test::writeText(file, Json{{"events", events}}.dump(1));
    fs::remove(state);
    if (doc.empty()) doc = document();
    const auto r = freeform::test::runEditorBinary(cat("'", doc,
                                           "' --replay '", file, "' --state '", state, "' --save '", out, "' --size ", size));
    INFO(r.err);
    REQUIRE(r.status == 0);
    REQUIRE(fs::exists(state));
    return Json::parse(freeform::test::slurp(state));
}

Json key(const std::string& k, const std::vector<std::string>& mods = {})
{
    Json e = {{"type", "key"}, {"key", k}};
    if (!mods.empty()) e["mods"] = mods;
    return e;
}

std::string corruptFile()
{
    const std::string corrupt = kTmp + "/dialogs_corrupt.json";
    freeform::test::writeText(corrupt, "{\"format\": \"freeform\", \"version\": 1, \"objects\": [{\"name\": \"c\", \"type\": \"bezier_curve\", \"points\": [[0, 0], [1");
    return corrupt;
}

/// Ctrl+O, the path typed over the dialog's text.
Json openTyped(const std::string& path)
{
    Json events = Json::array();
    events.push_back(key("O", {"ctrl"}));
    events.push_back(key("A", {"ctrl"}));
    events.push_back({{"type", "text"}, {"text", path}});
    return events;
}

void checkInside(const Json& state, int width, int height)
{
    REQUIRE(state["window"] == Json::array({width, height}));
    for (const char* name : {"Scene", "Properties", "Display"}) {
        REQUIRE(state["panels"].contains(name));
        const Json& r = state["panels"][name];
        INFO(name << " at " << r.dump() << " in " << width << " x " << height);
        CHECK(r[0].get<double>() >= 0);
        CHECK(r[1].get<double>() >= 0);
        CHECK(r[0].get<double>() + r[2].get<double>() <= width);
        CHECK(r[1].get<double>() + r[3].get<double>() <= height);
        CHECK(r[2].get<double>() >= 150); // not a strip
        CHECK(r[3].get<double>() >= 100);
    }
    const Json& p = state["panels"]["Properties"];
    CHECK(p[0].get<double>() + p[2].get<double>() == width - 8); // against the right edge
}

} // namespace

TEST_CASE("issue 12: an Open error confirmed with Enter shows, and a later Escape closes it", "[render][replay]")
{
    const std::string corrupt = corruptFile();
    Json events = openTyped(corrupt);
    events.push_back(key("Enter"));
    events.push_back({{"type", "frame"}, {"count", 3}});
    const Json state = replayState("open_enter", events);
    CHECK(state["path_dialog"] == false);
    const std::string error = state["error"].get<std::string>();
    INFO(error);
    CHECK(error.find(corrupt) != std::string::npos);
    CHECK(state["objects"] == 1); // the document is the same

    // Enter held down over frames (as in a real window), then released: the dialog stays up.
    Json held = openTyped(corrupt);
    held.push_back({{"type", "key_press"}, {"key", "Enter"}});
    held.push_back({{"type", "frame"}, {"count", 5}});
    held.push_back({{"type", "key_release"}, {"key", "Enter"}});
    held.push_back({{"type", "frame"}, {"count", 2}});
    CHECK(replayState("open_enter_held", held)["error"].get<std::string>().find(corrupt) != std::string::npos);

    // A key pressed after the dialog appeared closes it.
    Json closed = events;
    closed.push_back(key("Escape"));
    CHECK(replayState("open_enter_escape", closed)["error"] == "");
}

TEST_CASE("issue 12: the panels follow the window's size", "[render][replay]")
{
    const Json first = replayState("layout_start", Json::array({{{"type", "frame"}, {"count", 2}}}));
    checkInside(first, 1280, 800);
    for (const auto& [w, h] : {std::pair{900, 600}, std::pair{1600, 1000}, std::pair{1280, 800}}) {
        Json events = Json::array({{{"type", "frame"}, {"count", 2}}, {{"type", "resize"}, {"width", w}, {"height", h}}, {{"type", "frame"}, {"count", 2}}});
        checkInside(replayState(cat("layout_", w), events), w, h);
    }
    // Started small, then made large: the panels move to the new edges.
    Json grow = Json::array({{{"type", "resize"}, {"width", 1600}, {"height", 1000}}, {{"type", "frame"}, {"count", 2}}});
    checkInside(replayState("layout_grow", grow, "900x600"), 1600, 1000);
}

TEST_CASE("issue 12: a scroll over a panel leaves the camera alone; over the view it zooms", "[render][replay]")
{
    const double start = replayState("scroll_none", Json::array())["camera"]["distance"].get<double>();
    // Over Properties (top right, x 982..1272 at 1280 x 800) and over the view's middle.
    const Json panel = replayState("scroll_panel", Json::array({{{"type", "scroll"}, {"dy", 2}, {"x", 1100}, {"y", 200}}}));
    CHECK(panel["camera"]["distance"].get<double>() == start);
    const Json view = replayState("scroll_view", Json::array({{{"type", "scroll"}, {"dy", 2}, {"x", 640}, {"y", 400}}}));
    CHECK(view["camera"]["distance"].get<double>() < 0.9 * start); // 0.85^2 of it, about 0.72
}

TEST_CASE("issue 12: importing a mesh fits the camera to it", "[render][replay]")
{
    // An empty document whose camera looks far away from the mesh; File > Import (Ctrl+I), the
    // path typed, Enter: the camera's target is the centre of the mesh's bounding box, read here
    // from the OBJ's vertex lines (before: it stayed at (40, -30, 20)).
    const std::string mesh = std::string(FREEFORM_SOURCE_DIR) + "/data/meshes/sphere.obj";
    Eigen::AlignedBox3d box;
    std::istringstream in(freeform::test::slurp(mesh));
    for (std::string line; std::getline(in, line);)
        if (line.rfind("v ", 0) == 0) {
            std::istringstream v(line.substr(2));
            double x = 0, y = 0, z = 0;
            v >> x >> y >> z;
            box.extend(Eigen::Vector3d(x, y, z));
        }
    REQUIRE(!box.isEmpty());
    Json events = Json::array();
    events.push_back(key("I", {"ctrl"}));
    events.push_back(key("A", {"ctrl"}));
    events.push_back({{"type", "text"}, {"text", mesh}});
    events.push_back(key("Enter"));
    events.push_back({{"type", "frame"}, {"count", 2}});
    const std::string empty = kTmp + "/dialogs_empty.json";
    freeform::test::writeText(empty, R"({"format": "freeform", "version": 1, "objects": [],
      "editor": {"camera": {"target": [40, -30, 20], "distance": 200, "orientation": [1, 0, 0, 0], "fovy": 35,
                            "projection": "perspective", "orbit": "turntable"}}})");
    const Json state = replayState("import_fit", events, "1280x800", empty);
    CHECK(state["error"] == "");
    CHECK(state["objects"] == 1);
    const Json& t = state["camera"]["target"];
    const Eigen::Vector3d centre = box.center();
    INFO("target " << t.dump() << ", expected " << centre.transpose());
    CHECK(std::abs(t[0].get<double>() - centre.x()) < 1e-6);
    CHECK(std::abs(t[1].get<double>() - centre.y()) < 1e-6);
    CHECK(std::abs(t[2].get<double>() - centre.z()) < 1e-6);
}

TEST_CASE("issue 12: a tooltip shows over the Display panel's controls, and none over the view", "[render][replay]")
{
    // The Display panel's place from the state; its first rows are the shading, specular and
    // analysis combos (one frame height, 19 px, plus 4 px spacing each), below the 19-px title bar
    // and the 8-px padding. The pointer rests on each; --state reports the tooltip of the last frame.
    const Json start = replayState("tooltip_start", Json::array({{{"type", "frame"}, {"count", 2}}}));
    const Json& display = start["panels"]["Display"];
    const double x = display[0].get<double>() + 40, top = display[1].get<double>() + 19 + 8 + 9;
    const std::vector<std::pair<int, std::string>> rows = {{0, "Flat: one colour per triangle"}, {1, "Blinn-Phong"}, {2, "Reflection lines"}};
    for (const auto& [row, words] : rows) {
        const Json events = Json::array({{{"type", "move"}, {"x", x}, {"y", top + 23 * row}}, {{"type", "frame"}, {"count", 3}}});
        const std::string tip = replayState(cat("tooltip_", row), events)["tooltip"].get<std::string>();
        INFO("row " << row << ": " << tip);
        CHECK(tip.find(words) != std::string::npos);
    }
    const Json view = replayState("tooltip_view", Json::array({{{"type", "move"}, {"x", 640}, {"y", 400}}, {{"type", "frame"}, {"count", 3}}}));
    CHECK(view["tooltip"] == "");
}

} // namespace test_render_dialogs_layout
