// The two front ends on one document model: for data/ffd_every_type.json (every object type: curves
// in 2D and 3D, both spline kinds, a patch, a patch complex of two patches sharing an edge, a de Boor
// surface, a subdivision cage read from a mesh file, an imported mesh, and a skewed, non-affine
// cubic lattice "L"), `freeform ffd DOC --lattice DOC -o OUT` (the binary) and the editor's
// "apply exactly to curves and patches" (LatticeTool::applyLatticeToObjects, the operation the
// lattice panel's button calls, on a Scene loaded from the file, then Scene::save as File > Save as)
// write the same objects, number for number. Both go through deformDocument (docs/ffd.md,
// "Documents"); which objects change and to what is the rule's table, listed here by hand, and the
// results are checked against point-wise deformation (Lattice::deform), an independent path.

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "freeform/io/document.h"
#include "freeform/io/geometry_data.h"
#include "freeform/io/mesh_io.h"
#include "support/process.h"
#include "tools/tools.h"

namespace test_ffd_frontends {

using namespace freeform;
using namespace freeform::editor;
using JsonDoc = nlohmann::json;

namespace {

const std::string kTmp = FREEFORM_TEST_TMP;
const std::string kDoc = std::string(FREEFORM_SOURCE_DIR) + "/data/ffd_every_type.json";

/// The object's members without the editor's display settings (which only the editor writes).
JsonDoc content(JsonDoc object)
{
    object.erase("editor");
    return object;
}

const JsonDoc& named(const JsonDoc& doc, const std::string& name)
{
    for (const JsonDoc& o : doc["objects"])
        if (o["name"] == name) return o;
    FAIL("no object " << name);
    throw 0;
}

Eigen::Vector3d point(const JsonDoc& p) { return {p[0].get<double>(), p[1].get<double>(), p[2].get<double>()}; }

/// de Casteljau on JSON points [first, first + count).
Eigen::Vector3d casteljau(const JsonDoc& pts, std::size_t first, std::size_t count, double t)
{
    std::vector<Eigen::Vector3d> w;
    for (std::size_t i = 0; i < count; ++i) w.push_back(point(pts[first + i]));
    for (std::size_t r = 1; r < count; ++r)
        for (std::size_t i = 0; i + r < count; ++i) w[i] = (1 - t) * w[i] + t * w[i + 1];
    return w[0];
}

} // namespace

TEST_CASE("freeform ffd and the editor's apply lattice write the same objects", "[editor][ffd][cli]")
{
    // The document as written back unchanged (the writer's own form: defaults spelled out).
    const JsonDoc input = JsonDoc::parse(formatDocument(readDocument(kDoc)));

    // The command line.
    const std::string cliOut = kTmp + "/ffd_frontends_cli.json";
    const auto r = test::cli("ffd " + freeform::test::shellQuote(kDoc) + " --lattice " + freeform::test::shellQuote(kDoc) + " --object L -o " + freeform::test::shellQuote(cliOut));
    INFO(r.err);
    REQUIRE(r.status == 0);
    const JsonDoc report = JsonDoc::parse(r.out);
    const JsonDoc fromCli = JsonDoc::parse(test::slurp(cliOut));

    // The editor, headless: the lattice panel's operation, then File > Save as.
    Scene scene = Scene::load(kDoc);
    Selection selection;
    Tools tools;
    ToolContext context{scene, selection, 800, 500, Eigen::Matrix4d::Identity()};
    const int li = scene.indexOf(std::string("L"));
    REQUIRE(li >= 0);
    const std::size_t steps = scene.history().size();
    const std::string before = scene.text();
    REQUIRE(tools.lattice().applyLatticeToObjects(context, li));
    INFO(tools.message());
    CHECK(scene.history().size() == steps + 1); // one undo step: undo gives the file back, redo the result
    const std::string after = scene.text();
    REQUIRE(scene.undo());
    CHECK(scene.text() == before);
    REQUIRE(scene.redo());
    CHECK(scene.text() == after);
    const std::string editorOut = kTmp + "/ffd_frontends_editor.json";
    scene.save(editorOut);
    const JsonDoc fromEditor = JsonDoc::parse(test::slurp(editorOut));

    // Number for number: every object, in the same order, with the same members and values
    // (nlohmann compares doubles with ==).
    REQUIRE(fromCli["objects"].size() == input["objects"].size());
    REQUIRE(fromEditor["objects"].size() == input["objects"].size());
    for (std::size_t i = 0; i < input["objects"].size(); ++i) {
        INFO(input["objects"][i]["name"]);
        CHECK(content(fromEditor["objects"][i]) == content(fromCli["objects"][i]));
    }
    // The imported mesh stays in the editor's document (the command line copies "editor" as it is).
    REQUIRE(fromEditor["editor"]["meshes"].size() == 1);
    CHECK(fromEditor["editor"]["meshes"][0]["name"] == "cube");

    // The rule of docs/ffd.md for this non-affine lattice, by hand: what changed and what did not.
    const std::vector<std::string> deformed = {"curve3", "spline3", "deboor3", "patch", "complex_a", "complex_b", "cage"};
    const std::vector<std::string> unchanged = {"curve2", "spline2", "deboor2", "grid", "L"};
    REQUIRE(report["objects"].size() == deformed.size());
    for (std::size_t i = 0; i < deformed.size(); ++i) {
        CHECK(report["objects"][i]["name"] == deformed[i]);
        CHECK(report["objects"][i]["inside"] == true);
        CHECK(content(named(fromCli, deformed[i])) != content(named(input, deformed[i])));
    }
    REQUIRE(report["skipped"].size() == unchanged.size());
    for (std::size_t i = 0; i < unchanged.size(); ++i) {
        CHECK(report["skipped"][i]["name"] == unchanged[i]);
        CHECK(content(named(fromCli, unchanged[i])) == content(named(input, unchanged[i])));
    }
    CHECK(named(fromCli, "deboor3")["type"] == "bezier_spline");
    CHECK(named(fromCli, "deboor3")["degree"] == 27); // 3 (3 + 3 + 3)
    CHECK(named(fromCli, "patch")["degree"] == JsonDoc::array({18, 18}));
    CHECK(tools.message().find("deformed 7 object(s) exactly, left 4") == 0);

    // Against point-wise deformation through the lattice (inside the box the composition is exact).
    const Lattice lattice = latticeFromData(std::get<LatticeData>(scene.object(li).data));
    double worst = 0;
    const JsonDoc& c0 = named(input, "curve3")["points"];
    const JsonDoc& c1 = named(fromEditor, "curve3")["points"];
    REQUIRE(c1.size() == 28);
    for (int k = 0; k <= 50; ++k) {
        const double t = k / 50.0;
        worst = std::max(worst, (casteljau(c1, 0, 28, t) - lattice.deform(casteljau(c0, 0, 4, t)).point).norm());
    }
    CHECK(worst < 1e-11);
    // The patch complex stays watertight: complex_a's row u = 1 and complex_b's row u = 0 were one
    // curve and are still one.
    const JsonDoc& a = named(fromEditor, "complex_a")["points"];
    const JsonDoc& b = named(fromEditor, "complex_b")["points"];
    const std::size_t rows = a.size(), cols = a[0].size();
    REQUIRE(cols == b[0].size());
    for (std::size_t j = 0; j < cols; ++j) CHECK((point(a[rows - 1][j]) - point(b[0][j])).norm() < 1e-12);
    // The cage from cages/cube.obj is written inline, each vertex moved point-wise.
    const JsonDoc& cage = named(fromEditor, "cage");
    CHECK_FALSE(cage.contains("mesh"));
    const PolygonMesh cube = readPolygonMesh(std::string(FREEFORM_SOURCE_DIR) + "/data/cages/cube.obj");
    REQUIRE(cage["vertices"].size() == static_cast<std::size_t>(cube.positions.cols()));
    for (Eigen::Index v = 0; v < cube.positions.cols(); ++v)
        CHECK((point(cage["vertices"][static_cast<std::size_t>(v)]) - lattice.deform(Eigen::Vector3d(cube.positions.col(v))).point)
                  .norm() < 1e-12);
}

} // namespace test_ffd_frontends
