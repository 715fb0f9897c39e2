#pragma once
// The command-line tests' check of a refused run (docs/cli.md, "Errors"): the exit status (1 bad
// input, 2 bad usage), nothing on stdout, and exactly one "error: ..." line on stderr that holds
// `fragment`. Header only (Catch2 checks).

#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

#include "support/process.h"

namespace freeform::test {

inline void requireError(const ProcessResult& r, int status, const std::string& fragment)
{
    INFO("stderr: " << r.err);
    CHECK(r.status == status);
    CHECK(r.out.empty());
    CHECK(r.err.rfind("error: ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.err.find(fragment) != std::string::npos);
}

} // namespace freeform::test
