#pragma once
// Runs build/bin/freeform-editor from a test: every editor test that starts the binary goes through
// runEditorBinary. Header only; the test targets define FREEFORM_EDITOR and FREEFORM_TEST_TMP
// (editor/CMakeLists.txt).

#include <chrono>
#include <iostream>
#include <string>
#include <thread>

#include "support/process.h"

namespace freeform::test {

/// Runs the editor binary with `arguments`; `environment` is prepended (VAR=value ...).
/// LeakSanitizer is off for the child process only: Mesa's llvmpipe keeps allocations of its
/// JIT-compiled code until exit, which LeakSanitizer reports (from "<unknown module>"); every other
/// AddressSanitizer check stays on, and the editor's own code is leak-checked without a GL driver by
/// test_scene.
///
/// When the X server refuses the connection ("cannot open a window", the editor's exit 1 before it
/// reads any file), the run is repeated, at most twice, a second apart, and the refusal is printed
/// on stderr. That is the machine's X server failing, not the editor: a CI run once lost one
/// connection to its Xvfb among hundreds. Any other failure is returned at once.
inline ProcessResult runEditorBinary(const std::string& arguments, const std::string& environment = "")
{
    const std::string command =
        "ASAN_OPTIONS=\"${ASAN_OPTIONS:-}:detect_leaks=0\" " + environment + " '" + std::string(FREEFORM_EDITOR) + "' " + arguments;
    ProcessResult r = run(command);
    for (int retry = 0; retry < 2 && r.status == 1 && r.err.find("cannot open a window") != std::string::npos; ++retry) {
        std::cerr << "warning: the X server refused the editor's window (" << r.err.substr(0, r.err.find('\n'))
                  << "); running it again\n";
        std::this_thread::sleep_for(std::chrono::seconds(1));
        r = run(command);
    }
    return r;
}

} // namespace freeform::test
