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
// Held while a message is delivered, so that the handler sees one call at a time; separate from
// handlerMutex so that a handler may itself call setWarningHandler.
std::mutex& deliveryMutex()
{
    static std::mutex m;
    return m;
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
    if (!handler) return;
    std::lock_guard delivery(deliveryMutex());
    handler(message);
}

} // namespace freeform
