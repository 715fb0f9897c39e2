#pragma once
// The one gate every JSON text of the library passes before it is parsed into a tree (documents,
// glTF, points files, the editor's files): a streaming check, without recursion, that
//   - no value is nested deeper than maxDepth (nlohmann's tree copy, dump and destruction recurse
//     on depth: a text nested tens of thousands deep would overflow the stack),
//   - no object repeats a key (the strict reader does not let the last one silently win); keys are
//     compared after decoding their escapes, so "\u0061" and "a" are the same key.
// See docs/mesh-io.md ("Hostile input").

#include <string>
#include <string_view>

namespace freeform {

/// Deepest nesting of arrays and objects accepted (the top-level value is depth 1).
inline constexpr int kMaxJsonDepth = 256;

/// Error "SOURCE: ... (at PATH)" when the text nests deeper than maxDepth or repeats a key in one
/// object; PATH (its first components) says where, e.g. objects[0].editor. A syntax error stops the check silently: the parse that follows reports it with its position.
void checkJsonText(std::string_view text, const std::string& source, int maxDepth = kMaxJsonDepth);

} // namespace freeform
