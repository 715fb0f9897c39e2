#pragma once
// How a file path is shown where a long one would not fit: the recent files of File > Open recent
// and of the Open dialog. The full path goes in the entry's tooltip.

#include <cstddef>
#include <string>

namespace freeform::editor {

/// `path` itself when it has at most `maxChars` characters (UTF-8 code points), else its
/// beginning, "...", and its end (the file name kept whole where it fits), cut between code points.
std::string shortPathLabel(const std::string& path, std::size_t maxChars = 64);

} // namespace freeform::editor
