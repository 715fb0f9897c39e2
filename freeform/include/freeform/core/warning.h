#pragma once
// Warnings: what the library noticed and accepted, but a person should hear about (a PLY header
// line kept as a comment, an OpenSubdiv warning). The library never prints: it hands each message
// to the handler the caller set, one for the whole process. The front ends route them: the CLI to
// one `warning:` line on stderr (stdout keeps its JSON), the editor to its status line, Python to
// `warnings.warn`. Without a handler the messages are dropped. Errors are never warnings: they
// throw freeform::Error.

#include <functional>
#include <string>

namespace freeform {

/// Receives one warning message (no "warning:" prefix, no newline). It may be called from any
/// thread that runs library code (a worker of parallelFor, an editor's background thread), and
/// from several at once: a handler guards what it writes to. The library holds no lock while it
/// calls the handler.
using WarningHandler = std::function<void(const std::string& message)>;

/// Sets the process's handler (an empty one drops the messages) and returns the previous one.
WarningHandler setWarningHandler(WarningHandler handler);

/// Hands `message` to the handler, if there is one.
void warn(const std::string& message);

/// Sets a handler for its lifetime and puts the previous one back when it ends (a CLI run, an
/// editor window, a test).
class ScopedWarningHandler {
public:
    explicit ScopedWarningHandler(WarningHandler handler) : previous_(setWarningHandler(std::move(handler))) {}
    ~ScopedWarningHandler() { setWarningHandler(std::move(previous_)); }
    ScopedWarningHandler(const ScopedWarningHandler&) = delete;
    ScopedWarningHandler& operator=(const ScopedWarningHandler&) = delete;

private:
    WarningHandler previous_;
};

} // namespace freeform
