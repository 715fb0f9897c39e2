#pragma once
// The command line's lookup of an object by --object NAME in a typed document, with the reader's
// message when there is none (`DOC: no object named "x" (objects: a, b)`, docs/cli.md), which the
// commands have always printed.

#include <string>

#include "freeform/core/error.h"
#include "freeform/document/model.h"

namespace freeform::cli {

inline const TypedObject& objectNamed(const TypedDocument& doc, const std::string& name)
{
    if (const TypedObject* o = doc.find(name)) return *o;
    doc.toDocument().object(name); // throws: no object named "NAME" (objects: ...)
    throw Error(doc.source + ": no object named \"" + name + "\"");
}

} // namespace freeform::cli
