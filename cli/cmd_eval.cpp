// freeform eval: evaluate an object of a document at a parameter.

#include <memory>

#include "command.h"
#include "freeform/core/error.h"

namespace freeform::cli {
namespace {

struct EvalOptions {
    std::vector<std::string> positional;
    std::string object, at;
    int derivatives = 0;
};

Json eval(const EvalOptions& o)
{
    expectPositional(o.positional, 1, "the document (freeform eval DOC.json --object NAME --at T)");
    if (o.derivatives < 0) throw UsageError("option --derivatives: the order must not be negative");
    const TypedDocument doc = TypedDocument::read(o.positional[0]);
    const TypedObject& object = doc.object(o.object);
    const Evaluator evaluator = evaluatorFor(object.info());
    if (!evaluator) throw Error(doc.what(object) + ": eval does not support type \"" + object.type() + "\" yet");
    return evaluator(doc, object, o.at, o.derivatives);
}

} // namespace

Action defineEval(CLI::App& app)
{
    auto o = std::make_shared<EvalOptions>();
    app.footer("Evaluates the object NAME of the document at PARAM and prints one JSON object.\n"
               "Curve output: {\"object\": NAME, \"t\": T, \"point\": [...], \"derivatives\": [[...], ...]}\n"
               "with derivatives[k-1] the k-th derivative. Numbers read back to the same double.\n"
               "Exit status: 0 ok, 1 bad input (file, document, object), 2 bad usage. See docs/cli.md.");
    addPositionals(app, "DOC.json", o->positional, "the document");
    app.add_option("--object", o->object, "the object to evaluate")->type_name("NAME")->required();
    app.add_option("--at", o->at,
                   "the parameter: T for a curve (in [0, 1]) or a spline (in [0, sum of intervals]); U,V for a "
                   "surface; S,T,U for a lattice; FACE,U,V for a subdivision surface")
        ->type_name("PARAM")
        ->required();
    addNumber(app, "--derivatives", o->derivatives,
              "also print the derivatives of orders 1..K (none when 0); orders above the degree are zero vectors")
        ->type_name("K")
        ->capture_default_str();
    return [o] { return eval(*o); };
}

} // namespace freeform::cli
