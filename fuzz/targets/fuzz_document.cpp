// The JSON document (docs/format.md) with every object type, and the lattice built from its
// lattice objects. An accepted document must format and parse back to the same text.

#include <freeform/core/error.h>
#include <freeform/io/document.h>
#include <freeform/io/geometry_data.h>
#include <freeform/volume/lattice.h>

#include <string>

#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string text(reinterpret_cast<const char*>(data), size);
    freeform::Document doc;
    try {
        doc = freeform::parseDocument(text, "fuzz.json");
    } catch (const freeform::Error&) {
        return 0;
    }
    const std::string once = freeform::formatDocument(doc);
    freeform::Document again;
    try {
        again = freeform::parseDocument(once, "formatted.json");
    } catch (const freeform::Error& e) {
        fuzz::fail(std::string("a formatted document does not parse: ") + e.what());
    }
    if (freeform::formatDocument(again) != once) fuzz::fail("format -> parse -> format is not stable");
    for (const auto& o : doc.objects)
        if (const auto* lattice = std::get_if<freeform::LatticeData>(&o.data)) {
            try {
                const freeform::Lattice l = freeform::latticeFromData(*lattice);
                (void)freeform::latticeToData(l);
            } catch (const freeform::Error&) {
            }
        }
    return 0;
}
