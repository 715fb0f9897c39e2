#pragma once
// The points file of freeform interpolate (docs/cli.md): {"points": [[x, y(, z)], ...],
// "params": [...]} ("params" optional), read strictly. Alone in its own file so the fuzz target
// fuzz_points (fuzz/README.md) compiles just this reader, not the command line.

#include <string>
#include <vector>

#include "freeform/io/document.h"

namespace freeform::cli {

struct PointsFile {
    PointColumns points;         // one column per point, 2 or 3 rows
    std::vector<double> params;  // empty: not given
};

/// Reads path; every problem is a freeform::Error naming the file and the field.
PointsFile readPointsFile(const std::string& path);

/// The same from the text of a file named source.
PointsFile parsePointsFile(const std::string& text, const std::string& source);

} // namespace freeform::cli
