#pragma once
// Private to the library: the message of a lookup by name that found nothing, naming the objects
// there are (`SOURCE: no object named "x" (objects: a, b)`, or `(the document has no objects)`),
// which Document::object (io/document.cpp) and TypedDocument::object (document/model.cpp) throw
// and the command line prints for --object (docs/cli.md).

#include <string>
#include <vector>

namespace freeform {

std::string noObjectMessage(const std::string& source, const std::string& name, const std::vector<std::string>& names);

} // namespace freeform
