// Every object kind's document-layer code is in its one file, src/document/kinds/TYPE.cpp
// (src/document/kind_file.h; docs/architecture.md, "Adding an object kind"): one file per line of
// FREEFORM_OBJECT_KINDS and no other there, and the files that dispatch to them (the typed
// document, the kind table, the facades, deformDocument, the NURBS conversions, dataPoints) name
// no kind's data type in code, so a case on an object's data cannot come back into them
// unnoticed. (A case on a geometry class is not caught here: AnySurface's members have one per
// surface class, and the compiler asks for each.) That each kind's file defines all its
// functions is the linker's check.

#include <catch2/catch.hpp>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "freeform/io/document.h"

namespace test_kind_files {

namespace fs = std::filesystem;

namespace {

struct KindEntry {
    const char* data; // the data struct's name
    const char* name; // the "type" string
};

#define TEST_KIND_ENTRY(Kind, Data, name) KindEntry{#Data, name},
const std::vector<KindEntry> kEntries = {FREEFORM_OBJECT_KINDS(TEST_KIND_ENTRY)};
#undef TEST_KIND_ENTRY

/// The kinds' data types a line of code names (comments may name them), space-separated, or "".
std::string namedDataTypes(const std::string& line)
{
    const std::string code = line.substr(0, line.find("//"));
    std::string found;
    for (const KindEntry& k : kEntries) {
        const std::string type = k.data;
        for (std::size_t at = code.find(type); at != std::string::npos; at = code.find(type, at + 1)) {
            const bool before = at > 0 && (std::isalnum(static_cast<unsigned char>(code[at - 1])) || code[at - 1] == '_');
            const std::size_t end = at + type.size();
            const bool after = end < code.size() && (std::isalnum(static_cast<unsigned char>(code[end])) || code[end] == '_');
            if (!before && !after) {
                found += (found.empty() ? "" : " ") + type;
                break;
            }
        }
    }
    return found;
}

} // namespace

TEST_CASE("the data-type check finds what it forbids", "[kinds]")
{
    CHECK(namedDataTypes("    if (const auto* d = std::get_if<NurbsCurveData>(&data)) return d->points;") == "NurbsCurveData");
    CHECK(namedDataTypes("[](const BezierCurveData& a, const PartData& b) {}") == "BezierCurveData PartData");
    CHECK(namedDataTypes("    // a BezierCurveData here is fine") == "");
    CHECK(namedDataTypes("    TrimCurveData trim; PartFaceData face; NurbsCurveDataSet s;") == "");
}

TEST_CASE("every kind has its document file, and every document file is a kind", "[kinds]")
{
    const fs::path folder = fs::path(FREEFORM_SOURCE_DIR) / "freeform" / "src" / "document" / "kinds";
    REQUIRE(fs::is_directory(folder));
    std::set<std::string> files;
    for (const auto& entry : fs::directory_iterator(folder)) files.insert(entry.path().filename().string());
    std::set<std::string> expected;
    for (const KindEntry& k : kEntries) expected.insert(std::string(k.name) + ".cpp");
    CHECK(files == expected);
    for (const KindEntry& k : kEntries) {
        // Each file is about its kind: it defines the kind's row from its own data type.
        std::ifstream in(folder / (std::string(k.name) + ".cpp"));
        const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        INFO(k.name);
        CHECK(text.find(std::string("KindRow kindRow(std::type_identity<") + k.data + ">)") != std::string::npos);
    }
}

TEST_CASE("the document layer's dispatching files name no kind's data type", "[kinds]")
{
    const fs::path document = fs::path(FREEFORM_SOURCE_DIR) / "freeform" / "src" / "document";
    for (const char* file : {"model.cpp", "kinds.cpp", "any_geometry.cpp", "deform.cpp", "nurbs_convert.cpp", "object_data.cpp"}) {
        std::ifstream in(document / file);
        REQUIRE(in);
        std::string line;
        int number = 0;
        while (std::getline(in, line)) {
            ++number;
            INFO(file << ":" << number << ": " << line);
            CHECK(namedDataTypes(line).empty());
        }
    }
}

} // namespace test_kind_files
