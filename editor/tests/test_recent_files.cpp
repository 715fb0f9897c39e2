// File > Open recent (editor/app/recent_files.h; docs/editor.md, "Documents"), with a temporary
// XDG_CONFIG_HOME: the file's place ($XDG_CONFIG_HOME/freeform/recent.json, else ~/.config/...),
// the last 8 most recent first, a path opened again moves to the front, the list read back from
// the file equals the one written, and a broken file (not JSON, a repeated key caught by the JSON
// gate, too deep, the wrong shape) is ignored as a whole with one message naming it.

#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "app/recent_files.h"
#include "ui/path_label.h"
#include "support/process.h"

namespace test_recent_files {

using namespace freeform::editor;
namespace fs = std::filesystem;

namespace {

const fs::path kConfig = fs::path(FREEFORM_TEST_TMP) / "recent_config";

/// Sets XDG_CONFIG_HOME to a fresh folder for the test and restores the old value after it.
struct TemporaryConfig {
    std::string old;
    bool had = false;
    TemporaryConfig()
    {
        if (const char* v = std::getenv("XDG_CONFIG_HOME")) old = v, had = true;
        fs::remove_all(kConfig);
        fs::create_directories(kConfig);
        setenv("XDG_CONFIG_HOME", kConfig.c_str(), 1);
    }
    ~TemporaryConfig()
    {
        if (had) setenv("XDG_CONFIG_HOME", old.c_str(), 1);
        else unsetenv("XDG_CONFIG_HOME");
    }
};

std::string doc(int k) { return (fs::path(FREEFORM_TEST_TMP) / ("recent_" + std::to_string(k) + ".json")).string(); }

} // namespace

TEST_CASE("recent files: the file lives in $XDG_CONFIG_HOME/freeform, else ~/.config/freeform", "[editor][recent]")
{
    TemporaryConfig config;
    CHECK(RecentFiles::defaultFile() == kConfig / "freeform" / "recent.json");
    setenv("XDG_CONFIG_HOME", "", 1); // empty: as unset
    const char* home = std::getenv("HOME");
    if (home && *home) CHECK(RecentFiles::defaultFile() == fs::path(home) / ".config" / "freeform" / "recent.json");
}

TEST_CASE("recent files: the last 8, most recent first, written and read back", "[editor][recent]")
{
    TemporaryConfig config;
    RecentFiles recent;
    CHECK(recent.load().empty()); // no file yet: an empty list, no message
    CHECK(recent.paths().empty());
    for (int k = 1; k <= 10; ++k) CHECK(recent.add(doc(k)).empty());
    REQUIRE(recent.paths().size() == 8);
    for (int i = 0; i < 8; ++i) CHECK(recent.paths()[static_cast<std::size_t>(i)] == doc(10 - i)); // 10, 9, ..., 3
    REQUIRE(fs::exists(kConfig / "freeform" / "recent.json"));

    // Opened again: to the front, not twice; a relative path is stored absolute.
    CHECK(recent.add(doc(5)).empty());
    CHECK(recent.paths().front() == doc(5));
    CHECK(std::count(recent.paths().begin(), recent.paths().end(), doc(5)) == 1);
    CHECK(recent.paths().size() == 8);
    const fs::path cwd = fs::current_path();
    fs::current_path(FREEFORM_TEST_TMP);
    CHECK(recent.add("recent_11.json").empty());
    fs::current_path(cwd);
    CHECK(recent.paths().front() == doc(11));

    // A second list reads what the first wrote.
    RecentFiles again;
    CHECK(again.load().empty());
    CHECK(again.paths() == recent.paths());
    CHECK(again.paths() == std::vector<std::string>{doc(11), doc(5), doc(10), doc(9), doc(8), doc(7), doc(6), doc(4)});
}

TEST_CASE("recent files: a broken file is ignored with one message naming it", "[editor][recent]")
{
    TemporaryConfig config;
    const fs::path file = kConfig / "freeform" / "recent.json";
    fs::create_directories(file.parent_path());
    const std::vector<std::pair<std::string, std::string>> broken = {
        {"{\"recent\": [\"/a.json\", ", "not valid JSON"},
        {"{\"recent\": [\"/a.json\"], \"recent\": []}", "recent"},            // a repeated key: the JSON gate
        {std::string(300, '[') + std::string(300, ']'), "deep"},               // deeper than the gate allows
        {"[\"/a.json\"]", "expected {\"recent\": [paths]}"},
        {"{\"recent\": [\"/a.json\", 3]}", "recent[1]"},
        {"{\"recent\": [\"/a.json\"], \"more\": 1}", "expected"},
    };
    for (const auto& [text, what] : broken) {
        freeform::test::writeText(file.string(), text);
        RecentFiles recent;
        const std::string message = recent.load();
        INFO(text << " -> " << message);
        CHECK(message.find(file.string()) != std::string::npos);
        CHECK(message.find(what) != std::string::npos);
        CHECK(recent.paths().empty());
        // Adding after a broken file starts a fresh, valid list.
        CHECK(recent.add(doc(1)).empty());
        RecentFiles again;
        CHECK(again.load().empty());
        CHECK(again.paths() == std::vector<std::string>{doc(1)});
    }
}

TEST_CASE("recent files: a long path is shown by its beginning and its end, cut between characters", "[editor][recent]")
{
    CHECK(shortPathLabel("/a/b.json") == "/a/b.json");
    const std::string exact = "/" + std::string(63, 'a'); // 64 characters: shown whole
    CHECK(shortPathLabel(exact) == exact);

    // 116 characters: 61 are kept around "...", the last 30 (the file name and the end of its folder).
    const std::string folder(100, 'a');
    const std::string label = shortPathLabel("/" + folder + "/file name.json");
    CHECK(label == "/" + std::string(30, 'a') + "..." + std::string(15, 'a') + "/file name.json");
    CHECK(label.size() == 64);

    // A file name longer than the label keeps its end; the beginning keeps at least 8 characters.
    CHECK(shortPathLabel("/d/" + std::string(100, 'n')) == "/d/" + std::string(5, 'n') + "..." + std::string(53, 'n'));

    // Two-byte characters (u with diaeresis): 64 characters, 128 - 7 + 7 bytes, no character split.
    std::string u;
    for (int i = 0; i < 100; ++i) u += "\xC3\xBC";
    std::string u30, u23;
    for (int i = 0; i < 30; ++i) u30 += "\xC3\xBC";
    for (int i = 0; i < 23; ++i) u23 += "\xC3\xBC";
    CHECK(shortPathLabel("/" + u + "/x.json") == "/" + u30 + "..." + u23 + "/x.json");
}

} // namespace test_recent_files
