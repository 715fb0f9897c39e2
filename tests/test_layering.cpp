// The library's layers read bottom-up: core -> geometry -> io -> document -> (cli, editor).
// No file of the core and geometry layers (core/, curve/, surface/, volume/, subdivision/, mesh/,
// tessellate/, brep/; headers and sources) may include a file format (nlohmann), the io or document
// layer, or a stream header, nor print: the library reports through freeform::Error and the
// warning handler (core/warning.h) only. This test reads every such file; snprintf and
// to_chars, which format into memory, are allowed. The front ends (cli/, editor/, python/src/)
// compare no type string: they dispatch on the kind table (document/kinds.h). No source file of
// freeform/, cad/, cli/, editor/ or python/src/ is over 800 lines.

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>

#include "freeform/freeform.h" // compiles on its own, with every header in it

namespace test_layering {

namespace fs = std::filesystem;

namespace {

const char* const kLowerLayers[] = {"core", "curve", "surface", "volume", "subdivision", "mesh", "tessellate", "brep"};

/// What a line of a core or geometry file must not hold, or "" when it is clean.
std::string violation(const std::string& line)
{
    static const std::regex include(R"(^\s*#\s*include\s*[<"]([^>"]+)[>"])");
    static const std::regex printing(R"((^|[^\w:])(std::)?(printf|fprintf|vprintf|vfprintf|puts|fputs|putchar|perror)\s*\(|std::(cout|cerr|clog)\b)");
    std::smatch m;
    if (std::regex_search(line, m, include)) {
        const std::string header = m[1];
        if (header.find("nlohmann") != std::string::npos) return "includes JSON";
        if (header.rfind("freeform/io/", 0) == 0) return "includes the io layer";
        if (header.rfind("freeform/document/", 0) == 0) return "includes the document layer";
        for (const char* stream : {"iostream", "fstream", "sstream", "ostream", "istream", "iosfwd", "strstream"})
            if (header == stream) return "includes <" + header + ">";
        return "";
    }
    const std::string code = line.substr(0, line.find("//")); // comments may name what is forbidden
    if (std::regex_search(code, printing)) return "prints";
    return "";
}

/// The kind names a front-end line compares or keys on as a string literal ("nurbs_curve"), or ""
/// when it has none. Front ends dispatch on the kind table (document/kinds.h) instead. Comments may
/// name kinds, and so may longer texts (help, messages). "lattice" is also a JSON member of
/// command output, a Python argument, the `freeform lattice` command and a default object name:
/// those uses ([, py::arg(, def_property_readonly(, {, `name = `, a method name alone on its line)
/// are not the kind.
std::string quotedKind(const std::string& line)
{
    const std::string code = line.substr(0, line.find("//"));
    static const std::regex literal(R"rx((^|.)"([a-z_]+)")rx");
    static const std::regex latticeUse(R"rx((\[|py::arg\(|def_property_readonly\(|\{|name = |^\s*)"lattice")rx");
    std::string found;
    for (auto it = std::sregex_iterator(code.begin(), code.end(), literal); it != std::sregex_iterator(); ++it) {
        const std::string word = (*it)[2];
        if (!freeform::kindNamed(word)) continue;
        if (word == "lattice" && std::regex_search(code, latticeUse) &&
            code.find("== \"lattice\"") == std::string::npos && code.find("!= \"lattice\"") == std::string::npos)
            continue;
        found += (found.empty() ? "" : " ") + word;
    }
    return found;
}

} // namespace

TEST_CASE("the quoted-kind check finds what it forbids", "[layers]")
{
    CHECK(quotedKind(R"(    if (type == "nurbs_curve") return;)") == "nurbs_curve");
    CHECK(quotedKind(R"(    table["bezier_surface"] = evalSurface;)") == "bezier_surface");
    CHECK(quotedKind(R"(    return t == "rational_bezier_curve" || t == "lattice";)") == "rational_bezier_curve lattice");
    CHECK(quotedKind(R"(    if (it.type != "lattice") continue;)") == "lattice");
    CHECK(quotedKind(R"(    j["lattice"] = latticeObject.name;)") == "");
    CHECK(quotedKind(R"(    py::arg("lattice"), py::arg("threads") = 0)") == "");
    CHECK(quotedKind(R"(    throw UsageError("option --to: is not one of bezier_spline, deboor_spline");)") == "");
    CHECK(quotedKind(R"(    // a "bezier_spline" here)") == "");
    CHECK(quotedKind(R"(    std::string a = "mesh", b = "nurbs";)") == "");
    CHECK(quotedKind(R"(            "lattice",)") == "");
    CHECK(quotedKind(R"(            "nurbs_curve",)") == "nurbs_curve");
}

TEST_CASE("the front ends name no kind in code: they dispatch on the kind table", "[layers]")
{
    const fs::path root(FREEFORM_SOURCE_DIR);
    int files = 0;
    for (const char* folder : {"cli", "editor", "python/src"}) {
        REQUIRE(fs::is_directory(root / folder));
        for (const auto& entry : fs::recursive_directory_iterator(root / folder)) {
            const fs::path& path = entry.path();
            if (!entry.is_regular_file() || (path.extension() != ".cpp" && path.extension() != ".h")) continue;
            // Tests and benchmarks write documents, whose text names kinds.
            const std::string relative = fs::relative(path, root).generic_string();
            if (relative.rfind("editor/tests/", 0) == 0 || relative.rfind("editor/benchmarks/", 0) == 0) continue;
            ++files;
            std::ifstream in(path);
            std::string line;
            int number = 0;
            while (std::getline(in, line)) {
                ++number;
                INFO(path.string() << ":" << number << ": " << line);
                CHECK(quotedKind(line).empty());
            }
        }
    }
    CHECK(files >= 80);
}

TEST_CASE("no source file of the library, the CLI, the editor or the Python module is over 800 lines", "[layers]")
{
    const fs::path root(FREEFORM_SOURCE_DIR);
    int files = 0;
    for (const char* folder : {"freeform", "cad", "cli", "editor", "python/src"}) {
        REQUIRE(fs::is_directory(root / folder));
        for (const auto& entry : fs::recursive_directory_iterator(root / folder)) {
            const fs::path& path = entry.path();
            if (!entry.is_regular_file() || (path.extension() != ".cpp" && path.extension() != ".h")) continue;
            ++files;
            std::ifstream in(path);
            int lines = 0;
            for (std::string line; std::getline(in, line);) ++lines;
            INFO(path.string() << ": " << lines << " lines (docs/architecture.md: split it along its seams)");
            CHECK(lines <= 800);
        }
    }
    CHECK(files >= 200);
}

TEST_CASE("the violation check finds what it forbids", "[layers]")
{
    CHECK(violation("#include <nlohmann/json.hpp>") == "includes JSON");
    CHECK(violation("#include \"freeform/io/mesh_io.h\"") == "includes the io layer");
    CHECK(violation("  #  include \"freeform/document/document.h\"") == "includes the document layer");
    CHECK(violation("#include <sstream>") == "includes <sstream>");
    CHECK(violation("    std::cerr << x;") == "prints");
    CHECK(violation("    printf(\"%d\", 1);") == "prints");
    CHECK(violation("    std::fprintf(stderr, \"x\");") == "prints");
    CHECK(violation("    std::snprintf(buffer, sizeof buffer, \"%g\", x);") == "");
    CHECK(violation("#include <cstdio>") == "");
    CHECK(violation("    // never std::cout here") == "");
    CHECK(violation("    const int puts_count = 3;") == "");
}

TEST_CASE("core and geometry files include no JSON, io, document or stream header, and print nothing", "[layers]")
{
    const fs::path freeform = fs::path(FREEFORM_SOURCE_DIR) / "freeform";
    int files = 0;
    for (const char* layer : kLowerLayers) {
        const fs::path include = freeform / "include" / "freeform" / layer, source = freeform / "src" / layer;
        REQUIRE(fs::is_directory(include));
        for (const fs::path& dir : {include, source}) {
            if (!fs::is_directory(dir)) continue;
            for (const auto& entry : fs::recursive_directory_iterator(dir)) {
                if (!entry.is_regular_file()) continue;
                ++files;
                std::ifstream in(entry.path());
                std::string line;
                int number = 0;
                while (std::getline(in, line)) {
                    ++number;
                    INFO(entry.path().string() << ":" << number << ": " << line);
                    CHECK(violation(line).empty());
                }
            }
        }
    }
    CHECK(files >= 60);
}

TEST_CASE("freeform.h includes every public header", "[layers]")
{
    const fs::path include = fs::path(FREEFORM_SOURCE_DIR) / "freeform" / "include";
    std::set<std::string> listed;
    std::ifstream in(include / "freeform" / "freeform.h");
    std::string line;
    while (std::getline(in, line)) {
        const auto a = line.find("#include \"");
        if (a == std::string::npos) continue;
        const auto b = line.find('"', a + 10);
        listed.insert(line.substr(a + 10, b - a - 10));
    }
    int headers = 0;
    for (const auto& entry : fs::recursive_directory_iterator(include / "freeform")) {
        if (!entry.is_regular_file() || entry.path().extension() != ".h") continue;
        const std::string relative = fs::relative(entry.path(), include).generic_string();
        if (relative == "freeform/freeform.h") continue;
        ++headers;
        INFO(relative);
        CHECK(listed.count(relative) == 1);
    }
    CHECK(headers >= 30);
    CHECK(listed.size() == static_cast<std::size_t>(headers));
}

} // namespace test_layering
