// The process's warning handler (freeform/core/warning.h).

#include "freeform/core/warning.h"

#include <mutex>
#include <utility>

namespace freeform {

namespace {
std::mutex& handlerMutex()
{
    static std::mutex m;
    return m;
}
WarningHandler& currentHandler()
{
    static WarningHandler h;
    return h;
}
} // namespace

WarningHandler setWarningHandler(WarningHandler handler)
{
    std::lock_guard lock(handlerMutex());
    return std::exchange(currentHandler(), std::move(handler));
}

void warn(const std::string& message)
{
    WarningHandler handler;
    {
        std::lock_guard lock(handlerMutex());
        handler = currentHandler();
    }
    // Called without a lock held: a handler may take its own (the GIL, in Python) and may set
    // another handler.
    if (handler) handler(message);
}

} // namespace freeform
