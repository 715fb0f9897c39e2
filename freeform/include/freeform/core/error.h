#pragma once
// The one exception type of the library.
//
// Every check on user input (control points, documents, meshes, files) throws freeform::Error
// with a message that names the object, the field or the line that is wrong, so that a
// command-line tool can print it as it is and a user can fix the input without a debugger.

#include <stdexcept>
#include <string>

namespace freeform {

class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

} // namespace freeform
