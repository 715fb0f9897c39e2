// Trimmed surfaces and parts as document objects (docs/format.md, "Trimmed surfaces and parts"):
// data/parts/plate.json (a 40 x 30 x 10 mm plate with a 6 mm hole, written by Open CASCADE and
// converted by `freeform convert`) and data/parts/trimmed_square.json (the unit square with a hole
// of radius 1/4, written by hand). Checked against hand-computed values: the hole's circle, its
// derivatives and outward normal, the plate's volume, the square's area, affine images; and the
// reader's strictness, one message per field.

#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <numbers>
#include <string>

#include "freeform/core/error.h"
#include "freeform/document/document.h"
#include "freeform/document/object_data.h"

namespace test_document_part {

using namespace freeform;

namespace {

const std::string dataDir = std::string(FREEFORM_SOURCE_DIR) + "/data/parts/";

TypedDocument plate() { return TypedDocument::read(dataDir + "plate.json"); }

/// The signed volume of a closed triangle mesh (divergence theorem).
double meshVolume(const PolygonMesh& m)
{
    double v = 0;
    for (int f = 0; f < m.faceCount(); ++f) {
        const Eigen::Vector3d a = m.positions.col(m.faceVertices[3 * f]);
        const Eigen::Vector3d b = m.positions.col(m.faceVertices[3 * f + 1]);
        const Eigen::Vector3d c = m.positions.col(m.faceVertices[3 * f + 2]);
        v += a.dot(b.cross(c)) / 6;
    }
    return v;
}

double meshArea(const PolygonMesh& m)
{
    double area = 0;
    for (int f = 0; f < m.faceCount(); ++f) {
        const Eigen::Vector3d a = m.positions.col(m.faceVertices[3 * f]);
        const Eigen::Vector3d b = m.positions.col(m.faceVertices[3 * f + 1]);
        const Eigen::Vector3d c = m.positions.col(m.faceVertices[3 * f + 2]);
        area += 0.5 * (b - a).cross(c - a).norm();
    }
    return area;
}

int holeFace(const Part& part)
{
    for (std::size_t f = 0; f < part.faces.size(); ++f)
        if (part.faces[f].surfaceKind == "cylinder") return static_cast<int>(f);
    return -1;
}

/// The document text of a part with one edit applied to its first object's JSON text.
std::string edited(const std::string& text, const std::string& from, const std::string& to)
{
    const std::size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    return text.substr(0, at) + to + text.substr(at + from.size());
}

} // namespace

TEST_CASE("a part document reads into the part it was written from, and writes back the same text", "[part]")
{
    const std::string text = readFile(dataDir + "plate.json");
    const TypedDocument doc(parseDocument(text, "plate.json"));
    REQUIRE(doc.objects().size() == 1);
    const TypedObject& o = doc.objects()[0];
    CHECK(o.type() == "part");
    const Part& part = std::get<Part>(o.geometry());
    CHECK(part.faces.size() == 7);
    CHECK(part.edges.size() == 15);
    CHECK(part.vertices.size() == 10);
    CHECK(part.shells.size() == 1);
    CHECK(part.solids.size() == 1);
    CHECK(part.units == "mm");
    const PartCheck check = checkPart(part);
    CHECK(check.closed);
    CHECK(check.openEdges == 0);
    CHECK(check.gapsOverTolerance == 0);
    // The box is the plate's, to the bit where the planes are (the hole's arcs lie inside).
    const Box<double, 3> box = part.bounds();
    CHECK(box.min() == Eigen::Vector3d(0, 0, 0));
    CHECK(box.max() == Eigen::Vector3d(40, 30, 10));
    // Written again: the same text (the file is formatDocument's), and toData inverts the build.
    CHECK(formatDocument(doc.toDocument()) == text);
    CHECK(formatDocument(Document{{DocumentObject{"plate", toData(part), ""}}, "", ""}) == text);
}

TEST_CASE("the hole of the plate is the exact circle: points, derivatives, outward normals", "[part]")
{
    const TypedDocument doc = plate();
    const TypedObject& o = doc.objects()[0];
    const Part& part = std::get<Part>(o.geometry());
    const int f = holeFace(part);
    REQUIRE(f >= 0);
    const TrimmedSurface& hole = part.faces[static_cast<std::size_t>(f)].surface;
    const Box<double, 2>& box = hole.domain();
    // The cylinder's angle u runs over a full turn, its v along the axis over the plate's 10 mm.
    CHECK(box.max().x() - box.min().x() == Approx(2 * std::numbers::pi).epsilon(1e-13)); // 2 pi as the STEP file rounds it
    for (int i = 0; i <= 16; ++i)
        for (int j = 0; j <= 4; ++j) {
            const double u = box.min().x() + (box.max().x() - box.min().x()) * i / 16;
            const double v = box.min().y() + (box.max().y() - box.min().y()) * j / 4;
            const Evaluation e = evaluate(doc, o, {static_cast<double>(f), u, v}, 1);
            const Eigen::Vector3d p = e.point;
            const Eigen::Vector2d r(p.x() - 20, p.y() - 15);
            // On the circle of radius 6 about (20, 15), at the angle u (the half-angle map is exact).
            CHECK(std::abs(r.norm() - 6) <= 1e-13);
            CHECK(std::abs(std::remainder(std::atan2(r.y(), r.x()) - u, 2 * std::numbers::pi)) <= 1e-13);
            CHECK(p.z() >= -1e-12);
            CHECK(p.z() <= 10 + 1e-12);
            // dP/du = 6 (-sin u, cos u, 0); the outward normal of the solid points into the hole.
            REQUIRE(e.derivatives.size() == 2);
            CHECK((e.derivatives[0] - Eigen::Vector3d(-6 * std::sin(u), 6 * std::cos(u), 0)).norm() <= 1e-12);
            CHECK(std::abs(std::abs(e.derivatives[1].z()) - 1) <= 1e-13);
            CHECK((*e.normal + Eigen::Vector3d(r.x(), r.y(), 0) / 6).norm() <= 1e-12);
            CHECK(e.face == f);
            CHECK(e.trim.has_value());
        }
    // Parameters outside the face's box, a face that does not exist, an order above 1: refused.
    CHECK_THROWS_WITH(evaluate(doc, o, {static_cast<double>(f), box.min().x() - 1, box.min().y()}, 0),
                      Catch::Contains("outside the face's domain"));
    CHECK_THROWS_WITH(evaluate(doc, o, {7, 0, 0}, 0), Catch::Contains("FACE must be an integer in 0..6"));
    CHECK_THROWS_WITH(evaluate(doc, o, {0.5, 0, 0}, 0), Catch::Contains("FACE must be an integer"));
    CHECK_THROWS_WITH(evaluate(doc, o, {static_cast<double>(f), box.min().x(), box.min().y()}, 2),
                      Catch::Contains("first derivatives only"));
}

TEST_CASE("the plate's mesh is closed and holds the plate's volume within the bound", "[part]")
{
    const TypedDocument doc = plate();
    const TypedObject& o = doc.objects()[0];
    ObjectTessellation settings;
    settings.tolerance = 0.01;
    TessellationReport report;
    const std::optional<PolygonMesh> mesh = tessellateObject(o, settings, &report);
    REQUIRE(mesh);
    CHECK(report.errorBound <= 0.01);
    // Every edge in two triangles, once each way (a closed, consistently oriented mesh).
    std::map<std::pair<int, int>, int> directed;
    for (int f = 0; f < mesh->faceCount(); ++f)
        for (int k = 0; k < 3; ++k) ++directed[{mesh->faceVertices[3 * f + k], mesh->faceVertices[3 * f + (k + 1) % 3]}];
    for (const auto& [edge, count] : directed) {
        CHECK(count == 1);
        CHECK(directed.count({edge.second, edge.first}) == 1);
    }
    // 40 x 30 x 10 less the hole pi 6^2 10; every mesh point lies within the bound of the surface,
    // so the volumes differ by at most the bound times the area (plus its square's share).
    const double volume = 12000 - 360 * std::numbers::pi;
    const double area = 2 * (1200 - 36 * std::numbers::pi) + 2 * (40 + 30) * 10 + 2 * std::numbers::pi * 6 * 10;
    CHECK(std::abs(meshVolume(*mesh) - volume) <= report.errorBound * area * 1.01);
    CHECK(meshVolume(*mesh) > 0); // outward triangles

    // Split by face (the editor's shading): every planar face's vertices carry its own normal, the
    // hole's point to its axis; the same triangles, more vertices (each edge's once per face).
    settings.splitFaces = true;
    const std::optional<PolygonMesh> split = tessellateObject(o, settings);
    REQUIRE(split);
    CHECK(split->faceCount() == mesh->faceCount());
    CHECK(split->vertexCount() > mesh->vertexCount());
    REQUIRE(split->normals.cols() == split->vertexCount());
    int planar = 0;
    for (int v = 0; v < split->vertexCount(); ++v) {
        const Eigen::Vector3d n = split->normals.col(v), p = split->positions.col(v);
        const bool side = std::abs(std::hypot(p.x() - 20, p.y() - 15) - 6) <= 1e-9 && p.z() > 1e-9 && p.z() < 10 - 1e-9;
        if (side) continue; // the hole's wall: a smooth average of its own triangles
        const int axes = (std::abs(n.x()) > 1 - 1e-12) + (std::abs(n.y()) > 1 - 1e-12) + (std::abs(n.z()) > 1 - 1e-12);
        const bool onHole = std::abs(std::hypot(p.x() - 20, p.y() - 15) - 6) <= 1e-9;
        if (!onHole) {
            CHECK(axes == 1);
            ++planar;
        }
    }
    CHECK(planar > 0);
}

TEST_CASE("a lattice moves a part exactly: affine images and the lattice at every face point", "[part]")
{
    TypedDocument doc = plate();
    const Part before = std::get<Part>(doc.objects()[0].geometry());
    // An affine lattice: x' = 2x + 0.5z, y' = y, z' = z - 0.1y, written on a degree (1, 1, 1) box.
    const Eigen::Vector3d origin(-1, -1, -1), size(42, 32, 12);
    auto affine = [](const Eigen::Vector3d& p) { return Eigen::Vector3d(2 * p.x() + 0.5 * p.z(), p.y(), p.z() - 0.1 * p.y()); };
    auto latticeOf = [&](auto map) {
        Lattice::Points points(3, 8);
        for (int i = 0; i < 2; ++i)
            for (int j = 0; j < 2; ++j)
                for (int k = 0; k < 2; ++k)
                    points.col((i * 2 + j) * 2 + k) = map(Eigen::Vector3d(origin + Eigen::Vector3d(i * size.x(), j * size.y(), k * size.z())));
        return Lattice({1, 1, 1}, origin, size.asDiagonal(), points, OutsidePolicy::Keep);
    };
    {
        TypedDocument moved = doc;
        const DeformDocumentReport report = deformDocument(moved, latticeOf(affine));
        REQUIRE(report.objects.size() == 1);
        CHECK(report.objects[0].exact);
        const Part& after = std::get<Part>(moved.objects()[0].geometry());
        for (std::size_t f = 0; f < before.faces.size(); ++f) {
            const TrimmedSurface& a = before.faces[f].surface;
            const TrimmedSurface& b = after.faces[f].surface;
            CHECK(b.surface().nurbs.degreeU() == a.surface().nurbs.degreeU()); // no degree rise
            CHECK(b.surface().nurbs.degreeV() == a.surface().nurbs.degreeV());
            CHECK(after.faces[f].surfaceKind == (before.faces[f].surfaceKind == "plane" ? "plane" : "bspline"));
            for (int s = 0; s <= 4; ++s) {
                const Eigen::Vector2d uv = a.domain().min() + a.domain().sizes().cwiseProduct(Eigen::Vector2d(s / 4.0, (4 - s) / 4.0));
                CHECK((b.point(uv.x(), uv.y()) - affine(a.point(uv.x(), uv.y()))).norm() <= 1e-12 * 100);
            }
        }
    }
    {
        // A bent lattice (degree 2 along x, the middle row raised): every face point goes where the
        // lattice sends it.
        const Lattice straight = latticeOf([](const Eigen::Vector3d& p) { return p; });
        Lattice::Points points(3, 12);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 2; ++j)
                for (int k = 0; k < 2; ++k)
                    points.col((i * 2 + j) * 2 + k) =
                        origin + Eigen::Vector3d(i * size.x() / 2, j * size.y(), k * size.z() + (i == 1 ? 5 : 0));
        const Lattice bent({2, 1, 1}, origin, size.asDiagonal(), points, OutsidePolicy::Keep);
        (void)straight;
        TypedDocument moved = doc;
        const DeformDocumentReport report = deformDocument(moved, bent);
        REQUIRE(report.objects.size() == 1);
        CHECK(report.objects[0].degree == std::vector<int>{8}); // bilinear faces: 2 (2+1+1); the hole's arcs 2 * 4
        const Part& after = std::get<Part>(moved.objects()[0].geometry());
        for (std::size_t f = 0; f < before.faces.size(); ++f) {
            const TrimmedSurface& a = before.faces[f].surface;
            const TrimmedSurface& b = after.faces[f].surface;
            for (int s = 0; s <= 6; ++s) {
                const Eigen::Vector2d uv = a.domain().min() + a.domain().sizes().cwiseProduct(Eigen::Vector2d(s / 6.0, (s * 5 % 7) / 6.0));
                CHECK((b.point(uv.x(), uv.y()) - bent.deform(a.point(uv.x(), uv.y())).point).norm() <= 1e-12 * 100);
            }
        }
    }
}

TEST_CASE("a trimmed surface object: the hole classified, its area meshed, its points mapped", "[part]")
{
    const TypedDocument doc = TypedDocument::read(dataDir + "trimmed_square.json");
    const TypedObject& o = doc.object("square");
    CHECK(o.type() == "trimmed_surface");
    CHECK(evaluate(doc, o, {0.5, 0.5}, 0).trim == TrimClass::Outside);  // the hole's centre
    CHECK(evaluate(doc, o, {0.1, 0.2}, 0).trim == TrimClass::Inside);
    CHECK(evaluate(doc, o, {0.75, 0.5}, 0).trim == TrimClass::Boundary); // on the circle
    CHECK(evaluate(doc, o, {0.5 + 0.25 * std::cos(1.0), 0.5 + 0.25 * std::sin(1.0)}, 0).trim == TrimClass::Boundary);
    CHECK(evaluate(doc, o, {0.5 + 0.26 * std::cos(1.0), 0.5 + 0.26 * std::sin(1.0)}, 0).trim == TrimClass::Inside);
    CHECK(evaluate(doc, o, {0.5 + 0.24 * std::cos(1.0), 0.5 + 0.24 * std::sin(1.0)}, 0).trim == TrimClass::Outside);
    const Evaluation e = evaluate(doc, o, {0.1, 0.2}, 1);
    CHECK(e.point == Eigen::Vector3d(0.1, 0.2, 0).cast<double>());
    CHECK(*e.normal == Eigen::Vector3d(0, 0, 1));
    // The mesh covers the square less the disc: 1 - pi/16, within the bound times the trim length.
    ObjectTessellation settings;
    settings.tolerance = 1e-3;
    TessellationReport report;
    const std::optional<PolygonMesh> mesh = tessellateObject(o, settings, &report);
    REQUIRE(mesh);
    CHECK(report.errorBound <= 1e-3);
    CHECK(std::abs(meshArea(*mesh) - (1 - std::numbers::pi / 16)) <= report.errorBound * (4 + std::numbers::pi / 2));
    // Through a lattice that doubles x: the control points of its plane doubled, the trims kept.
    TypedDocument moved = doc;
    Lattice::Points points(3, 8);
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
            for (int k = 0; k < 2; ++k) points.col((i * 2 + j) * 2 + k) = Eigen::Vector3d(4.0 * i - 1, 2.0 * j - 0.5, 2.0 * k - 1);
    deformDocument(moved, Lattice({1, 1, 1}, Eigen::Vector3d(-0.5, -0.5, -1), Eigen::Vector3d(2, 2, 2).asDiagonal(), points,
                                  OutsidePolicy::Keep));
    const auto& data = std::get<TrimmedSurfaceData>(moved.object("square").data());
    const auto& old = std::get<TrimmedSurfaceData>(o.data());
    CHECK(data.surface.points.row(0) == 2 * old.surface.points.row(0));
    CHECK(data.surface.points.bottomRows(2) == old.surface.points.bottomRows(2));
    CHECK(formatDocument(Document{{DocumentObject{"l", ObjectData(TrimmedSurfaceData{old.surface, old.map, old.domain, data.loops}), ""}}, "", ""}) ==
          formatDocument(Document{{DocumentObject{"l", ObjectData(old), ""}}, "", ""})); // the loops as they were, no edges
}

TEST_CASE("bad part and trimmed surface fields: one error naming the member and field", "[part]")
{
    const std::string square = readFile(dataDir + "trimmed_square.json");
    const std::string plateText = readFile(dataDir + "plate.json");
    struct Case {
        const std::string* text;
        std::string from, to, message;
    };
    const Case cases[] = {
        {&square, "\"domain\": [0, 1, 0, 1]", "\"domain\": [1, 0, 0, 1]", "field \"domain\": u0 must be below u1"},
        {&square, "\"domain\": [0, 1, 0, 1]", "\"domain\": [0, 2, 0, 1]", "outside the knots' domain"},
        {&square, "\"range\": [0, 4]", "\"range\": [0, 5]", "loops[1][0]: field \"range\": parameter 5"},
        {&square, "\"range\": [0, 4]", "\"range\": [0, 4], \"edge\": 0", "loops[1][0]: field \"edge\": unknown field"},
        {&square, "\"range\": [0, 4]", "\"range\": [0, 4], \"map\": {\"kind\": \"half_angle\", \"start\": 0, \"span\": 4, \"spans\": 1}",
         "field \"span\": must be in (0, pi]"},
        {&square, "\"range\": [0, 4]", "\"range\": [0, 4], \"map\": {\"kind\": \"spiral\"}", "\"spiral\" is not one of"},
        {&square, "\"loops\": [", "\"loops\": [[], ", "field \"loops[0]\": expected a non-empty array of trim curves"},
        {&square, "\"weights\": [1, 0.7071067811865476,", "\"weights\": [1, -0.7071067811865476,", "weight must be positive"},
        {&plateText, "\"shells\": [\n        [\n          0,", "\"shells\": [\n        [\n          9,", "face 9 is out of range 0..6"},
        {&plateText, "\"solids\": [\n        [\n          0", "\"solids\": [\n        [\n          3", "shell 3 is out of range 0..0"},
        {&plateText, "\"edge\": 0", "\"edge\": 15", "field \"edge\": edge 15 is out of range 0..14"},
        {&plateText, "\"vertices\": [\n            0,", "\"vertices\": [\n            10,", "edges[0]: field \"vertices[0]\": vertex 10 is out of range"},
        {&plateText, "\"units\": \"mm\"", "\"units\": \"\"", "field \"units\": is empty"},
        {&plateText, "\"tolerance\": 1e-07", "\"tolerance\": -1", "field \"tolerance\": must be >= 0"},
        {&plateText, "\"type\": \"part\",", "\"type\": \"part\", \"colour\": 1,", "field \"colour\": unknown field"},
    };
    for (const Case& c : cases) {
        INFO(c.to);
        const std::string text = edited(*c.text, c.from, c.to);
        try {
            const TypedDocument doc(parseDocument(text, "bad.json"));
            FAIL("accepted");
        } catch (const Error& e) {
            const std::string what = e.what();
            CHECK(what.rfind("bad.json: object ", 0) == 0);
            CHECK(what.find(c.message) != std::string::npos);
            if (what.find(c.message) == std::string::npos) WARN(what);
        }
    }
}

} // namespace test_document_part
