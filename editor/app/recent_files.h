#pragma once
// File > Open recent: the last kMax documents opened or saved, most recent first, kept in the
// user's configuration folder ($XDG_CONFIG_HOME/freeform/recent.json, else
// ~/.config/freeform/recent.json) as {"recent": ["/absolute/path.json", ...]}. The file is read
// through the library's JSON gate (freeform/io/json_check.h) and strictly: anything else is
// ignored as a whole, with one message (docs/editor.md, "Documents").

#include <filesystem>
#include <string>
#include <vector>

namespace freeform::editor {

class RecentFiles {
public:
    static constexpr std::size_t kMax = 8;

    /// $XDG_CONFIG_HOME/freeform/recent.json (when set and not empty), else
    /// $HOME/.config/freeform/recent.json, else an empty path (no list is kept).
    static std::filesystem::path defaultFile();

    explicit RecentFiles(std::filesystem::path file = defaultFile()) : file_(std::move(file)) {}

    /// Reads the list. A missing file is an empty list; a file that cannot be read, is not JSON,
    /// fails the gate (depth, a repeated key) or is not {"recent": [strings]} leaves the list
    /// empty and returns the message (naming the file); otherwise returns "".
    std::string load();
    /// Puts `path` (made absolute) first, drops an older entry of it and keeps the first kMax,
    /// then writes the file atomically. Returns "" or the message when it cannot be written.
    std::string add(const std::string& path);
    const std::vector<std::string>& paths() const { return paths_; }
    const std::filesystem::path& file() const { return file_; }

private:
    std::string save() const;
    std::filesystem::path file_;
    std::vector<std::string> paths_;
};

} // namespace freeform::editor
