#pragma once
// Whole-file reads and atomic writes.

#include <functional>
#include <ostream>
#include <string>

#include "freeform/core/error.h"

namespace freeform {

/// Reads a whole file; Error naming the path when it cannot.
std::string readFile(const std::string& path);

/// Writes text to path atomically, so that a failure, or the process being killed at any moment,
/// never leaves a half-written or clobbered file (see docs/mesh-io.md, "Errors"). On Linux the
/// bytes go to an unnamed file in path's folder (O_TMPFILE), are flushed to the disk (fsync), and
/// only then get a name: path itself when it does not exist yet, otherwise a temporary name that is
/// renamed over path. Where the file system refuses unnamed files (or /proc is missing) the bytes go
/// to a named temporary file beside path instead, renamed over it on success; a process killed
/// mid-write can then leave that temporary file behind. The new file's permissions are those of an
/// ordinary create (0666 less the umask). Throws Error on failure.
void writeFileAtomically(const std::string& path, const std::string& text);

/// The same for a writer that fills a stream: write(std::ostream&) runs against the new file.
template <typename Writer>
void writeFileAtomicallyWith(const std::string& path, Writer&& write);

namespace detail {

/// How writeFileAtomically holds the bytes before they get a name: Anonymous (O_TMPFILE, falling
/// back to Named where refused) or Named (a temporary file beside the target: the fallback, which
/// tests choose directly to cover it).
enum class TemporaryFile { Anonymous, Named };

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                         TemporaryFile kind = TemporaryFile::Anonymous);

} // namespace detail

template <typename Writer>
void writeFileAtomicallyWith(const std::string& path, Writer&& write)
{
    detail::writeFileAtomically(path, [&write](std::ostream& out) { write(out); });
}

} // namespace freeform
