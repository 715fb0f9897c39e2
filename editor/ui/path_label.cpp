#include "ui/path_label.h"

#include <algorithm>

namespace freeform::editor {

namespace {

bool continuationByte(char c) { return (static_cast<unsigned char>(c) & 0xC0) == 0x80; }

std::size_t codePoints(const std::string& s, std::size_t from = 0)
{
    std::size_t n = 0;
    for (std::size_t i = from; i < s.size(); ++i) n += !continuationByte(s[i]);
    return n;
}

/// The byte offset where code point `k` of `s` starts (s.size() past the last one).
std::size_t codePointOffset(const std::string& s, std::size_t k)
{
    for (std::size_t i = 0, seen = 0; i < s.size(); ++i)
        if (!continuationByte(s[i]) && seen++ == k) return i;
    return s.size();
}

} // namespace

std::string shortPathLabel(const std::string& path, std::size_t maxChars)
{
    const std::size_t total = codePoints(path);
    if (total <= maxChars || maxChars < 16) return path;
    const std::size_t keep = maxChars - 3; // "..." takes three
    const std::size_t slash = path.find_last_of('/');
    const std::size_t name = slash == std::string::npos ? total : codePoints(path, slash); // "/name"
    const std::size_t tail = std::max(keep / 2, std::min(name, keep - 8));
    const std::size_t head = keep - tail;
    return path.substr(0, codePointOffset(path, head)) + "..." + path.substr(codePointOffset(path, total - tail));
}

} // namespace freeform::editor
