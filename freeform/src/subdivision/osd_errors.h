#pragma once
// OpenSubdiv's errors (private to src/subdivision/): its error callback keeps the first message of
// a call instead of printing it (stdout is the CLI's JSON); takeOsdError throws it as an Error once
// the call has returned. The callbacks are installed by the SubdivisionSurface constructor.

namespace freeform {

void clearOsdError();
void takeOsdError();

} // namespace freeform
