// The document layer against the command line (eval, continuity, convert --to, tessellate, ffd DOC;
// written when each command had its own bridge, kept now that they call the layer): the same
// document through both must give the same numbers bit for bit. (Where the layer's rule deliberately differs: subdivision cages and
// affine lattices, docs/ffd.md; those objects are left out here.)

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "freeform/document/document.h"
#include "freeform/io/geometry_data.h"
#include "support/process.h"

namespace test_cli_document_layer {

using freeform::test::cli;
using freeform::test::writeText;
using Json = nlohmann::json;
using namespace freeform;

namespace {

std::string tmp(const std::string& name) { return std::string(FREEFORM_TEST_TMP) + "/" + name; }

const char* kDoc = R"({"format": "freeform", "version": 1, "objects": [
  {"name": "c2", "type": "bezier_curve", "points": [[0,0],[1,2],[3,2],[4,0]]},
  {"name": "c3", "type": "bezier_curve", "points": [[0.2,0.2,0.2],[0.6,0.6,0.6],[0.8,0.2,0.8]]},
  {"name": "s2", "type": "bezier_spline", "degree": 1, "closed": false, "points": [[0,0],[1,0],[1,2]], "intervals": [1, 2]},
  {"name": "s3", "type": "bezier_spline", "degree": 3, "closed": true,
   "points": [[0.1,0.1,0.1],[0.5,0.2,0.9],[0.6,0.6,0.6],[0.7,1.0,0.3],[0.9,0.8,0.9],[0.3,0.9,0.2]], "intervals": [1, 0.5]},
  {"name": "d3", "type": "deboor_spline", "degree": 3, "end": "clamped",
   "points": [[0.1,0.1,0.1],[0.7,0.1,0.1],[0.7,0.7,0.1],[0.1,0.7,0.7],[0.4,0.4,0.9]], "intervals": [1, 2]},
  {"name": "p", "type": "bezier_surface", "degree": [1, 2], "points": [[[0.1,0.1,0.2],[0.2,0.5,0.9],[0.1,0.9,0.3]], [[0.9,0.2,0.8],[0.8,0.6,0.1],[0.9,0.9,0.7]]]},
  {"name": "g", "type": "deboor_surface", "degree": [3, 3], "end": ["open", "closed"],
   "points": [[[0,0,0],[0,1,0],[0,2,0],[0,3,1]],[[1,0,0],[1,1,1],[1,2,2],[1,3,3]],
              [[2,0,0],[2,1,2],[2,2,4],[2,3,6]],[[3,0,0],[3,1,3],[3,2,6],[3,3,9]]]},
  {"name": "out", "type": "bezier_curve", "points": [[0.5,0.5,0.5],[1.5,0.5,0.5]]},
  {"name": "L", "type": "lattice", "degree": [1, 1, 2], "origin": [0, 0, 0], "axes": [[1,0,0],[0,1,0],[0,0,1]],
   "points": [[0,0,0],[0,0,0.5],[0,0,1],[0,1,0],[0,1,0.5],[0,1,1],[1,0,0],[1,0,0.5],[1,0,1],[1,1,0],[1,1.1,0.5],[1.1,1.2,1.3]],
   "outside": "clamp"}
]})";

std::string docPath()
{
    const std::string path = tmp("layer_doc.json");
    writeText(path, kDoc);
    return path;
}

Json run(const std::string& args)
{
    const auto r = cli(args);
    INFO(args << "\n" << r.err);
    REQUIRE(r.status == 0);
    return Json::parse(r.out);
}

void checkVector(const Json& j, const Eigen::VectorXd& v)
{
    REQUIRE(j.size() == static_cast<std::size_t>(v.size()));
    for (Eigen::Index i = 0; i < v.size(); ++i) CHECK(j[static_cast<std::size_t>(i)].get<double>() == v[i]);
}

} // namespace

TEST_CASE("evaluate equals freeform eval bit for bit", "[cli][document]")
{
    const std::string path = docPath();
    const TypedDocument doc = TypedDocument::read(path);
    struct Case {
        std::string object, at;
        std::vector<double> values;
        int order;
    };
    const std::vector<Case> cases = {
        {"c2", "0.3", {0.3}, 3},           {"c3", "0.7", {0.7}, 2},        {"s2", "2.5", {2.5}, 1},
        {"s3", "1.2", {1.2}, 3},           {"d3", "2.25", {2.25}, 3},      {"p", "0.25,0.6", {0.25, 0.6}, 2},
        {"g", "0.5,2.7", {0.5, 2.7}, 2},   {"L", "0.2,0.7,0.9", {0.2, 0.7, 0.9}, 1},
    };
    for (const Case& c : cases) {
        INFO(c.object);
        const Json j = run("eval " + freeform::test::shellQuote(path) + " --object " + c.object + " --at " + c.at + " --derivatives " + std::to_string(c.order));
        const Evaluation e = evaluate(doc, doc.object(c.object), c.values, c.order);
        checkVector(j["point"], e.point);
        if (e.normal) checkVector(j["normal"], *e.normal);
        if (e.keys.empty()) {
            REQUIRE(j["derivatives"].size() == e.derivatives.size());
            for (std::size_t k = 0; k < e.derivatives.size(); ++k) checkVector(j["derivatives"][k], e.derivatives[k]);
        } else if (c.object == "L") {
            checkVector(j["derivatives"][0]["s"], e.derivatives[0]);
            checkVector(j["derivatives"][0]["u"], e.derivatives[2]);
            CHECK(j["derivatives"][0]["det"].get<double>() == *e.det);
        } else {
            for (std::size_t k = 0; k < e.keys.size(); ++k) checkVector(j["derivatives"][e.keys[k]], e.derivatives[k]);
        }
    }
}

TEST_CASE("continuity equals freeform continuity", "[cli][document]")
{
    const std::string path = docPath();
    const TypedDocument doc = TypedDocument::read(path);
    for (const std::string name : {"s2", "s3", "d3"}) {
        const Json j = run("continuity " + freeform::test::shellQuote(path) + " --object " + name);
        const auto joints = continuity(doc, doc.object(name));
        REQUIRE(j["joints"].size() == joints.size());
        for (std::size_t i = 0; i < joints.size(); ++i) {
            CHECK(j["joints"][i]["joint"] == joints[i].joint);
            CHECK(j["joints"][i]["t"].get<double>() == joints[i].t);
            CHECK(j["joints"][i]["C"] == joints[i].C);
            CHECK(j["joints"][i]["G"] == joints[i].G);
            CHECK(j["joints"][i]["jumps"].get<std::vector<double>>() == joints[i].jumps);
        }
    }
}

TEST_CASE("convertSpline equals freeform convert --to", "[cli][document]")
{
    const std::string path = docPath();
    TypedDocument doc = TypedDocument::read(path);
    run("convert " + freeform::test::shellQuote(path) + " --object d3 --to bezier_spline -o " + freeform::test::shellQuote(tmp("layer_conv1.json")));
    convertSpline(doc, doc.object("d3").id(), "bezier_spline");
    CHECK(formatDocument(readDocument(tmp("layer_conv1.json"))) == formatDocument(doc.toDocument()));
    run("convert " + freeform::test::shellQuote(tmp("layer_conv1.json")) + " --object d3 --to deboor_spline --end open -o " + freeform::test::shellQuote(tmp("layer_conv2.json")));
    convertSpline(doc, doc.object("d3").id(), "deboor_spline", EndCondition::Open);
    CHECK(formatDocument(readDocument(tmp("layer_conv2.json"))) == formatDocument(doc.toDocument()));
}

TEST_CASE("tessellation of surfaces equals freeform tessellate", "[cli][document]")
{
    const std::string path = docPath();
    const TypedDocument doc = TypedDocument::read(path);
    const Json j = run("tessellate " + freeform::test::shellQuote(path) + " --segments 5 -o " + freeform::test::shellQuote(tmp("layer_tess.obj")));
    TessellationOptions options;
    options.segmentsU = options.segmentsV = 5;
    TessellationReport report;
    const PolygonMesh mesh = tessellate(documentPatches(doc), options, &report);
    CHECK(j["patches"] == documentPatches(doc).patches.size());
    CHECK(j["vertices"] == mesh.vertexCount());
    CHECK(j["triangles"] == mesh.faceCount());
    CHECK(j["error_bound"].get<double>() == report.errorBound);
}

TEST_CASE("deformDocument equals freeform ffd DOC: the document and the report", "[cli][document][ffd]")
{
    const std::string path = docPath();
    const Json report = run("ffd " + freeform::test::shellQuote(path) + " --lattice " + freeform::test::shellQuote(path) + " -o " + freeform::test::shellQuote(tmp("layer_ffd.json")));
    TypedDocument doc = TypedDocument::read(path);
    const Lattice lattice = latticeFromData(std::get<LatticeData>(doc.object("L").data()));
    const DeformDocumentReport r = deformDocument(doc, lattice);
    CHECK(formatDocument(readDocument(tmp("layer_ffd.json"))) == formatDocument(doc.toDocument()));
    REQUIRE(report["objects"].size() == r.objects.size());
    for (std::size_t i = 0; i < r.objects.size(); ++i) {
        const Json& o = report["objects"][i];
        CHECK(o["name"] == r.objects[i].name);
        CHECK(o["from"] == r.objects[i].from);
        CHECK(o["type"] == r.objects[i].type);
        CHECK(o["inside"] == r.objects[i].inside);
        if (r.objects[i].degree.size() == 1) CHECK(o["degree"] == r.objects[i].degree[0]);
        else CHECK(o["degree"].get<std::vector<int>>() == r.objects[i].degree);
    }
    REQUIRE(report["skipped"].size() == r.skipped.size());
    for (std::size_t i = 0; i < r.skipped.size(); ++i) {
        CHECK(report["skipped"][i]["name"] == r.skipped[i].name);
        CHECK(report["skipped"][i]["type"] == r.skipped[i].type);
        CHECK(report["skipped"][i]["reason"] == r.skipped[i].reason);
    }
    CHECK(report["certificate"]["min_coefficient"].get<double>() == r.certificate.minCoefficient);
}

} // namespace test_cli_document_layer
