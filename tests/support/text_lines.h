#pragma once
// A text cut into lines, a line into words (what the file-format tests compare by hand). Header only.

#include <sstream>
#include <string>
#include <vector>

namespace freeform::test {

/// The lines of `text` (without their '\n').
inline std::vector<std::string> lines(const std::string& text)
{
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) out.push_back(l);
    return out;
}

/// The blank-separated words of `line`.
inline std::vector<std::string> words(const std::string& line)
{
    std::vector<std::string> out;
    std::istringstream in(line);
    for (std::string w; in >> w;) out.push_back(w);
    return out;
}

} // namespace freeform::test
