// freeform eval: evaluate an object of a document at a parameter.

#include <iostream>

#include "command.h"
#include "freeform/core/error.h"

namespace freeform::cli {
namespace {

int runEval(const std::vector<std::string>& argv)
{
    const Args args(argv, {"object", "at", "derivatives"}, {});
    args.expectPositional(1, "the document (freeform eval DOC.json --object NAME --at T)");
    const std::string name = args.required("object");
    const std::string at = args.required("at");
    int order = 0;
    if (const auto k = args.get("derivatives")) {
        order = parseInteger(*k, "--derivatives");
        if (order < 0) throw UsageError("option --derivatives: the order must not be negative");
    }
    const Document doc = readDocument(args.positional()[0]);
    const DocumentObject& object = doc.object(name);
    const std::string type = objectType(object.data);
    const auto it = evaluators().find(type);
    if (it == evaluators().end()) throw Error(doc.source + ": object \"" + name + "\": eval does not support type \"" + type + "\" yet");
    printJson(it->second(doc, object, at, order));
    return 0;
}

const RegisterCommand reg({"eval", "evaluate an object at a parameter (point, derivatives)",
                           "usage: freeform eval DOC.json --object NAME --at PARAM [--derivatives K]\n"
                           "\n"
                           "Evaluates the object NAME of the document at PARAM and prints one JSON object.\n"
                           "\n"
                           "  --object NAME     the object to evaluate\n"
                           "  --at PARAM        the parameter: T for a curve (in [0, 1]) or a spline (in [0, sum of\n"
                           "                    intervals]); U,V for a surface; S,T,U for a lattice; FACE,U,V for a\n"
                           "                    subdivision surface\n"
                           "  --derivatives K   also print the derivatives of orders 1..K (default 0: none);\n"
                           "                    orders above the degree are zero vectors\n"
                           "\n"
                           "Curve output: {\"object\": NAME, \"t\": T, \"point\": [...], \"derivatives\": [[...], ...]}\n"
                           "with derivatives[k-1] the k-th derivative. Numbers read back to the same double.\n"
                           "Exit status: 0 ok, 1 bad input (file, document, object), 2 bad usage.\n",
                           runEval});

} // namespace
} // namespace freeform::cli
