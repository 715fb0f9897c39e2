// freeform_cad without Open CASCADE (FREEFORM_BUILD_CAD=OFF; cad/CMakeLists.txt): the interface of
// cad_file.h, whose reader and writer refuse every file with an error naming it. The front ends
// link this as they link the real library, so parts from documents, trimmed surfaces built in
// code, their tessellation and deformation work the same in such a build.

#include "freeform/cad/cad_file.h"

#include "freeform/core/error.h"
#include "freeform/io/part_file.h"

namespace freeform {

namespace {

[[noreturn]] void refuse(const std::string& path)
{
    throw Error(path + ": this freeform was built without Open CASCADE (FREEFORM_BUILD_CAD=OFF): it reads and writes no "
                       "STEP, IGES or BRep file");
}

} // namespace

bool cadFilesSupported() { return false; }

void requireCadFiles(const std::string& path) { refuse(path); }

bool isCadFile(const std::string& path) { return isPartFileName(path); }

Part readCadFile(const std::string& path, std::vector<std::string>*) { refuse(path); }

/// Open CASCADE's B-spline degree cap (Geom_BSplineSurface::MaxDegree() in 7.6), which the real
/// library reads from Open CASCADE: the degree a part must stay within to be written by a build
/// that has it.
int cadMaxDegree() { return 25; }

CadWriteReport writeCadFile(const Part&, const std::string& path) { refuse(path); }

} // namespace freeform
