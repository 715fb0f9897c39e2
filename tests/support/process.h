#pragma once
// Runs a command line through the shell and captures stdout, stderr and the exit status, for the
// command-line contract tests.

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace freeform::test {

struct ProcessResult {
    int status = -1;
    std::string out;
    std::string err;
};

inline std::string slurp(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

inline void writeText(const std::string& path, const std::string& text)
{
    std::ofstream(path, std::ios::binary) << text;
}

/// Runs `commandLine` (already quoted for sh) with stdout and stderr captured in files.
inline ProcessResult run(const std::string& commandLine)
{
    static int counter = 0;
    const std::string base = std::string(FREEFORM_TEST_TMP) + "/run" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
    const std::string full = commandLine + " >" + base + ".out 2>" + base + ".err </dev/null";
    const int raw = std::system(full.c_str());
    ProcessResult r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = slurp(base + ".out");
    r.err = slurp(base + ".err");
    std::remove((base + ".out").c_str());
    std::remove((base + ".err").c_str());
    return r;
}

/// The freeform command-line tool with arguments.
inline ProcessResult cli(const std::string& arguments)
{
    return run(std::string("'") + FREEFORM_CLI + "' " + arguments);
}

} // namespace freeform::test
