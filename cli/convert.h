#pragma once
// The options of `freeform convert`, shared by its two halves: cmd_convert_kind.cpp (--to) and
// cmd_convert_obj.cpp (documents to and from OBJ free-form).

#include "command.h"

namespace freeform::cli {

struct ConvertOptions {
    std::vector<std::string> positional;
    std::string object, to, end, output;
    const CLI::Option* objectGiven = nullptr;
    const CLI::Option* toGiven = nullptr;
    const CLI::Option* endGiven = nullptr;
};

Json convertKind(const ConvertOptions& o);        // cmd_convert_kind.cpp: --to
Json convertObjFreeform(const ConvertOptions& o); // cmd_convert_obj.cpp

} // namespace freeform::cli
