#include "tools/ffd_tools.h"

#include "freeform/io/mesh_io.h"
#include "freeform/io/deform_file.h"

namespace freeform::editor {

DeformReport exportDeformedMesh(const std::string& input, const Lattice& lattice, double strength, const std::string& output)
{
    MeshFile file = MeshFile::read(input);
    DeformOptions options;
    options.strength = strength;
    const DeformReport report = deformMeshFile(lattice, file, options).report; // what `freeform ffd` does
    file.write(output);
    return report;
}

} // namespace freeform::editor
