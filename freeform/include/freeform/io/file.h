#pragma once
// Whole-file reads and atomic writes.

#include <string>

namespace freeform {

/// Reads a whole file; Error naming the path when it cannot.
std::string readFile(const std::string& path);

/// Writes text to path atomically: a temporary file beside it, flushed and closed, then renamed
/// over path, so a failure never leaves a half-written or clobbered file. Throws Error on failure.
void writeFileAtomically(const std::string& path, const std::string& text);

/// The same for a writer that fills a stream: write(std::ostream&) runs against the temporary file.
template <typename Writer>
void writeFileAtomicallyWith(const std::string& path, Writer&& write);

} // namespace freeform

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include "freeform/core/error.h"

namespace freeform {

template <typename Writer>
void writeFileAtomicallyWith(const std::string& path, Writer&& write)
{
    namespace fs = std::filesystem;
    const fs::path target(path);
    fs::path dir = target.parent_path();
    if (dir.empty()) dir = ".";
    std::random_device rd;
    std::string tmpName(1, '.');
    tmpName += target.filename().string();
    tmpName += ".tmp";
    tmpName += std::to_string(rd());
    const fs::path tmp = dir / tmpName;
    try {
        {
            std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
            if (!out) throw Error(path + ": cannot open a temporary file in " + dir.string() + " for writing");
            write(out);
            out.flush();
            if (!out) throw Error(path + ": writing failed");
        }
        std::error_code ec;
        fs::rename(tmp, target, ec);
        if (ec) throw Error(path + ": cannot replace the file: " + ec.message());
    } catch (...) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw;
    }
}

} // namespace freeform
