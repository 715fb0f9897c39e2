#pragma once
// Shared by the fuzz targets (fuzz/README.md): inputs go through the library's file entry points,
// so each target writes its input to a file in a private folder first. A freeform::Error is the
// expected answer to bad input; any other exception escapes and libFuzzer reports it as a finding
// (an error message without the file's name, "map::at", "basic_string::compare", bad_alloc).

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace fuzz {

/// A folder of this process (under $TMPDIR, /dev/shm when it exists).
inline const std::string& folder()
{
    static const std::string dir = [] {
        std::string base = std::filesystem::exists("/dev/shm") ? "/dev/shm" : std::filesystem::temp_directory_path().string();
        if (const char* t = std::getenv("FREEFORM_FUZZ_TMP")) base = t;
        const std::string d = base + "/freeform-fuzz-" + std::to_string(::getpid());
        std::filesystem::create_directories(d);
        return d;
    }();
    return dir;
}

inline std::string path(const std::string& name) { return folder() + "/" + name; }

inline std::string writeInput(const std::uint8_t* data, std::size_t size, const std::string& name)
{
    const std::string p = path(name);
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    return p;
}

inline std::string slurp(const std::string& p)
{
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// A violated property: print and abort, so libFuzzer keeps the input.
[[noreturn]] inline void fail(const std::string& what)
{
    std::fprintf(stderr, "fuzz property violated: %s\n", what.c_str());
    std::abort();
}

} // namespace fuzz
