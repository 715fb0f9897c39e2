// freeform interpolate's points file (cli/points_file.cpp, compiled alone into the target, not the
// command line). An accepted file has 2 or 3 finite coordinates per point, one column per point,
// and finite parameters; anything else must be a freeform::Error.

#include <freeform/core/error.h>

#include <cmath>
#include <string>

#include "fuzz_common.h"
#include "points_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string text(reinterpret_cast<const char*>(data), size);
    freeform::cli::PointsFile in;
    try {
        in = freeform::cli::parsePointsFile(text, "points.json");
    } catch (const freeform::Error&) {
        return 0;
    }
    if (in.points.rows() != 2 && in.points.rows() != 3) fuzz::fail("a point with neither 2 nor 3 coordinates");
    if (in.points.cols() < 1) fuzz::fail("an accepted points file without points");
    if (!in.points.allFinite()) fuzz::fail("a non-finite coordinate accepted");
    for (double u : in.params)
        if (!std::isfinite(u)) fuzz::fail("a non-finite parameter accepted");
    return 0;
}
