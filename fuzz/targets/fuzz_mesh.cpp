// Mesh readers and the format-preserving writers: one target per format (FUZZ_FORMAT = "obj",
// "ply", "stl", "off", "gltf", "glb"). An input the reader accepts must
//   - give the same mesh through MeshFile and readPolygonMesh (one validation path), and be read
//     from memory (MeshFile::readBytes, with the buffers read() found beside it) to the same
//     numbers, bit for bit; an input read() refuses, readBytes refuses too,
//   - write back in its own format byte for byte (text formats and binary PLY/STL: the identity
//     round trip of docs/mesh-io.md) and read back to the same positions,
//   - convert to binary PLY (float64) and read back to exactly the same positions.

#include <freeform/core/error.h>
#include <freeform/io/mesh_io.h>

#include <cstring>
#include <optional>

#include "fuzz_common.h"

#ifndef FUZZ_FORMAT
#error "FUZZ_FORMAT must name the format"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string format = FUZZ_FORMAT;
    const std::string in = fuzz::writeInput(data, size, "in." + format);
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    std::optional<freeform::MeshFile> read;
    try {
        read = freeform::MeshFile::read(in);
    } catch (const freeform::Error&) {
        try {
            (void)freeform::MeshFile::readBytes(in, bytes);
        } catch (const freeform::Error&) {
            return 0; // refused both ways: fine
        }
        fuzz::fail("MeshFile::readBytes accepted what MeshFile::read refuses");
    }
    freeform::MeshFile& file = *read;
    if (file.bytes() != bytes) fuzz::fail("MeshFile::bytes is not the file as read");
    try {
        const freeform::MeshFile memory = freeform::MeshFile::readBytes(in, bytes, file.companions());
        const auto sameBits = [](const auto& a, const auto& b) {
            return a.rows() == b.rows() && a.cols() == b.cols() &&
                   (a.size() == 0 || std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0);
        };
        if (!sameBits(memory.positions(), file.positions()) || !sameBits(memory.normals(), file.normals()) ||
            !sameBits(memory.tangents(), file.tangents()))
            fuzz::fail("MeshFile::readBytes and MeshFile::read disagree");
    } catch (const freeform::Error& e) {
        fuzz::fail(std::string("MeshFile::readBytes refused what MeshFile::read accepts: ") + e.what());
    }
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
    if (format != "glb" && format != "gltf" && fuzz::slurp(same) != bytes)
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

