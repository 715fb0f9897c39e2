// Mesh readers and the format-preserving writers: one target per format (FUZZ_FORMAT = "obj",
// "ply", "stl", "off", "gltf", "glb"). An input the reader accepts must
//   - give the same mesh through MeshFile and readPolygonMesh (one validation path),
//   - write back in its own format byte for byte (text formats and binary PLY/STL: the identity
//     round trip of docs/mesh-io.md) and read back to the same positions,
//   - convert to binary PLY (float64) and read back to exactly the same positions.

#include <freeform/core/error.h>
#include <freeform/io/mesh_io.h>

#include <optional>

#include "fuzz_common.h"

#ifndef FUZZ_FORMAT
#error "FUZZ_FORMAT must name the format"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string format = FUZZ_FORMAT;
    const std::string in = fuzz::writeInput(data, size, "in." + format);
    std::optional<freeform::MeshFile> read;
    try {
        read = freeform::MeshFile::read(in);
    } catch (const freeform::Error&) {
        return 0; // refused: fine
    }
    freeform::MeshFile& file = *read;
    const freeform::PolygonMesh mesh = file.toPolygonMesh();
    freeform::PolygonMesh viaRead;
    try {
        viaRead = freeform::readPolygonMesh(in);
    } catch (const freeform::Error& e) {
        fuzz::fail(std::string("MeshFile::read accepted what readPolygonMesh refuses: ") + e.what());
    }
    if (format != "stl" && viaRead.positions != mesh.positions) fuzz::fail("readPolygonMesh and MeshFile disagree");

    const std::string same = fuzz::path("same." + format);
    file.write(same);
    if (format != "glb" && format != "gltf" && fuzz::slurp(same) != std::string(reinterpret_cast<const char*>(data), size))
        fuzz::fail("the identity round trip changed bytes");
    if (freeform::MeshFile::read(same).positions() != file.positions()) fuzz::fail("the round trip changed positions");

    const std::string ply = fuzz::path("conv.ply");
    try {
        file.write(ply);
    } catch (const freeform::Error& e) {
        fuzz::fail(std::string("conversion to PLY refused an accepted mesh: ") + e.what());
    }
    if (freeform::readPolygonMesh(ply).positions != mesh.positions) fuzz::fail("PLY conversion changed positions");
    return 0;
}

