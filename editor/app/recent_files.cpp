#include "app/recent_files.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "freeform/core/error.h"
#include "freeform/io/file.h"
#include "freeform/io/json_check.h"

namespace freeform::editor {

namespace fs = std::filesystem;

fs::path RecentFiles::defaultFile()
{
    const char* config = std::getenv("XDG_CONFIG_HOME");
    const char* home = std::getenv("HOME");
    if (config && *config) return fs::path(config) / "freeform" / "recent.json";
    if (home && *home) return fs::path(home) / ".config" / "freeform" / "recent.json";
    return {};
}

std::string RecentFiles::load()
{
    paths_.clear();
    if (file_.empty()) return "";
    std::error_code ec;
    if (!fs::exists(file_, ec)) return "";
    const std::string source = file_.string();
    try {
        std::ifstream in(file_, std::ios::binary);
        if (!in) throw Error(source + ": cannot be read");
        std::ostringstream text;
        text << in.rdbuf();
        checkJsonText(text.str(), source);
        nlohmann::json j;
        try {
            j = nlohmann::json::parse(text.str());
        } catch (const nlohmann::json::exception& e) {
            throw Error(source + ": not valid JSON: " + e.what());
        }
        if (!j.is_object() || j.size() != 1 || !j.contains("recent") || !j["recent"].is_array())
            throw Error(source + ": expected {\"recent\": [paths]}");
        std::vector<std::string> paths;
        for (std::size_t i = 0; i < j["recent"].size(); ++i) {
            const auto& p = j["recent"][i];
            if (!p.is_string() || p.get<std::string>().empty())
                throw Error(source + ": recent[" + std::to_string(i) + "]: expected a non-empty string");
            if (paths.size() < kMax && std::find(paths.begin(), paths.end(), p.get<std::string>()) == paths.end())
                paths.push_back(p.get<std::string>());
        }
        paths_ = std::move(paths);
        return "";
    } catch (const Error& e) {
        return e.what();
    }
}

std::string RecentFiles::add(const std::string& path)
{
    std::error_code ec;
    const std::string absolute = fs::absolute(path, ec).lexically_normal().string();
    paths_.erase(std::remove(paths_.begin(), paths_.end(), absolute), paths_.end());
    paths_.insert(paths_.begin(), absolute);
    if (paths_.size() > kMax) paths_.resize(kMax);
    return save();
}

std::string RecentFiles::save() const
{
    if (file_.empty()) return "";
    std::error_code ec;
    fs::create_directories(file_.parent_path(), ec);
    try {
        writeFileAtomically(file_.string(), nlohmann::json{{"recent", paths_}}.dump(1) + "\n");
        return "";
    } catch (const Error& e) {
        return e.what();
    }
}

} // namespace freeform::editor
