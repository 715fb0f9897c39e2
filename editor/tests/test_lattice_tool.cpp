// The lattice (FFD) tool without a window (tools/lattice_tool.h), driven as test_tools.cpp drives
// the tools: a lattice fitted to an imported mesh (a distorted box), its points moved, and the mesh
// checked against Lattice::deform evaluated point by point (the reference for the batched FFD the
// tool uses); the deformed mesh exported; a curve in the box deformed as deformCurve does; the
// injectivity certificate; direct manipulation checked with the interaction layer's own ray/mesh
// intersection. Every operation must be one undo step that gives the document text back byte for
// byte.

#include <catch2/catch.hpp>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <freeform/core/transform.h>
#include <freeform/io/mesh_io.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "freeform/io/geometry_data.h"
#include "freeform/cad/cad_file.h"
#include "interaction/picking.h"
#include "support/process.h"
#include "support/sanitizers.h"
#include "support/tool_bench.h"
#include "tools/tools.h"

namespace test_lattice_tool {

using namespace freeform;
using namespace freeform::editor;
using namespace freeform::editor::tool_test;

namespace {

const std::string kTmp = FREEFORM_TEST_TMP;

Eigen::Vector3d boxVertex(int v) { return {kBox[v][0], kBox[v][1], kBox[v][2]}; }

Lattice latticeOf(const Scene& scene, int item)
{
    return latticeFromData(std::get<LatticeData>(scene.object(item).data));
}

} // namespace

TEST_CASE("Tools: fit a lattice to an imported mesh, move a point, the mesh follows Lattice::deform", "[tools][ffd]")
{
    const std::string obj = writeBox("ffd_box.obj");
    Bench b{Scene()};
    b.scene.importFile(obj);
    int mesh = findItem(b.scene, "ffd_box");
    REQUIRE(mesh >= 0);
    const std::string imported = b.scene.text();
    const std::size_t steps = b.scene.history().size();

    b.selection.selectItem(mesh);
    b.tools.lattice().degree[0] = 2;
    b.tools.lattice().degree[1] = 3;
    b.tools.lattice().degree[2] = 1;
    b.tools.lattice().margin = 0.1;
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_L, 0));
    const int li = findItem(b.scene, "ffd_box_lattice");
    REQUIRE(li >= 0);
    CHECK(b.selection.item == li);
    CHECK(b.scene.item(li).settings.ffd.mesh == "ffd_box");
    CHECK(b.scene.history().size() == steps + 1);
    const LatticeData& fit = std::get<LatticeData>(b.scene.object(li).data);
    CHECK(fit.degree == std::array<int, 3>{2, 3, 1});
    // Bounds x [-1.05, 1.2], y [-0.6, 0.7], z [-0.3, 0.9]; largest extent 2.25, margin 0.225.
    CHECK((fit.origin - Eigen::Vector3d(-1.275, -0.825, -0.525)).norm() < 1e-12);
    CHECK((fit.axes - Eigen::Vector3d(2.7, 1.75, 1.65).asDiagonal().toDenseMatrix()).norm() < 1e-12);
    CHECK(latticeOf(b.scene, li).isRest());
    mesh = findItem(b.scene, "ffd_box"); // document objects come before the imported meshes
    CHECK(mesh == li + 1);

    // At rest the mesh is the file's vertices, in the file's order.
    b.update();
    const PolygonMesh& shown = *b.scene.item(mesh).geometry.surface;
    REQUIRE(shown.positions.cols() == 8);
    for (int v = 0; v < 8; ++v) CHECK(Eigen::Vector3d(shown.positions.col(v)) == boxVertex(v));

    // Move control point (1, 2, 1).
    const Lattice rest = latticeOf(b.scene, li);
    const int k = rest.index(1, 2, 1);
    b.scene.setControlPoint(li, k, rest.restPoint(1, 2, 1) + Eigen::Vector3d(0.3, -0.2, 0.25));
    b.update();
    const Lattice moved = latticeOf(b.scene, li);
    CHECK_FALSE(moved.isRest());
    // Rest normals: the library's area-weighted normals of the file's quads cut into fans, as the
    // scene shows them (the corners of each triangle get its area).
    const PolygonMesh quads = readPolygonMesh(obj);
    PolygonMesh fans;
    fans.positions = quads.positions;
    for (int f = 0; f < quads.faceCount(); ++f)
        for (int k = 1; k + 1 < quads.faceSize(f); ++k)
            fans.addFace({quads.face(f)[0], quads.face(f)[k], quads.face(f)[k + 1]});
    const Eigen::Matrix3Xd restNormals = areaWeightedNormals(fans);
    const SceneItem& item = b.scene.item(mesh);
    REQUIRE(item.scalars.size() == 8);
    // The live view computes in float (the GPU's precision; exports are double, tested below):
    // coordinates of size ~1 agree to a few float roundings, 1e-6 (float epsilon is 1.2e-7).
    constexpr double kFloat = 1e-6;
    for (int v = 0; v < 8; ++v) {
        const Lattice::PointJet jet = moved.deform(boxVertex(v));
        CHECK((Eigen::Vector3d(item.geometry.surface->positions.col(v)) - jet.point).norm() < kFloat);
        const Eigen::Vector3d n = item.geometry.surface->normals.col(v);
        CHECK(std::abs(n.norm() - 1) < kFloat);
        CHECK((n - transformNormal(jet.jacobian, restNormals.col(v)).normalized()).norm() < kFloat);
        CHECK(item.scalars[static_cast<std::size_t>(v)] == Approx(jet.jacobian.determinant()).epsilon(1e-6));
    }
    CHECK((item.geometry.surface->positions - shown.positions).norm() == 0); // same storage, updated
    // Nothing changed: nothing recomputed (the mesh's revision stays).
    const int revision = b.scene.item(mesh).revision;
    b.update();
    CHECK(b.scene.item(mesh).revision == revision);

    // Reset: the rest lattice, the mesh back to the file's vertices bit for bit; one step.
    const std::string deformed = b.scene.text();
    const std::size_t before = b.scene.history().size();
    REQUIRE(b.tools.lattice().resetLattice(b.context, li));
    b.update();
    CHECK(latticeOf(b.scene, li).isRest());
    for (int v = 0; v < 8; ++v) CHECK(Eigen::Vector3d(b.scene.item(mesh).geometry.surface->positions.col(v)) == boxVertex(v));
    CHECK(b.scene.history().size() == before + 1);
    b.scene.undo();
    b.update();
    CHECK(b.scene.text() == deformed);
    for (int v = 0; v < 8; ++v)
        CHECK((Eigen::Vector3d(b.scene.item(mesh).geometry.surface->positions.col(v)) - moved.deform(boxVertex(v)).point).norm() < kFloat);

    // Undo everything: the imported document, and the mesh at rest once the lattice is gone.
    while (b.scene.history().size() > steps) b.scene.undo();
    b.update();
    mesh = findItem(b.scene, "ffd_box");
    CHECK(b.scene.text() == imported);
    for (int v = 0; v < 8; ++v) CHECK(Eigen::Vector3d(b.scene.item(mesh).geometry.surface->positions.col(v)) == boxVertex(v));
}

TEST_CASE("Tools: exportDeformed writes the file's faces with Lattice::deform's positions", "[tools][ffd]")
{
    const std::string obj = writeBox("ffd_export.obj");
    Bench b{Scene()};
    b.scene.importFile(obj);
    const int mesh = findItem(b.scene, "ffd_export");
    REQUIRE(b.tools.lattice().fitLattice(b.context, mesh));
    const int li = b.selection.item;
    Lattice lattice = latticeOf(b.scene, li);
    b.scene.setControlPoint(li, lattice.index(3, 0, 3), lattice.restPoint(3, 0, 3) + Eigen::Vector3d(-0.4, 0.1, 0.2));
    b.scene.setControlPoint(li, lattice.index(1, 2, 2), lattice.restPoint(1, 2, 2) + Eigen::Vector3d(0, 0.3, -0.1));
    b.update();
    lattice = latticeOf(b.scene, li);
    const std::string text = b.scene.text();
    const std::string out = cat(kTmp, "/ffd_export_out.obj");
    REQUIRE(b.tools.lattice().exportDeformed(b.context, li, out));
    CHECK(b.scene.text() == text);
    const PolygonMesh written = readPolygonMesh(out), input = readPolygonMesh(obj);
    REQUIRE(written.positions.cols() == 8);
    for (int v = 0; v < 8; ++v) CHECK((Eigen::Vector3d(written.positions.col(v)) - lattice.deform(boxVertex(v)).point).norm() < 1e-12);
    REQUIRE(written.faceCount() == input.faceCount());
    for (int f = 0; f < input.faceCount(); ++f) {
        REQUIRE(written.faceSize(f) == 4); // quads stay quads
        for (int c = 0; c < 4; ++c) CHECK(written.face(f)[c] == input.face(f)[c]);
    }
}

TEST_CASE("Tools: applyLatticeToObjects turns a curve inside the box into deformCurve's curve", "[tools][ffd]")
{
    const std::string obj = writeBox("ffd_apply.obj");
    Bench b{Scene()};
    b.scene.importFile(obj);
    REQUIRE(b.tools.lattice().fitLattice(b.context, findItem(b.scene, "ffd_apply")));
    const int li = b.selection.item;
    Lattice lattice = latticeOf(b.scene, li);
    b.scene.setControlPoint(li, lattice.index(2, 1, 1), lattice.restPoint(2, 1, 1) + Eigen::Vector3d(0.2, 0.3, -0.1));
    lattice = latticeOf(b.scene, li);
    Points3 inside(3, 3), outside(3, 2);
    inside << -0.5, 0, 0.6, -0.2, 0.4, -0.1, 0, 0.3, 0.5;
    outside << 5, 6, 5, 6, 5, 6;
    b.scene.addObject({"in", BezierCurveData{inside}, ""});
    b.scene.addObject({"out", BezierCurveData{outside}, ""});
    const std::string before = b.scene.text();
    const std::size_t steps = b.scene.history().size();

    REQUIRE(b.tools.lattice().applyLatticeToObjects(b.context, li));
    // One rule with `freeform ffd DOC` (docs/ffd.md, "Documents"): the curve outside the box is
    // composed too (the lattice polynomial continued), and the status line says it is outside.
    CHECK(b.tools.message().find("1 of them outside the box") != std::string::npos);
    const BezierCurve<double, 3> original(inside), composed = curveOf(b.scene, "in");
    CHECK(composed.degree() == 2 * 9); // degree d (l + m + n) for the cubic lattice
    const BezierCurve<double, 3> library = deformCurve(lattice, original);
    CHECK((composed.controlPoints() - library.controlPoints()).norm() < 1e-12);
    double worst = 0; // and point by point through the lattice map
    for (int i = 0; i <= 100; ++i)
        worst = std::max(worst, (composed.evaluate(i / 100.0) - lattice.deform(original.evaluate(i / 100.0)).point).norm());
    CHECK(worst < 1e-12);
    const BezierCurve<double, 3> outsideComposed = curveOf(b.scene, "out");
    CHECK(outsideComposed.degree() == 1 * 9);
    CHECK((outsideComposed.controlPoints() - deformCurve(lattice, BezierCurve<double, 3>(outside)).controlPoints()).norm() < 1e-9);
    CHECK(b.scene.history().size() == steps + 1);
    b.scene.undo();
    CHECK(b.scene.text() == before);
}

TEST_CASE("Tools: the certificate of a lattice: injective for a small move, folds for a crossing one", "[tools][ffd]")
{
    const std::string obj = writeBox("ffd_certify.obj");
    Bench b{Scene()};
    b.scene.importFile(obj);
    b.tools.lattice().degree[0] = b.tools.lattice().degree[1] = b.tools.lattice().degree[2] = 1;
    REQUIRE(b.tools.lattice().fitLattice(b.context, findItem(b.scene, "ffd_certify")));
    const int li = b.selection.item;
    const Lattice rest = latticeOf(b.scene, li);
    b.scene.setControlPoint(li, rest.index(1, 1, 1), rest.restPoint(1, 1, 1) + Eigen::Vector3d(0.1, 0.05, -0.1));
    b.update();
    REQUIRE(b.tools.lattice().certifyLattice(b.context, li));
    REQUIRE(b.scene.ffdLink(li));
    const auto& link = *b.scene.ffdLink(li);
    REQUIRE(link.certificate);
    CHECK(link.certificate->verdict == Verdict::CertifiedInjective);
    // The corner (1, 1, 1) pulled through the opposite corner (0, 0, 0): the trilinear map folds.
    b.scene.setControlPoint(li, rest.index(1, 1, 1), rest.restPoint(0, 0, 0) - 0.5 * (rest.restPoint(1, 1, 1) - rest.restPoint(0, 0, 0)));
    b.update();
    REQUIRE(b.tools.lattice().certifyLattice(b.context, li));
    REQUIRE(b.scene.ffdLink(li)->certificate);
    CHECK(b.scene.ffdLink(li)->certificate->verdict == Verdict::Folds);
    CHECK(b.tools.message().find("folds") != std::string::npos);
}

TEST_CASE("Tools: direct manipulation drags a point of the mesh and the lattice follows exactly (key D)", "[tools][ffd]")
{
    const std::string obj = writeBox("ffd_direct.obj");
    Bench b{Scene()};
    b.scene.camera.setView("top"); // the drag plane faces +z
    b.scene.importFile(obj);
    REQUIRE(b.tools.lattice().fitLattice(b.context, findItem(b.scene, "ffd_direct")));
    const int li = b.selection.item, mesh = findItem(b.scene, "ffd_direct");
    b.update();
    const std::string fitted = b.scene.text();
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_D, 0));

    // The grabbed point: where the ray meets the rest mesh (the picking code's ray/mesh test).
    const Eigen::Vector3d origin(0.1, 0.05, 10), down(0, 0, -1);
    const auto distance = rayMesh(origin, down, *b.scene.item(mesh).geometry.surface);
    REQUIRE(distance);
    const Eigen::Vector3d grabbed = origin + *distance * down;
    PointerEvent e = press(origin, down);
    REQUIRE(b.tools.onPointer(b.context, e));
    e.type = PointerEvent::Type::Move;
    e.rayOrigin = Eigen::Vector3d(0.3, 0.05, 10);
    b.tools.onPointer(b.context, e);
    e.rayOrigin = Eigen::Vector3d(0.4, -0.1, 10);
    b.tools.onPointer(b.context, e);
    e.type = PointerEvent::Type::Release;
    b.tools.onPointer(b.context, e);
    b.update();

    const Eigen::Vector3d target = grabbed + Eigen::Vector3d(0.3, -0.15, 0);
    CHECK((latticeOf(b.scene, li).deform(grabbed).point - target).norm() < 1e-9);
    // The mesh shows the new lattice (computed in float for the view, see above).
    const Lattice moved = latticeOf(b.scene, li);
    for (int v = 0; v < 8; ++v)
        CHECK((Eigen::Vector3d(b.scene.item(mesh).geometry.surface->positions.col(v)) - moved.deform(boxVertex(v)).point).norm() < 1e-6);
    CHECK(b.scene.history().undoLabel() == "direct manipulation");
    b.scene.undo();
    CHECK(b.scene.text() == fitted);
}

TEST_CASE("Scene: the part to export is the selected one, else the document's only one; the approximation text", "[tools][cad]")
{
    // A document of a part (plate.json), a trimmed surface (trimmed_square.json) and a curve.
    const std::string dir = std::string(FREEFORM_SOURCE_DIR) + "/data/parts/";
    Document doc = readDocument(dir + "plate.json");
    doc.objects.push_back(readDocument(dir + "trimmed_square.json").objects.at(0));
    doc.objects.push_back({"c", BezierCurveData{PointColumns::Identity(3, 2)}, ""});
    const std::string path = kTmp + "/two_parts.json";
    writeDocument(doc, path);
    Scene scene = Scene::load(path);
    REQUIRE(scene.itemCount() == 3);
    CHECK(scene.findPartItem(0) == 0);
    CHECK(scene.findPartItem(1) == 1);
    CHECK(scene.findPartItem(2) == -1); // the curve is selected: two parts to choose from
    std::string why;
    CHECK(scene.findPartItem(-1, &why) == -1);
    CHECK(why == "the document has several parts: select the one to export");
    CHECK_THROWS_WITH(scene.partItem(-1), why);
    scene.remove(0);
    CHECK(scene.findPartItem(-1) == 0); // the trimmed square, now the only one
    CHECK(scene.partItem(1) == 0);

    PartDeformReport r;
    CHECK(Scene::approximationText(r).empty());
    r.approximatedFaces = {1, 4};
    r.approximatedEdges = 3;
    r.maxApproximationError = 2.5e-7;
    r.maxDegree = 25;
    CHECK(Scene::approximationText(r) == ", 2 faces and 3 edges approximated at degree 25 (certified error <= 2.5e-07)");
}

TEST_CASE("Tools: a STEP part imported, a lattice fitted (L) previews on its mesh; apply composes it exactly; export writes STEP",
          "[tools][ffd][cad]")
{
    if (!freeform::cadFilesSupported()) {
        WARN("this build has no Open CASCADE: no STEP part to import");
        return;
    }
    const std::string step = "/usr/share/opencascade/data/step/screw.step";
    Bench b{Scene()};
    // mm: a screw of 10 faces in about 2,000 triangles; under the sanitizers 0.5 mm (the exact
    // image's faces, of degree 27, are tessellated after the apply: 50 s there at 0.05 mm).
    b.scene.display.tolerance = freeform::test::underSanitizers ? 0.5 : 0.05;
    const int part = b.scene.importFile(step);
    REQUIRE(b.scene.item(part).is(ObjectKind::Part));
    CHECK(b.scene.item(part).name == "screw");
    CHECK(std::get<PartData>(b.scene.object(part).data).faces.size() == 10);
    CHECK(partSummary(std::get<PartData>(b.scene.object(part).data)) == "10 faces, 22 edges, 14 vertices, 1 shell, 1 solid, units mm");
    CHECK(b.scene.history().undoLabel() == "import screw.step");
    const std::string imported = b.scene.text();
    b.update();
    REQUIRE(b.scene.item(part).geometry.surface);
    REQUIRE(b.scene.item(part).geometry.error.empty());
    const PolygonMesh rest = *b.scene.item(part).geometry.surface;

    // L on the part: a lattice around it, bound to it.
    b.selection.selectItem(part);
    b.tools.lattice().degree[0] = b.tools.lattice().degree[1] = b.tools.lattice().degree[2] = 3; // the default
    REQUIRE(b.tools.onKey(b.context, GLFW_KEY_L, 0));
    const int li = findItem(b.scene, "screw_lattice");
    REQUIRE(li >= 0);
    CHECK(b.scene.item(li).settings.ffd.mesh == "screw");
    const Lattice restLattice = latticeOf(b.scene, li);
    const double size = restLattice.axes().norm();
    b.scene.setControlPoint(li, restLattice.index(1, 1, 2), restLattice.restPoint(1, 1, 2) + Eigen::Vector3d(0.2, -0.1, 0.15) * size);
    b.update();
    const Lattice moved = latticeOf(b.scene, li);
    REQUIRE_FALSE(moved.isRest());

    // The preview: the part's mesh through the lattice, vertex by vertex (float, as the GPU draws).
    const int pi = findItem(b.scene, "screw");
    const PolygonMesh& shown = *b.scene.item(pi).geometry.surface;
    REQUIRE(shown.positions.cols() == rest.positions.cols());
    double previewGap = 0;
    for (Eigen::Index v = 0; v < rest.positions.cols(); v += 7)
        previewGap = std::max(previewGap, (Eigen::Vector3d(shown.positions.col(v)) - moved.deform(Eigen::Vector3d(rest.positions.col(v))).point).norm());
    CHECK(previewGap < 1e-5 * size);
    CHECK(previewGap > 0); // not the rest mesh: it moved (the check above cannot pass by accident)
    CHECK((shown.positions - rest.positions).norm() > 1e-3 * size);

    // Face points before, at the centre of each face's parameter box.
    const auto& faces = std::get<PartData>(b.scene.object(pi).data).faces;
    std::vector<std::array<double, 3>> at;
    std::vector<Eigen::Vector3d> before;
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const auto& d = faces[f].surface.domain;
        at.push_back({double(f), 0.5 * (d[0] + d[1]), 0.5 * (d[2] + d[3])});
        before.push_back(b.eval("screw", {at.back()[0], at.back()[1], at.back()[2]}).head<3>());
    }

    // Apply exactly: every face is the lattice applied to the original face (1e-9 of the size:
    // the composition in double), the lattice back at rest, one undo step.
    const std::string movedText = b.scene.text();
    const std::size_t steps = b.scene.history().size();
    REQUIRE(b.tools.lattice().applyLatticeToObjects(b.context, li));
    CHECK(b.scene.history().size() == steps + 1);
    CHECK(latticeOf(b.scene, li).isRest());
    CHECK_THAT(b.tools.message(), Catch::Contains("the lattice is back at rest around screw"));
    for (std::size_t f = 0; f < at.size(); ++f) {
        const Eigen::Vector3d after = b.eval("screw", {at[f][0], at[f][1], at[f][2]}).head<3>();
        INFO("face " << f);
        CHECK((after - moved.deform(before[f]).point).norm() < 1e-9 * size);
    }
    // The preview is now the exact part's own mesh: the lattice at rest moves nothing.
    b.update();
    const int pj = findItem(b.scene, "screw");
    REQUIRE(b.scene.item(pj).geometry.surface);
    CHECK(b.scene.item(pj).geometry.error.empty());
    // File > Export part of the exact image (edges of degree 27 under a cubic lattice): those over
    // 25 are approximated at 25 with a certified error; read back, every face centre lies within
    // that error (and 1e-9 of the size) of the exact image.
    const std::string plain = kTmp + "/screw_exact.iges";
    std::filesystem::remove(plain);
    const Scene::PartExport e = b.scene.exportPart(b.scene.partItem(-1), plain);
    CHECK(e.faces == 10);
    CHECK(e.valid);
    CHECK(e.deform.approximatedFaces.size() + static_cast<std::size_t>(e.deform.approximatedEdges) > 0);
    CHECK(e.deform.maxDegree == 25);
    CHECK(e.deform.maxApproximationError < 1e-6 * size);
    const Part exported = readCadFile(plain);
    REQUIRE(exported.faces.size() == 10);
    for (std::size_t f = 0; f < at.size(); ++f) {
        INFO("face " << f);
        CHECK((exported.faces[f].surface.point(at[f][1], at[f][2]) - moved.deform(before[f]).point).norm() <
              e.deform.maxApproximationError + 1e-9 * size);
    }
    REQUIRE(b.scene.undo());
    CHECK(b.scene.text() == movedText);

    // Export deformed (the moved lattice again): the exact composition written as STEP, which
    // Open CASCADE reads back as 10 faces whose points are the lattice's image of the originals.
    const std::string out = kTmp + "/screw_ffd.step";
    std::filesystem::remove(out);
    REQUIRE(b.tools.lattice().exportDeformed(b.context, li, out));
    CHECK_THAT(b.tools.message(), Catch::Contains("of 10 faces exact") && Catch::Contains("a valid shape"));
    const Part written = readCadFile(out);
    REQUIRE(written.faces.size() == 10);
    for (std::size_t f = 0; f < at.size(); ++f) {
        INFO("face " << f);
        CHECK((written.faces[f].surface.point(at[f][1], at[f][2]) - moved.deform(before[f]).point).norm() < 1e-9 * size);
    }
    // A mesh extension for a part: refused, nothing written.
    CHECK_FALSE(b.tools.lattice().exportDeformed(b.context, li, kTmp + "/screw_ffd.obj"));
    CHECK_THAT(b.tools.message(), Catch::Contains("a part is written as STEP"));
    CHECK_FALSE(std::filesystem::exists(kTmp + "/screw_ffd.obj"));

    // Undo back to the import gives the file's text.
    while (b.scene.history().canUndo() && b.scene.text() != imported) b.scene.undo();
    CHECK(b.scene.text() == imported);
}

TEST_CASE("Scene: a STEP file opens as a document of one part; bad files change nothing", "[cad]")
{
    const std::string screw = "/usr/share/opencascade/data/step/screw.step";
    if (!freeform::cadFilesSupported()) {
        // Without Open CASCADE: the file refused by name, an open document's part kept, nothing written.
        CHECK_THROWS_WITH(Scene::load(screw), Catch::Contains("screw.step") && Catch::Contains("without Open CASCADE"));
        Scene plate = Scene::load(std::string(FREEFORM_SOURCE_DIR) + "/data/parts/plate.json");
        const std::string text = plate.text();
        CHECK_THROWS_WITH(plate.importFile(screw), Catch::Contains("without Open CASCADE"));
        CHECK(plate.text() == text);
        CHECK_THROWS_WITH(plate.exportPart(0, kTmp + "/plate_out.step"), Catch::Contains("without Open CASCADE"));
        CHECK_FALSE(std::filesystem::exists(kTmp + "/plate_out.step"));
        return;
    }
    Scene scene = Scene::load(screw);
    REQUIRE(scene.itemCount() == 1);
    CHECK(scene.item(0).is(ObjectKind::Part));
    CHECK(scene.path().empty()); // Save asks for a .json path
    CHECK(scene.display.tolerance > 0.01); // 1/1000 of the part's size (mm), not the default 0.001
    const std::string text = scene.text();
    const std::string bad = kTmp + "/broken.step";
    std::ofstream(bad) << "ISO-10303-21;\nHEADER;\nnot a step file\n";
    CHECK_THROWS_AS(scene.importFile(bad), Error);
    CHECK(scene.text() == text);
    CHECK(scene.itemCount() == 1);
    CHECK(scene.partItem(-1) == 0);
    CHECK_THROWS_WITH(scene.exportPart(0, kTmp + "/x.json"), Catch::Contains("a part is written as STEP"));
    CHECK_FALSE(std::filesystem::exists(kTmp + "/x.json"));
}

} // namespace test_lattice_tool
