// Free-form deformation of a mesh file in place (io/deform_file.h).

#include "freeform/io/deform_file.h"

namespace freeform {

MeshFileDeformation deformMeshFile(const Lattice& lattice, MeshFile& file, const DeformOptions& options, NormalMode normals)
{
    // Positions, with the Jacobian at every position for the normals and tangents anchored there.
    auto& positions = file.positions();
    const Eigen::Index count = positions.cols();
    if (count == 0) return {}; // nothing to move (the binding has no output array for no positions)
    const FfdBinding<double> binding(lattice, positions);
    Eigen::Matrix<double, 3, Eigen::Dynamic> moved(3, count);
    Eigen::Matrix<double, 9, Eigen::Dynamic> jacobians(9, count);
    FfdOutputs<double> out;
    out.positions = moved.data();
    out.jacobians = jacobians.data();
    MeshFileDeformation result;
    binding.deform(lattice, out, options, &result.report);
    // Only the extrapolate policy evaluates the lattice polynomial outside its box, and far enough
    // outside it overflows: refuse before the file changes (a NaN position would be written as
    // "nan"). Inside the box, or under keep and clamp, the result of finite input is finite.
    if (lattice.outside() == OutsidePolicy::Extrapolate)
        for (const int v : binding.outsideVertices())
            if (!moved.col(v).allFinite() || !jacobians.col(v).allFinite())
                throw Error(file.path() + ": vertex " + std::to_string(v) +
                            " deforms to a position that is not finite (the extrapolate policy continues the lattice "
                            "polynomial, which overflows this far outside the box: use clamp or keep, or a lattice "
                            "that covers the mesh)");
    result.outside = binding.outsideVertices();
    auto& n = file.normals();
    const bool recompute = n.cols() > 0 && normals == NormalMode::Recompute;
    Eigen::Matrix<double, 3, Eigen::Dynamic> before; // the positions as they were, while a failure may undo
    if (recompute) before = positions;
    positions = moved;
    const auto jacobianAt = [&](int v) { return Eigen::Matrix3d(Eigen::Map<const Eigen::Matrix3d>(jacobians.col(v).data())); };

    const auto& normalAnchors = file.normalAnchors();
    if (recompute) {
        Eigen::Matrix<double, 3, Eigen::Dynamic> fresh;
        try {
            fresh = areaWeightedNormals(file.toPolygonMesh());
        } catch (const Error& e) {
            positions = before; // the file as it was
            throw Error(file.path() + ": cannot recompute normals: " + e.what()); // name the file
        }
        for (Eigen::Index i = 0; i < n.cols(); ++i) {
            const int a = normalAnchors[static_cast<std::size_t>(i)];
            if (a >= 0 && fresh.col(a).squaredNorm() > 0) n.col(i) = fresh.col(a);
        }
    } else {
        for (Eigen::Index i = 0; i < n.cols(); ++i) {
            const int a = normalAnchors[static_cast<std::size_t>(i)];
            if (a < 0) continue;
            const Eigen::Matrix3d j = jacobianAt(a);
            if (j != Eigen::Matrix3d::Identity()) n.col(i) = transformNormal(j, n.col(i));
        }
    }
    auto& tangents = file.tangents();
    const auto& tangentAnchors = file.tangentAnchors();
    for (Eigen::Index i = 0; i < tangents.cols(); ++i) {
        const int a = tangentAnchors[static_cast<std::size_t>(i)];
        if (a < 0) continue;
        const Eigen::Matrix3d j = jacobianAt(a);
        if (j != Eigen::Matrix3d::Identity()) tangents.col(i).head<3>() = transformTangent(j, tangents.col(i).head<3>()); // w kept
    }
    return result;
}

} // namespace freeform
