// The commands of `freeform`, in the order `freeform --help` lists them, and which evaluator
// `freeform eval` uses for each kind of the kind table. A new command is a new cmd_NAME.cpp with a defineNAME (declared in
// command.h) and one line here.

#include "command.h"

#include <cctype>
#include <filesystem>

namespace freeform::cli {

const std::vector<Command>& commands()
{
    static const std::vector<Command> list = {
        {"eval", "evaluate an object at a parameter (point, derivatives)", defineEval},
        {"continuity", "continuity of every joint of a spline (C and G levels, jumps)", defineContinuity},
        {"interpolate", "C2 cubic spline through points (natural, clamped, periodic ends)", defineInterpolate},
        {"convert", "convert splines between forms, documents to and from OBJ free-form", defineConvert},
        {"tessellate", "surfaces (document, .bpt, STEP or IGES part) to a triangle mesh", defineTessellate},
        {"subdivide", "the limit surface of a control cage (Catmull-Clark or Loop) as a triangle mesh", defineSubdivide},
        {"info", "topology of a mesh file (counts, boundary, manifoldness, genus)", defineInfo},
        {"lattice", "write the identity FFD lattice around a mesh", defineLattice},
        {"ffd", "deform a mesh file or a document through a lattice (free-form deformation)", defineFfd},
        {"bench", "measure free-form deformation speed on this machine", defineBench},
    };
    return list;
}

std::string lowerExtension(const std::string& path)
{
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

Evaluator evaluatorFor(const KindInfo& kind)
{
    if (!kind.supports(KindOperation::Evaluate)) return nullptr;
    switch (kind.parameters) {
    case KindParameters::T:
    case KindParameters::UV: return evalObject;
    case KindParameters::STU: return evalLattice;
    case KindParameters::FaceUV: return kind.nature == KindNature::Part ? evalObject : evalSubdivision;
    }
    return nullptr;
}

} // namespace freeform::cli
