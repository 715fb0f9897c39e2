// freeform convert: between representations of the same geometry.
//   - spline forms inside a document (--to bezier_spline|deboor_spline), see cmd_convert_spline.cpp
//   - documents and OBJ free-form geometry (cstype bezier), by the file extensions, see
//     cmd_convert_obj.cpp

#include "command.h"

namespace freeform::cli {

int convertSpline(const Args& args);   // cmd_convert_spline.cpp
int convertObjFreeform(const Args& args); // cmd_convert_obj.cpp

namespace {

int runConvert(const std::vector<std::string>& argv)
{
    const Args args(argv, {"object", "to", "end", "output"}, {});
    if (args.has("to")) return convertSpline(args);
    if (args.has("end")) throw UsageError("option --end: goes with --to deboor_spline only");
    return convertObjFreeform(args);
}

const RegisterCommand reg({"convert", "convert splines between forms, documents to and from OBJ free-form",
                           "usage: freeform convert DOC.json --object NAME --to bezier_spline|deboor_spline\n"
                           "                        [--end open|clamped|closed] -o OUT.json\n"
                           "       freeform convert DOC.json -o OUT.obj     (Bézier curves and surfaces as OBJ cstype bezier)\n"
                           "       freeform convert IN.obj -o OUT.json      (OBJ free-form Bézier geometry to a document)\n"
                           "\n"
                           "  --object NAME   the spline to convert (with --to)\n"
                           "  --to FORM       bezier_spline: the A-frame turns a deboor_spline into Bézier segments;\n"
                           "                  deboor_spline: recovers the de Boor points of a C2 cubic bezier_spline\n"
                           "  --end END       with --to deboor_spline: the end condition of the de Boor form,\n"
                           "                  open or clamped for an open spline (default clamped), closed for a\n"
                           "                  closed one (the default there)\n"
                           "  -o, --output F  the file to write (written to a temporary file, then renamed)\n"
                           "\n"
                           "Exit status: 0 ok, 1 bad input, 2 bad usage.\n",
                           runConvert});

} // namespace
} // namespace freeform::cli
