#include "scene/ffd_session.h"

#include <algorithm>

#include "freeform/core/parallel.h"

namespace freeform::editor {

FfdSession::FfdSession(const Lattice& lattice, PolygonMesh rest)
    : frame_(lattice), rest_(std::move(rest)), binding_(lattice, rest_.positions), restNormals_(rest_.normals.cast<float>())
{
}

bool FfdSession::matches(const Lattice& lattice) const
{
    return lattice.sameFrame(frame_) && lattice.outside() == frame_.outside();
}

DeformReport FfdSession::deform(const Lattice& lattice, double strength, PolygonMesh& out, std::vector<float>* detJ)
{
    const Eigen::Index count = rest_.positions.cols();
    const bool normals = rest_.normals.cols() == count;
    positions_.resize(3, count);
    if (out.positions.cols() != count) out.positions.resize(3, count);
    FfdOutputs<float> o;
    o.positions = positions_.data();
    if (normals) {
        normals_.resize(3, count);
        if (out.normals.cols() != count) out.normals.resize(3, count);
        o.normalsIn = restNormals_.data();
        o.normalsOut = normals_.data();
    }
    if (detJ) {
        detJ->resize(static_cast<std::size_t>(count));
        o.determinants = detJ->data();
    }
    DeformOptions options;
    options.strength = strength;
    DeformReport report;
    if (lattice.isRest() || strength == 0) {
        // The identity: the file's own vertices, bit for bit (float would round them), det J 1.
        out.positions = rest_.positions;
        if (normals) out.normals = rest_.normals;
        if (detJ) std::fill(detJ->begin(), detJ->end(), 1.0f);
        report.vertices = static_cast<std::size_t>(count);
        report.outside = binding_.outsideVertices().size();
        return report;
    }
    binding_.deform(lattice, o, options, &report);
    // Into the scene's double mesh, on the same threads as the deformation.
    parallelFor(0, static_cast<std::size_t>(count), 16384, 0, [&](int, std::size_t first, std::size_t last) {
        const auto n = static_cast<Eigen::Index>(last - first), f = static_cast<Eigen::Index>(first);
        out.positions.middleCols(f, n) = positions_.middleCols(f, n).cast<double>();
        if (normals) out.normals.middleCols(f, n) = normals_.middleCols(f, n).cast<double>();
    });
    return report;
}

} // namespace freeform::editor
