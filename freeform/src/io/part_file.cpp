// Which files are CAD parts (io/part_file.h).

#include "freeform/io/part_file.h"

#include <cctype>
#include <filesystem>

namespace freeform {

bool isPartFileName(const std::string& path)
{
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".step" || ext == ".stp" || ext == ".iges" || ext == ".igs" || ext == ".brep";
}

} // namespace freeform
