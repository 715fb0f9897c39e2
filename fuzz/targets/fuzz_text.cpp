// Text readers without a mesh: FUZZ_KIND 1 = .bpt patch files, 2 = OBJ free-form geometry,
// 3 = subdivision cages with OpenSubdiv tags (OBJ + `t` lines, validated and built into a surface).

#include <freeform/core/error.h>
#include <freeform/io/bpt.h>
#include <freeform/io/geometry_data.h>
#include <freeform/io/obj_freeform.h>
#include <freeform/subdivision/subdivision_surface.h>
#include <freeform/surface/patch_complex.h>

#include <string>

#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
#if FUZZ_KIND == 1
        const freeform::PatchComplex c = freeform::parseBpt(text, "fuzz.bpt");
        const std::string once = freeform::formatBpt(c);
        if (freeform::formatBpt(freeform::parseBpt(once, "formatted.bpt")) != once) fuzz::fail(".bpt format is not stable");
#elif FUZZ_KIND == 2
        const freeform::Document d = freeform::parseObjFreeform(text, "fuzz.obj");
        const std::string once = freeform::formatObjFreeform(d);
        (void)freeform::parseObjFreeform(once, "formatted.obj");
#elif FUZZ_KIND == 3
        const std::string in = fuzz::writeInput(data, size, "cage.obj");
        const freeform::SubdivisionCage cage = freeform::readCage(in);
        if (cage.mesh.vertexCount() <= 64 && cage.mesh.faceCount() <= 64) {
            freeform::SubdivisionSurface surface(cage, freeform::defaultScheme(cage.mesh));
            (void)surface;
        }
#else
#error "FUZZ_KIND must be 1, 2 or 3"
#endif
    } catch (const freeform::Error&) {
    }
    return 0;
}
