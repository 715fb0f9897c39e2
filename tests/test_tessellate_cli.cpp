// `freeform tessellate` with the options of issue 15: the measured deviations in the report (at
// most the certified bound, and within 2x of it on the teapot), --refinement, --max-triangles (a
// patch a million units large is refused with the estimate, exit 1, no output file), bad usage.
// Needs the freeform-cli target (built with everything; FREEFORM_CLI names it).

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>

#include "support/cli_errors.h"
#include "support/process.h"
#include "support/sanitizers.h"

namespace test_tessellate_cli {

using freeform::test::cli;
using freeform::test::requireError;
using freeform::test::writeText;
using Json = nlohmann::json;

namespace {
std::string tmp(const std::string& name) { return std::string(FREEFORM_TEST_TMP) + "/" + name; }

const std::string kTeapot = std::string(FREEFORM_SOURCE_DIR) + "/data/teapot.bpt";

} // namespace

TEST_CASE("tessellate reports the measured deviations beside the certified bound", "[cli][tessellate][local]")
{
    const std::string out = tmp("tess_local.obj");
    const auto local = cli("tessellate " + freeform::test::shellQuote(kTeapot) + " -o " + freeform::test::shellQuote(out) + " --tolerance 1e-3");
    INFO(local.err);
    REQUIRE(local.status == 0);
    const Json a = Json::parse(local.out);
    for (const char* key : {"output", "patches", "vertices", "triangles", "error_bound"}) CHECK(a.contains(key));
    CHECK(a["error_bound"].get<double>() <= 1e-3);
    CHECK(a["measured_parametric"].get<double>() <= a["error_bound"].get<double>());
    CHECK(a["measured_geometric"].get<double>() <= a["measured_parametric"].get<double>());
    CHECK(a["measured_geometric"].get<double>() >= 0.5e-3);
    // Under the sanitizers (support/sanitizers.h) the patch-grid run is left out: it measures the
    // deviations of about twice the triangles, the larger part of this test's 73 s of ASan + UBSan
    // (the tool runs instrumented too). It runs in Release; the library's patch-grid refinement is
    // tested under the sanitizers in test_tessellate.
    if (!freeform::test::underSanitizers) {
        const auto grid = cli("tessellate " + freeform::test::shellQuote(kTeapot) + " -o " + freeform::test::shellQuote(out) + " --tolerance 1e-3 --refinement patch-grid");
        REQUIRE(grid.status == 0);
        const Json b = Json::parse(grid.out);
        CHECK(b["error_bound"].get<double>() <= 1e-3);
        CHECK(b["triangles"].get<long>() > a["triangles"].get<long>());
    }
    // --measure geometric: every mesh point within the tolerance of the surface, fewer triangles.
    const auto geo = cli("tessellate " + freeform::test::shellQuote(kTeapot) + " -o " + freeform::test::shellQuote(out) + " --tolerance 1e-3 --measure geometric");
    REQUIRE(geo.status == 0);
    const Json g = Json::parse(geo.out);
    CHECK(g["error_bound"].get<double>() <= 1e-3);
    CHECK(g["measured_geometric"].get<double>() <= 1e-3);
    CHECK(g["triangles"].get<long>() < a["triangles"].get<long>());
    requireError(cli("tessellate " + freeform::test::shellQuote(kTeapot) + " -o " + freeform::test::shellQuote(out) + " --tolerance 1e-3 --measure hausdorff"), 2, "--measure");
}

TEST_CASE("tessellate --max-triangles refuses with the estimate and writes nothing", "[cli][tessellate][limits]")
{
    // A bicubic patch a million units large.
    std::string bpt = "1\n3 3\n";
    for (int i = 0; i <= 3; ++i)
        for (int j = 0; j <= 3; ++j)
            bpt += std::to_string(i * 1e6 / 3) + " " + std::to_string(j * 1e6 / 3) + " " +
                   std::to_string((i == 1 || i == 2) && (j == 1 || j == 2) ? 4e5 : 0.0) + "\n";
    const std::string huge = tmp("tess_huge.bpt"), out = tmp("tess_huge.obj");
    writeText(huge, bpt);
    std::filesystem::remove(out);
    requireError(cli("tessellate " + freeform::test::shellQuote(huge) + " -o " + freeform::test::shellQuote(out) + " --tolerance 1e-2 --max-triangles 100000"), 1,
                 "needs more than maxTriangles = 100000");
    CHECK(!std::filesystem::exists(out));
    // The default limit (10^7), with one grid per patch: refused from the count alone.
    requireError(cli("tessellate " + freeform::test::shellQuote(huge) + " -o " + freeform::test::shellQuote(out) + " --tolerance 1e-2 --refinement patch-grid"), 1,
                 "33554432 triangles");
    CHECK(!std::filesystem::exists(out));
    const auto coarse = cli("tessellate " + freeform::test::shellQuote(huge) + " -o " + freeform::test::shellQuote(out) + " --tolerance 1e4 --max-triangles 0");
    CHECK(coarse.status == 0);
    requireError(cli("tessellate " + freeform::test::shellQuote(kTeapot) + " -o " + freeform::test::shellQuote(out) + " --max-triangles -1"), 2, "--max-triangles");
    requireError(cli("tessellate " + freeform::test::shellQuote(kTeapot) + " -o " + freeform::test::shellQuote(out) + " --max-triangles lots"), 2, "--max-triangles");
    requireError(cli("tessellate " + freeform::test::shellQuote(kTeapot) + " -o " + freeform::test::shellQuote(out) + " --refinement quadtree"), 2, "--refinement");
}

} // namespace test_tessellate_cli
