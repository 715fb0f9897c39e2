#include "freeform/io/file.h"

#include <fstream>
#include <sstream>
#include <system_error>

namespace freeform {

std::string readFile(const std::string& path)
{
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw Error(path + ": is a directory, not a file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot open the file for reading");
    std::ostringstream ss;
    ss << in.rdbuf();
    if (in.bad()) throw Error(path + ": reading failed");
    return ss.str();
}

void writeFileAtomically(const std::string& path, const std::string& text)
{
    writeFileAtomicallyWith(path, [&](std::ostream& out) { out.write(text.data(), static_cast<std::streamsize>(text.size())); });
}

} // namespace freeform
