#pragma once
// Runs a command line through the shell and captures stdout, stderr and the exit status, for the
// command-line contract tests. Every run of the command-line tool (cli() here, runCli() in
// support/cli.h) also checks docs/cli.md's stdout contract: one JSON object on one line, or nothing
// (and nothing after an error); --help and --version, which print their text there, are the
// exceptions.

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

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

/// `text` as one word for sh, whatever it holds (spaces, quotes, non-ASCII): in single quotes, each
/// single quote in it written as '\''.
inline std::string shellQuote(const std::string& text)
{
    std::string quoted = "'";
    for (const char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

/// Runs `commandLine` (already quoted for sh) with stdout and stderr captured in files.
inline ProcessResult run(const std::string& commandLine)
{
    static int counter = 0;
    const std::string base = std::string(FREEFORM_TEST_TMP) + "/run" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
    const std::string full = commandLine + " >" + shellQuote(base + ".out") + " 2>" + shellQuote(base + ".err") + " </dev/null";
    const int raw = std::system(full.c_str());
    ProcessResult r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = slurp(base + ".out");
    r.err = slurp(base + ".err");
    std::remove((base + ".out").c_str());
    std::remove((base + ".err").c_str());
    return r;
}

/// docs/cli.md: stdout holds one JSON object on one line, or nothing; nothing when the command
/// failed. `asksForHelp`: the arguments hold --help, -h or --version (their text goes to stdout).
inline void checkStdoutContract(const ProcessResult& r, bool asksForHelp, const std::string& arguments)
{
    if (asksForHelp || r.out.empty()) return;
    INFO("freeform " << arguments << "\nstdout: " << r.out.substr(0, 400));
    CHECK(r.status == 0);
    CHECK(r.out.back() == '\n');
    CHECK(r.out.find('\n') == r.out.size() - 1);
    bool object = false;
    try {
        object = nlohmann::json::parse(r.out).is_object();
    } catch (const nlohmann::json::exception&) {
    }
    CHECK(object);
}

/// The freeform command-line tool with arguments.
inline ProcessResult cli(const std::string& arguments)
{
    ProcessResult r = run(shellQuote(FREEFORM_CLI) + " " + arguments);
    const std::string padded = " " + arguments + " ";
    const bool help = padded.find(" --help ") != std::string::npos || padded.find(" -h ") != std::string::npos ||
                      padded.find(" --help=") != std::string::npos || padded.find("'--help'") != std::string::npos ||
                      padded.find(" --version ") != std::string::npos;
    checkStdoutContract(r, help, arguments);
    return r;
}

} // namespace freeform::test
