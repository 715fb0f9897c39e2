#pragma once
// STEP, IGES and BRep parts through Open CASCADE's data exchange (docs/cad.md, "Reading").
//
// The freeform_cad library is the only code that includes Open CASCADE; its interface holds only
// freeform's own types (brep/part.h), so the CLI, the editor and Python link it without seeing
// Open CASCADE. Every face becomes a trimmed surface in its exact NURBS form, with its trims and
// edges in the file's own parameters (brep/parameter_map.h); coordinates stay in the file's length
// unit, which the part names. Open CASCADE's messages are collected, never printed.

#include <string>
#include <vector>

#include "freeform/brep/part.h"

namespace freeform {

/// Whether this build reads and writes STEP, IGES and BRep files: false where freeform_cad was
/// built without Open CASCADE (FREEFORM_BUILD_CAD=OFF), whose readCadFile and writeCadFile throw
/// freeform::Error naming the file.
bool cadFilesSupported();
/// Throws that error for `path` in a build without Open CASCADE; nothing in one with it (for a
/// front end that refuses before work that would end in writing the file).
void requireCadFiles(const std::string& path);

/// Whether the path names a STEP (.step .stp), IGES (.iges .igs) or BRep (.brep) file (by its
/// extension, in any case): io/part_file.h's isPartFileName.
bool isCadFile(const std::string& path);

/// Reads a STEP, IGES or BRep file into a part (a BRep file, Open CASCADE's own format, has no
/// unit: its part is in millimetres, Open CASCADE's default). Throws freeform::Error naming the file, and the face or
/// edge (by its index, counted from 1 as Open CASCADE's maps count them) whose geometry has no
/// exact rational form (offset curves and surfaces, and other kinds freeform does not read).
/// Open CASCADE's warnings are appended to `warnings` when it is given, else handed to
/// freeform::warn (core/warning.h) like every warning of the library.
Part readCadFile(const std::string& path, std::vector<std::string>* warnings = nullptr);

/// The highest B-spline degree Open CASCADE (and so the writer) takes: 25.
int cadMaxDegree();

/// What writing a part found (docs/cad.md, "Writing").
struct CadWriteReport {
    bool valid = false;       // BRepCheck_Analyzer finds the written shape valid
    int fittedPcurves = 0;    // trims written as fitted B-splines (see occt_write.cpp)
    double maxPcurveGap = 0;  // the largest measured 3D distance of a fitted trim from the exact one
    int raisedTolerances = 0; // edges whose tolerance was raised to their measured gap (see occt_write.cpp)
    double maxTolerance = 0;  // the largest edge tolerance written
};

/// Writes the part as STEP (.step .stp), IGES (.iges .igs, B-rep entities) or BRep (.brep, Open
/// CASCADE's own format; only a part in millimetres, since the format has no unit), in the part's unit:
/// faces as B-spline surfaces of their NURBS, edges as B-spline curves, trims in the surfaces'
/// parameters. Throws freeform::Error naming the file, and the face or edge whose degree is over
/// Open CASCADE's 25; nothing is written then (the file is written beside the target and renamed).
CadWriteReport writeCadFile(const Part& part, const std::string& path);

} // namespace freeform
