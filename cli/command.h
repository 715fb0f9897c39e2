#pragma once
// The `freeform` command-line tool as a library: one file per command (cmd_*.cpp), each declaring
// its options on a CLI11 subcommand and turning the parsed options into the JSON it prints. The
// list of commands is cli/commands.cpp; cli/main.cpp only calls run().
//
// Contract (docs/cli.md): results are JSON on stdout; errors are one line "error: ..." on stderr
// with exit status 1 for bad input and 2 for bad usage, and then nothing is written to stdout and
// no output file is left behind.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <functional>
#include <map>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "freeform/document/model.h"
#include "freeform/io/part_file.h" // isPartFileName: which inputs and outputs are parts
#include "freeform/curve/continuity.h"
#include "freeform/curve/interpolation.h"
#include "freeform/io/document.h"
#include "freeform/mesh/polygon_mesh.h"
#include "freeform/tessellate/tessellate.h"

namespace freeform {
struct Part;      // freeform/brep/part.h
struct PartCheck; // freeform/brep/part.h
} // namespace freeform

namespace freeform::cli {

using Json = nlohmann::ordered_json;

/// Bad usage found after parsing (a value out of its range, options that do not go together):
/// exit status 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// What a command does once its options are parsed: the JSON result it prints. Throws UsageError
/// (exit 2) or freeform::Error (exit 1); it never writes to stdout itself.
using Action = std::function<Json()>;

struct Command {
    std::string name;
    std::string summary; // one line, listed by `freeform --help`
    /// Declares the command's options on `app` (the subcommand) and returns the action that runs
    /// on the values CLI11 parsed into them. `freeform NAME --help` is generated from `app`.
    Action (*define)(CLI::App& app);
};

/// The commands, in the order `freeform --help` lists them (cli/commands.cpp).
const std::vector<Command>& commands();

/// Runs the tool on `args` (without the program name): the JSON result on `out`, an error line
/// on `err`; returns the exit status (0 ok, 1 bad input, 2 bad usage).
int run(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

// --- option helpers ----------------------------------------------------------------------------

/// The positional arguments of a command, collected by CLI11; the command checks their count.
CLI::Option* addPositionals(CLI::App& app, const std::string& name, std::vector<std::string>& values,
                            const std::string& description);

/// Exactly `count` positional arguments, else UsageError ("missing WHAT" / "unexpected argument").
void expectPositional(const std::vector<std::string>& positional, std::size_t count, const std::string& what);

/// A numeric option: an integer must be written in decimal, a floating-point number must be
/// finite (CLI11 would also read hex, octal and nan); CLI11 reports anything else as bad usage.
CLI::Option* addNumber(CLI::App& app, const std::string& name, int& value, const std::string& description);
CLI::Option* addNumber(CLI::App& app, const std::string& name, long& value, const std::string& description);
CLI::Option* addNumber(CLI::App& app, const std::string& name, double& value, const std::string& description);

/// A switch: no value (--flag=x is bad usage) and not given twice, like every other option.
CLI::Option* addFlag(CLI::App& app, const std::string& name, bool& value, const std::string& description);

/// Whether the option was given on the command line.
inline bool given(const CLI::Option* option) { return option->count() > 0; }

/// A number from a string argument (e.g. --at); UsageError naming the option when it is not finite.
double parseNumber(const std::string& text, const std::string& option);
/// "a,b,c" into exactly `count` numbers (count 0: any positive count).
std::vector<double> parseNumberList(const std::string& text, const std::string& option, std::size_t count);

/// A point as a JSON array.
Json pointJson(const double* p, int dim);


/// `freeform eval` picks one evaluator by the object's row of the kind table (document/kinds.h:
/// its parameters). Each, given the object, the text of --at and the derivative order K, parses
/// --at (usage errors), then prints the document layer's evaluate() (document/operations.h), which
/// checks the domain.
using Evaluator = Json (*)(const TypedDocument& doc, const TypedObject& object, const std::string& at, int order);
/// The evaluator for a kind; nullptr when eval does not support it.
Evaluator evaluatorFor(const KindInfo& kind); // cli/commands.cpp

Json evalObject(const TypedDocument&, const TypedObject&, const std::string& at, int order);      // eval_object.cpp: T, U,V, a part's FACE,U,V
Json evalLattice(const TypedDocument&, const TypedObject&, const std::string& at, int order);     // eval_lattice.cpp
Json evalSubdivision(const TypedDocument&, const TypedObject&, const std::string& at, int order); // eval_subdivision.cpp

/// `freeform interpolate --degree P` (interpolate_nurbs.cpp): writes the nurbs_curve "interpolant".
Json interpolateNurbsCommand(const PointColumns& points, const std::vector<double>& params, Parametrization param,
                             int degree, const std::vector<double>& start, const std::vector<double>& end,
                             const std::string& source, const std::string& output);

/// The file's extension in lower case, with its dot (".json"), or empty; commands.cpp.
std::string lowerExtension(const std::string& path);

/// The counts `info` and `convert` print for a part, in their order: faces, edges, vertices,
/// shells, solids, closed, units (info_part.cpp).
void addPartCounts(Json& j, const Part& part, const PartCheck& check);
/// `freeform info` on a STEP or IGES part, or on a document's only part (info_part.cpp).
Json partInfo(const std::string& path, bool details);
/// The report `info` prints for a part (info_part.cpp).
Json partReport(const Part& part, bool details);
/// The part of a document: the object called `name`, or its only part (or trimmed surface, as a
/// part of one face); `chosen` receives its name. Error naming the document when there is none,
/// several, or the object is of another kind (info_part.cpp).
Part documentPart(const std::string& path, const std::optional<std::string>& name, std::string& chosen);
/// `freeform tessellate` on a STEP or IGES part (tessellate_part.cpp): the certified watertight
/// mesh (freeform/brep/part_mesh.h) written to `output` (.obj, .ply, .stl).
Json partTessellate(const std::string& path, const std::string& output, double tolerance, long long maxTriangles);
/// The same for a part in memory (a document's part object; tessellate_part.cpp).
Json partMeshCommand(const Part& part, const std::string& output, double tolerance, long long maxTriangles);
/// `freeform ffd` on a part (ffd_part.cpp): composed exactly with the lattice, faces and edges over
/// Open CASCADE's degree approximated within `tolerance` (<= 0: 1e-6 of the part's size), written
/// as STEP or IGES; or, to OUT.json, composed exactly (no cap) into a document of one part object.
Json partFfd(const std::string& path, const std::string& output, const std::string& latticeName,
             const Lattice& lattice, double strength, double tolerance, int threads);
/// The two corners of a part's box (Part::bounds), and its vertex count (ffd_part.cpp): a STEP,
/// IGES or BRep file, or a document's part (the object `object`, or its only part).
Lattice::Points partBoxCorners(const std::string& path, const std::optional<std::string>& object, long long& vertices);
/// `freeform convert` of a part (ffd_part.cpp): a STEP or IGES file to STEP, IGES or a document
/// (one part object named after the file), or a document's part (`object`, or its only one) to
/// STEP or IGES.
Json partConvert(const std::string& path, const std::string& output, const std::optional<std::string>& object);

// The commands (one file each).
Action defineBench(CLI::App& app);       // cmd_bench.cpp
Action defineContinuity(CLI::App& app);  // cmd_continuity.cpp
Action defineConvert(CLI::App& app);     // cmd_convert.cpp
Action defineEval(CLI::App& app);        // cmd_eval.cpp
Action defineFfd(CLI::App& app);         // cmd_ffd.cpp
Action defineInfo(CLI::App& app);        // cmd_info.cpp
Action defineInterpolate(CLI::App& app); // cmd_interpolate.cpp
Action defineLattice(CLI::App& app);     // cmd_lattice.cpp
Action defineSubdivide(CLI::App& app);   // cmd_subdivide.cpp
Action defineTessellate(CLI::App& app);  // cmd_tessellate.cpp

} // namespace freeform::cli
