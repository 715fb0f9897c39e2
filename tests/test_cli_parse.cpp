// The command line as CLI11 parses it (cli/run.cpp), in process: parse errors are bad usage (exit 2,
// one "error:" line, nothing on stdout), the accepted spellings give the same result, and every
// command's --help lists every option docs/cli.md documents for it.

// GCC 12 at -O1 with ASan warns "may be used uninitialized" inside libstdc++'s <regex> (the
// std::function of an NFA state being moved): a false positive in the library's own code, which
// -Werror would turn into a build failure of the sanitizer build. Off for this file only.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "support/cli.h"

namespace test_cli_parse {

using freeform::test::cliInProcess;
using freeform::test::runCli;
using freeform::test::writeText;
using Json = nlohmann::json;

namespace {

std::string tmp(const std::string& name)
{
    return std::string(FREEFORM_TEST_TMP) + "/" + name;
}

std::string doc()
{
    const std::string path = tmp("cli_parse.json");
    writeText(path, R"({"format": "freeform", "version": 1, "objects": [
        {"name": "c", "type": "bezier_curve", "points": [[0,0],[1,2],[3,2],[4,0]]},
        {"name": "s", "type": "bezier_spline", "degree": 3,
         "points": [[0,0],[1,2],[3,2],[4,0],[5,-2],[7,-2],[8,0]], "intervals": [1, 2]}]})");
    return path;
}

/// Bad usage: exit 2, one line "error: ... (see freeform CMD --help)" naming `fragment`, no stdout.
void requireUsageError(const std::string& arguments, const std::string& command, const std::string& fragment)
{
    const auto r = cliInProcess(arguments);
    INFO(arguments << "\nstderr: " << r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(r.err.rfind("error: ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.err.find(fragment) != std::string::npos);
    const std::string tail = "(see freeform " + command + " --help)\n";
    CHECK(r.err.size() >= tail.size());
    CHECK(r.err.compare(r.err.size() - std::min(r.err.size(), tail.size()), tail.size(), tail) == 0);
}

std::string readDocs()
{
    std::ifstream in(std::string(FREEFORM_SOURCE_DIR) + "/docs/cli.md");
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

/// docs/cli.md: for every "## `freeform CMD`" section, the options named in its first code block
/// (the synopsis) and in the first column of its option table.
std::map<std::string, std::set<std::string>> documentedOptions()
{
    std::map<std::string, std::set<std::string>> result;
    const std::string text = readDocs();
    const std::regex heading(R"(^## `freeform ([a-z]+)`$)");
    const std::regex option(R"((^|[\s\[`|,])(--[a-z][a-z-]*|-o)\b)");
    std::istringstream lines(text);
    std::string line, command;
    int fences = 0;
    while (std::getline(lines, line)) {
        std::smatch m;
        if (std::regex_match(line, m, heading)) {
            command = m[1];
            result[command];
            fences = 0;
            continue;
        }
        if (line.rfind("## ", 0) == 0) command.clear();
        if (command.empty()) continue;
        if (line.rfind("```", 0) == 0) {
            ++fences;
            continue;
        }
        std::string scan;
        if (fences == 1) scan = line; // inside the synopsis block
        else if (line.rfind("| `-", 0) == 0) scan = line.substr(0, line.find(" | ")); // first column
        for (auto it = std::sregex_iterator(scan.begin(), scan.end(), option); it != std::sregex_iterator(); ++it)
            result[command].insert((*it)[2]);
    }
    return result;
}

} // namespace

TEST_CASE("CLI11 parse errors are bad usage with CLI11's message", "[cli][errors]")
{
    const std::string d = doc();
    // A missing value: CLI11 names the option.
    requireUsageError("eval " + d + " --object c --at", "eval", "--at");
    // Numbers: not an integer, not finite, not a number at all.
    requireUsageError("eval " + d + " --object c --at 0.5 --derivatives x", "eval", "--derivatives: \"x\" is not an integer");
    requireUsageError("eval " + d + " --object c --at 0.5 --derivatives 1.5", "eval", "is not an integer");
    requireUsageError("eval " + d + " --object c --at 0.5 --derivatives 0x2", "eval", "is not an integer");
    requireUsageError("continuity " + d + " --object s --tolerance nan", "continuity", "--tolerance: \"nan\" is not a finite number");
    requireUsageError("continuity " + d + " --object s --tolerance inf", "continuity", "not a finite number");
    requireUsageError("continuity " + d + " --object s --tolerance 1e-3x", "continuity", "not a finite number");
    // An option given twice.
    requireUsageError("eval " + d + " --object c --object c --at 0.5", "eval", "--object");
    // A value that is not one of the choices: CLI11 lists them.
    requireUsageError("lattice --fit x.obj -o x.json --outside bogus", "lattice", "--outside");
    requireUsageError("ffd x.obj --lattice l.json -o y.obj --normals bogus", "ffd", "jacobian");
    // A flag takes no value; an unknown option written with '=' is named without its value.
    requireUsageError("info x.obj --genus=3", "info", "unknown option --genus");
    requireUsageError("info x.obj --details=3", "info", "details was given a disallowed flag override");
    requireUsageError("info x.obj --details --details", "info", "--details");
    requireUsageError("bench --vertices", "bench", "--vertices");
}

TEST_CASE("the spellings CLI11 accepts give the same result", "[cli]")
{
    const std::string d = doc();
    const auto plain = cliInProcess("eval " + freeform::test::shellQuote(d) + " --object c --at 0.5 --derivatives 2");
    REQUIRE(plain.status == 0);
    // --name=value, options before the positional argument, in any order.
    CHECK(cliInProcess("eval " + freeform::test::shellQuote(d) + " --object=c --at=0.5 --derivatives=2").out == plain.out);
    CHECK(cliInProcess("eval --derivatives 2 --at 0.5 --object c " + freeform::test::shellQuote(d)).out == plain.out);
    CHECK(runCli({"eval", "--at", "0.5", d, "--object", "c", "--derivatives", "2"}).out == plain.out);
    // Integers are decimal: 010 is ten derivatives (CLI11 alone would read octal 8).
    const auto ten = cliInProcess("eval " + freeform::test::shellQuote(d) + " --object c --at 0.5 --derivatives 010");
    REQUIRE(ten.status == 0);
    CHECK(Json::parse(ten.out)["derivatives"].size() == 10);
    // A value starting with '-' is the option's value, not an option: t = -0.5 is outside [0, 1].
    for (const char* at : {"-0.5", "-.5"}) {
        const auto r = runCli({"eval", d, "--object", "c", "--at", at});
        CHECK(r.status == 1);
        CHECK(r.err.find("outside") != std::string::npos);
    }
    // The derivative of the cubic at t = 0.5, hand-computed: 3 * sum of the differences weighted
    // by B(2, k)(0.5) = 3 (0.25 (1,2) + 0.5 (2,0) + 0.25 (1,-2)) = (4.5, 0).
    CHECK(Json::parse(plain.out)["derivatives"][0] == Json::array({4.5, 0.0}));
}

TEST_CASE("--help anywhere after the command prints that command's help", "[cli]")
{
    for (const std::string& line : {std::string("eval --help"), std::string("eval -h"), "eval " + doc() + " --object c -h",
                                    std::string("eval --bogus --help")}) {
        const auto r = cliInProcess(line);
        INFO(line);
        CHECK(r.status == 0);
        CHECK(r.err.empty());
        CHECK(r.out.find("freeform eval") != std::string::npos);
        CHECK(r.out.find("--derivatives") != std::string::npos);
    }
}

TEST_CASE("every command's --help lists every option docs/cli.md documents for it", "[cli]")
{
    const auto documented = documentedOptions();
    const std::set<std::string> commands = {"eval", "continuity", "interpolate", "convert", "tessellate",
                                            "subdivide", "info", "lattice", "ffd", "bench"};
    std::set<std::string> sections;
    for (const auto& [name, options] : documented) sections.insert(name);
    CHECK(sections == commands); // every command has its section, and no section is stale

    const auto top = cliInProcess("--help");
    REQUIRE(top.status == 0);
    for (const std::string& name : commands) {
        CHECK(top.out.find("  " + name + " ") != std::string::npos);
        const auto r = cliInProcess(name + " --help");
        INFO(name << " --help:\n" << r.out);
        REQUIRE(r.status == 0);
        CHECK(r.err.empty());
        const auto it = documented.find(name);
        if (it == documented.end()) continue;
        CHECK_FALSE(it->second.empty());
        for (const std::string& option : it->second) {
            INFO(option);
            // As an option of the list: "-o,--output" or "--name" at the start of a help line.
            const std::regex listed("(^|\\n)  (-[a-z],)?" + option + "[ ,\\n]");
            CHECK(std::regex_search(r.out, listed));
        }
    }
}

} // namespace test_cli_parse
