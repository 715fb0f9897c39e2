// The library's layers read bottom-up: core -> geometry -> io -> document -> (cli, editor).
// No header of the geometry layer (curve/, surface/, volume/, subdivision/) may include a file
// format (nlohmann), the io layer or the document layer; this test reads every such header.

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "freeform/freeform.h" // compiles on its own, with every header in it

namespace test_layering {

namespace fs = std::filesystem;

TEST_CASE("geometry headers include no JSON, io or document header", "[layers]")
{
    const fs::path root = fs::path(FREEFORM_SOURCE_DIR) / "freeform" / "include" / "freeform";
    int headers = 0;
    for (const char* layer : {"curve", "surface", "volume", "subdivision"}) {
        REQUIRE(fs::is_directory(root / layer));
        for (const auto& entry : fs::recursive_directory_iterator(root / layer)) {
            if (!entry.is_regular_file()) continue;
            ++headers;
            std::ifstream in(entry.path());
            std::string line;
            int number = 0;
            while (std::getline(in, line)) {
                ++number;
                const auto first = line.find_first_not_of(" \t");
                if (first == std::string::npos || line[first] != '#') continue;
                if (line.find("include", first) == std::string::npos) continue;
                INFO(entry.path().string() << ":" << number << ": " << line);
                CHECK(line.find("nlohmann") == std::string::npos);
                CHECK(line.find("freeform/io/") == std::string::npos);
                CHECK(line.find("freeform/document/") == std::string::npos);
            }
        }
    }
    CHECK(headers >= 10);
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
