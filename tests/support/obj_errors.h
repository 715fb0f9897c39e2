#pragma once
// The OBJ free-form reader's message for a text ("no error" when it reads), for the tests that pin
// its line-numbered errors (test_obj_freeform.cpp, test_obj_freeform_rational.cpp, test_obj_trim.cpp).

#include <string>

#include "freeform/core/error.h"
#include "freeform/io/obj_freeform.h"

namespace freeform::test {

inline std::string objError(const std::string& text)
{
    try {
        parseObjFreeform(text, "x.obj");
    } catch (const Error& e) {
        return std::string(e.what());
    }
    return std::string("no error");
}

} // namespace freeform::test
