// The det J colour map's legend and fixed range (issue 12; label "render": they need an X display).
// A sphere (data/meshes/sphere.obj) gets a lattice fitted with L, the colour map is on
// (display.analysis "scalar_map"):
//   - the legend's colour bar, found through --state, has at its two ends the map's colours at
//     the range's min and max: the first and last stops of the map (render/colour_map.h, the
//     same numbers as the shader's), rounded to 8 bits by hand: (68, 1, 84) and (253, 231, 37);
//     its values are the document's range;
//   - with the fixed range (the default), dragging a lattice corner leaves the colour of a sphere
//     vertex away from that corner as it was (within 2 levels: det J there changes by about 0.01);
//     with "auto" (the behaviour before issue 12) the same drag changes it by more than 20 levels
//     (the whole map rescales), which shows that the comparison can fail.

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "image_compare.h"
#include "interaction/replay.h"
#include "scene/scene.h"
#include "support/editor_process.h"
#include "support/process.h"

namespace test_render_colour_map {

using namespace freeform;
using namespace freeform::editor;
using Json = nlohmann::ordered_json;

namespace {

namespace fs = std::filesystem;

const std::string kTmp = FREEFORM_TEST_TMP;
constexpr int kW = 1280, kH = 800;
const Eigen::Vector3d kBack = Eigen::Vector3d(1, -2, 1).normalized(); // the camera's backward direction
constexpr double kDistance = 7;

template <typename... Parts>
std::string cat(const Parts&... parts)
{
    std::ostringstream s;
    (s << ... << parts);
    return s.str();
}

Json camera()
{
    const Eigen::Vector3d right = Eigen::Vector3d(2, 1, 0).normalized();
    Eigen::Matrix3d frame;
    frame << right, kBack.cross(right), kBack;
    const Eigen::Quaterniond q(frame);
    return {{"target", {0.0, 0.0, 0.0}}, {"distance", kDistance}, {"orientation", {q.w(), q.x(), q.y(), q.z()}},
            {"fovy", 35.0}, {"projection", "perspective"}, {"orbit", "turntable"}};
}

std::string meshPath() { return cat(FREEFORM_SOURCE_DIR, "/data/meshes/sphere.obj"); }

/// The sphere with the colour map on, the range given ("auto" or [min, max]).
std::string document(const std::string& name, const Json& range)
{
    const std::string doc = cat(kTmp, "/colour_map_", name, ".json");
    const Json j = {{"format", "freeform"},
                    {"version", 1},
                    {"objects", Json::array()},
                    {"editor",
                     {{"camera", camera()},
                      {"display", {{"analysis", "scalar_map"}, {"scalar_range", range}, {"grid", false}, {"axes", false}}},
                      {"meshes", Json::array({{{"name", "sphere"}, {"path", meshPath()}}})}}}};
    test::writeText(doc, j.dump(1));
    return doc;
}

Json move(const Eigen::Vector2d& p) { return {{"type", "move"}, {"x", p.x()}, {"y", p.y()}}; }
Json button(const char* type, const Eigen::Vector2d& p) { return {{"type", type}, {"button", "left"}, {"x", p.x()}, {"y", p.y()}}; }
Json key(const std::string& k) { return {{"type", "key"}, {"key", k}}; }
Json frames(int count) { return {{"type", "frame"}, {"count", count}}; }

/// Click on the sphere's middle (selects it), L (fits a 3 x 3 x 3 lattice, selected), optionally a
/// drag from `from` to `to`, then Escape twice (no selection: no lattice net over the mesh).
Json session(const Scene& scene, const Eigen::Vector2d* from, const Eigen::Vector2d* to)
{
    Json e = Json::array();
    const Eigen::Vector2d centre = worldToPixel(scene, kW, kH, Eigen::Vector3d::Zero());
    e.push_back(move(centre));
    e.push_back(button("press", centre));
    e.push_back(button("release", centre));
    e.push_back(frames(1));
    e.push_back(key("L"));
    e.push_back(frames(2));
    if (from) {
        e.push_back(move(*from));
        e.push_back(button("press", *from));
        e.push_back(move(0.5 * (*from + *to)));
        e.push_back(move(*to));
        e.push_back(button("release", *to));
    }
    e.push_back(key("Escape"));
    e.push_back(key("Escape"));
    e.push_back(frames(2));
    return e;
}

struct Run {
    test::RgbImage image;
    Json state;
    Json saved;
};

Run run(const std::string& doc, const std::string& name, const Json& events)
{
    const std::string file = cat(kTmp, "/colour_map_", name, ".events.json"), png = cat(kTmp, "/colour_map_", name, ".png"),
                      state = cat(kTmp, "/colour_map_", name, ".state.json"), out = cat(kTmp, "/colour_map_", name, ".out.json");
    test::writeText(file, Json{{"events", events}}.dump(1));
    fs::remove(png);
    const auto r = test::runEditorBinary(cat("'", doc, "' --replay '", file,
                                 "' --screenshot '", png, "' --state '", state, "' --save '", out, "' --size ", kW, "x", kH));
    INFO(r.err);
    REQUIRE(r.status == 0);
    Run result{test::loadPng(png), Json::parse(test::slurp(state)), Json::parse(test::slurp(out))};
    REQUIRE(result.image.width == kW);
    return result;
}

std::vector<Eigen::Vector3d> objPositions(const std::string& path)
{
    std::vector<Eigen::Vector3d> out;
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);)
        if (line.rfind("v ", 0) == 0) {
            std::istringstream s(line.substr(2));
            Eigen::Vector3d p;
            s >> p.x() >> p.y() >> p.z();
            out.push_back(p);
        }
    return out;
}

std::vector<Eigen::Vector3d> latticePoints(const Json& doc)
{
    std::vector<Eigen::Vector3d> out;
    for (const Json& o : doc["objects"])
        if (o["type"] == "lattice")
            for (const Json& p : o["points"]) out.emplace_back(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
    return out;
}

int channelDifference(const test::RgbImage& a, const test::RgbImage& b, const Eigen::Vector2d& p)
{
    const int x = static_cast<int>(std::floor(p.x())), y = static_cast<int>(std::floor(p.y()));
    int d = 0;
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c])));
    return d;
}

} // namespace

TEST_CASE("the det J legend's colour bar ends in the map's colours at its min and max", "[render][replay][ffd]")
{
    const std::string doc = document("legend", Json::array({0.5, 1.5}));
    const Scene scene = Scene::load(doc);
    const Run r = run(doc, "legend", session(scene, nullptr, nullptr));
    REQUIRE(r.state["legend"].is_object());
    CHECK(r.state["legend"]["min"].get<double>() == 0.5);
    CHECK(r.state["legend"]["max"].get<double>() == 1.5);
    const Json& rect = r.state["legend"]["rect"];
    const int x0 = static_cast<int>(rect[0].get<double>()), y0 = static_cast<int>(rect[1].get<double>());
    const int w = static_cast<int>(rect[2].get<double>()), h = static_cast<int>(rect[3].get<double>());
    REQUIRE(w >= 100);
    REQUIRE(h >= 8);
    REQUIRE(x0 + w <= kW);
    REQUIRE(y0 + h <= kH);
    const int y = y0 + h / 2;
    // 255 x the first stop (0.267, 0.005, 0.329) and the last (0.993, 0.906, 0.144), rounded.
    const unsigned char* first = r.image.at(x0, y);
    const unsigned char* last = r.image.at(x0 + w - 1, y);
    INFO("first " << int(first[0]) << " " << int(first[1]) << " " << int(first[2]) << ", last " << int(last[0]) << " "
                  << int(last[1]) << " " << int(last[2]));
    CHECK(std::abs(int(first[0]) - 68) <= 1);
    CHECK(std::abs(int(first[1]) - 1) <= 1);
    CHECK(std::abs(int(first[2]) - 84) <= 1);
    CHECK(std::abs(int(last[0]) - 253) <= 1);
    CHECK(std::abs(int(last[1]) - 231) <= 1);
    CHECK(std::abs(int(last[2]) - 37) <= 1);
    // The bar runs from dark to bright: its middle is neither end.
    const unsigned char* middle = r.image.at(x0 + w / 2, y);
    CHECK(std::abs(int(middle[1]) - 1) > 60);
    CHECK(std::abs(int(middle[1]) - 231) > 40);
    // The range was saved as it was read.
    CHECK(r.saved["editor"]["display"]["scalar_range"] == Json::array({0.5, 1.5}));
}

TEST_CASE("with a fixed det J range a lattice drag keeps the colour of an untouched vertex; with auto it does not", "[render][replay][ffd]")
{
    // The lattice's rest points (from a first run's saved document), its corner (1, 1, 1), and a
    // front-facing sphere vertex away from that corner: the one whose lattice coordinates have
    // s t u nearest 0.2 (the corner's own point has 1). Its det J changes by about 0.01 under the
    // drag (under 2 levels of 255 over the fixed range [0, 2]) while the auto range goes from
    // [1, 1] to about [1, 1.08], so there its colour moves along the map. (At the vertex farthest
    // from the corner, det J stays the minimum and both ranges give it the first colour: no test.)
    const std::string fixedDoc = document("fixed", Json::array({0.0, 2.0}));
    const Scene scene = Scene::load(fixedDoc);
    const Run fixedRest = run(fixedDoc, "fixed_rest", session(scene, nullptr, nullptr));
    const std::vector<Eigen::Vector3d> rest = latticePoints(fixedRest.saved);
    REQUIRE(rest.size() == 64);
    const Eigen::Vector3d lo = rest[0], hi = rest[63];
    const Eigen::Vector3d eye = kDistance * kBack;
    Eigen::Vector3d far = Eigen::Vector3d::Zero();
    double best = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& v : objPositions(meshPath())) {
        const Eigen::Vector3d n = v.normalized(), toEye = (eye - v).normalized();
        if (n.dot(toEye) < 0.6) continue; // well inside the silhouette
        const Eigen::Vector3d s = (v - lo).cwiseQuotient(hi - lo);
        const double distance = std::abs(s.x() * s.y() * s.z() - 0.2);
        if (distance < best) best = distance, far = v;
    }
    REQUIRE(best < 0.02);
    const Eigen::Vector2d pixel = worldToPixel(scene, kW, kH, far);
    const Eigen::Vector2d corner = worldToPixel(scene, kW, kH, hi), to = corner + Eigen::Vector2d(43, -34);

    const Run fixedMoved = run(fixedDoc, "fixed_moved", session(scene, &corner, &to));
    REQUIRE((latticePoints(fixedMoved.saved)[63] - hi).norm() > 0.1); // the corner did move
    const int fixedChange = channelDifference(fixedRest.image, fixedMoved.image, pixel);

    const std::string autoDoc = document("auto", "auto");
    const Run autoRest = run(autoDoc, "auto_rest", session(scene, nullptr, nullptr));
    const Run autoMoved = run(autoDoc, "auto_moved", session(scene, &corner, &to));
    const int autoChange = channelDifference(autoRest.image, autoMoved.image, pixel);
    INFO("vertex " << far.transpose() << " at pixel " << pixel.transpose() << ": fixed range changes it by " << fixedChange
                   << " levels, auto by " << autoChange);
    CHECK(fixedChange <= 2);
    CHECK(autoChange > 20);
    CHECK(autoMoved.saved["editor"]["display"]["scalar_range"] == "auto");
}

} // namespace test_render_colour_map
