// freeform convert between a document and OBJ free-form geometry (cstype [rat] bezier|bspline), by extension:
//   DOC.json -o OUT.obj   Bézier curves, open Bézier splines, Bézier surfaces, their rational forms,
//                         NURBS curves and surfaces and trimmed surfaces (curv2, trim, hole) to OBJ
//   IN.obj   -o OUT.json  the OBJ's free-form elements to a document

#include <filesystem>

#include "convert.h"
#include "freeform/core/error.h"
#include "freeform/io/obj_freeform.h"

namespace freeform::cli {

Json convertObjFreeform(const ConvertOptions& o)
{
    expectPositional(o.positional, 1, "the input file (freeform convert IN -o OUT)");
    const std::string input = o.positional[0];
    const std::string output = o.output;
    const std::string in = lowerExtension(input), out = lowerExtension(output);
    Json result;
    if (in == ".json" && out == ".obj") {
        const Document doc = readDocument(input);
        const std::string name = given(o.objectGiven) ? o.object : std::string();
        writeObjFreeform(doc, output, name);
        Json names = Json::array();
        for (const DocumentObject& o : doc.objects)
            if (name.empty() || o.name == name) names.push_back(o.name);
        result["output"] = output;
        result["objects"] = std::move(names);
    } else if (in == ".obj" && out == ".json") {
        if (given(o.objectGiven)) throw UsageError("option --object applies to a document input");
        const Document doc = readObjFreeform(input);
        if (doc.objects.empty()) throw Error(input + ": no free-form curves or surfaces (cstype [rat] bezier|bspline) found");
        writeDocument(doc, output);
        Json names = Json::array();
        for (const DocumentObject& o : doc.objects) names.push_back(o.name);
        result["output"] = output;
        result["objects"] = std::move(names);
    } else {
        throw UsageError("convert without --to goes from .json to .obj or from .obj to .json (got " +
                         (in.empty() ? std::string("no extension") : in) + " to " + (out.empty() ? std::string("no extension") : out) + ")");
    }
    return result;
}

} // namespace freeform::cli
