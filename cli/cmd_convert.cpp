// freeform convert: between representations of the same geometry.
//   - one object of a document in another form (--to KIND: spline forms, NURBS, Bézier pieces), see
//     cmd_convert_kind.cpp
//   - documents and OBJ free-form geometry (cstype bezier), by the file extensions, see
//     cmd_convert_obj.cpp

#include <memory>

#include "convert.h"

namespace freeform::cli {

namespace {

Json convert(const ConvertOptions& o)
{
    const bool partIn = !o.positional.empty() && isPartFileName(o.positional[0]);
    if (partIn || isPartFileName(o.output)) {
        expectPositional(o.positional, 1, "the part (freeform convert PART.step -o OUT.step|.iges|.json)");
        if (given(o.toGiven) || given(o.endGiven))
            throw UsageError("a part takes only -o (freeform convert PART.step -o OUT.step|.iges|.json)");
        if (partIn && given(o.objectGiven))
            throw UsageError("option --object: picks the part of a document (freeform convert DOC.json --object NAME -o OUT.step)");
        if (partIn && !isPartFileName(o.output) && lowerExtension(o.output) != ".json")
            throw UsageError("option -o: a part is written as STEP, IGES, BRep (.step .stp .iges .igs .brep) or a document (.json)");
        if (!partIn && lowerExtension(o.positional[0]) != ".json")
            throw UsageError("option -o: STEP and IGES are written from a part: a STEP or IGES file or a document (.json)");
        return partConvert(o.positional[0], o.output, given(o.objectGiven) ? std::optional<std::string>(o.object) : std::nullopt);
    }
    if (given(o.toGiven)) return convertKind(o);
    if (given(o.endGiven)) throw UsageError("option --end: goes with --to deboor_spline only");
    return convertObjFreeform(o);
}

} // namespace

Action defineConvert(CLI::App& app)
{
    auto o = std::make_shared<ConvertOptions>();
    // --to and --end are checked by convertKind: docs/cli.md and the tests pin their messages.
    app.footer("Five forms:\n"
               "  freeform convert DOC.json --object NAME --to bezier_spline|deboor_spline\n"
               "                   [--end open|clamped|closed] -o OUT.json\n"
               "  freeform convert DOC.json -o OUT.obj   (Bézier curves and surfaces as OBJ cstype bezier)\n"
               "  freeform convert IN.obj -o OUT.json    (OBJ free-form Bézier geometry to a document)\n"
               "  freeform convert PART.step|.iges -o OUT.step|.iges|.json   (a part, every face as a\n"
               "                   B-spline surface; prints the counts and Open CASCADE's validity check;\n"
               "                   .json: a document of one part object)\n"
               "  freeform convert DOC.json [--object NAME] -o OUT.step|.iges   (a document's part)\n"
               "Exit status: 0 ok, 1 bad input, 2 bad usage.");
    addPositionals(app, "IN", o->positional, "the document (DOC.json) or OBJ file (IN.obj) to convert");
    o->objectGiven = app.add_option("--object", o->object, "the spline to convert (with --to), or the part to write as STEP or IGES")->type_name("NAME");
    o->toGiven = app.add_option("--to", o->to,
                                "bezier_spline: the A-frame turns a deboor_spline into Bézier segments; "
                                "deboor_spline: recovers the de Boor points of a C2 cubic bezier_spline")
                     ->type_name("bezier_spline|deboor_spline");
    o->endGiven = app.add_option("--end", o->end,
                                 "with --to deboor_spline: the end condition of the de Boor form, open or clamped "
                                 "for an open spline (default clamped), closed for a closed one (the default there)")
                      ->type_name("open|clamped|closed");
    app.add_option("-o,--output", o->output, "the file to write (written to a temporary file, then renamed)")
        ->type_name("FILE")
        ->required();
    return [o] { return convert(*o); };
}

} // namespace freeform::cli
