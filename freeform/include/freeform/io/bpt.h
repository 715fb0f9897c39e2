#pragma once
// The .bpt text format of patch complexes (the Utah teapot's format), moved here from
// surface/patch_complex.h: geometry knows no file formats.

#include <string>

#include "freeform/surface/patch_complex.h"

namespace freeform {

/// Parses the .bpt text format: the number of patches on the first line, then per patch a line
/// "m n" (degrees) and (m+1)(n+1) lines "x y z", point (i, j) on line i*(n+1) + j of the patch.
/// Blank lines are skipped; anything else that does not fit (a missing or extra number, a
/// non-number, a degree outside 1..67, fewer or more patches than announced) is an Error naming
/// `source` and the line.
PatchComplex parseBpt(const std::string& text, const std::string& source = "bpt");

/// Reads a .bpt file (Error naming the path when it cannot be read or parsed).
PatchComplex readBpt(const std::string& path);

/// The complex in .bpt form (numbers in shortest round-trip form).
std::string formatBpt(const PatchComplex& complex);

} // namespace freeform
