#pragma once
// The freeform command-line tool run in process: the freeform_cli library's run() with stdout and
// stderr captured in strings. Same result type as test::cli (support/process.h), which starts the
// binary; the command-line tests use this one and keep a few runs of the binary for what only a
// process shows (exit status, stdout purity, --help).

#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/command.h"
#include "support/process.h"

namespace freeform::test {

/// `freeform ARGS...` in process: {exit status, stdout, stderr}.
inline ProcessResult runCli(const std::vector<std::string>& args)
{
    std::ostringstream out, err;
    ProcessResult r;
    r.status = freeform::cli::run(args, out, err);
    r.out = out.str();
    r.err = err.str();
    bool help = false;
    std::string line;
    for (const std::string& a : args) {
        help = help || a == "--help" || a == "-h" || a == "--version";
        line += (line.empty() ? "" : " ") + a;
    }
    checkStdoutContract(r, help, line);
    return r;
}

/// A command line split into words as sh splits it when it holds only words, blanks and quotes
/// ('...' literal, "..." with \" \\ \$ \` escapes, \x outside quotes); anything sh would expand or
/// redirect is refused, so a test line means the same here as through test::cli.
inline std::vector<std::string> splitCommandLine(const std::string& line)
{
    std::vector<std::string> words;
    std::string word;
    bool inWord = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (c == ' ' || c == '\t' || c == '\n') {
            if (inWord) words.push_back(word);
            word.clear();
            inWord = false;
        } else if (c == '\'') {
            const std::size_t end = line.find('\'', i + 1);
            if (end == std::string::npos) throw std::invalid_argument("unterminated ' in: " + line);
            word += line.substr(i + 1, end - i - 1);
            i = end;
            inWord = true;
        } else if (c == '"') {
            for (++i; i < line.size() && line[i] != '"'; ++i) {
                if (line[i] == '\\' && i + 1 < line.size() && std::string("\"\\$`").find(line[i + 1]) != std::string::npos) ++i;
                else if (line[i] == '$' || line[i] == '`') throw std::invalid_argument("expansion in: " + line);
                word += line[i];
            }
            if (i >= line.size()) throw std::invalid_argument("unterminated \" in: " + line);
            inWord = true;
        } else if (c == '\\' && i + 1 < line.size()) {
            word += line[++i];
            inWord = true;
        } else if (std::string("|&;<>()$`*?[#~").find(c) != std::string::npos && !(c == '#' && inWord)) {
            throw std::invalid_argument(std::string("shell syntax '") + c + "' in: " + line);
        } else {
            word += c;
            inWord = true;
        }
    }
    if (inWord) words.push_back(word);
    return words;
}

/// `freeform ARGUMENTS` in process, ARGUMENTS written as for test::cli.
inline ProcessResult cliInProcess(const std::string& arguments)
{
    return runCli(splitCommandLine(arguments));
}

} // namespace freeform::test
