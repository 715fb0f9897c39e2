// Face and vertex normals: Newell area vectors, weighted corner sums.

#include "freeform/mesh/normals.h"

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

namespace freeform {

namespace {


Eigen::Vector3d unitOrZero(const Eigen::Vector3d& v)
{
    const double length = v.norm();
    return length > 0 && std::isfinite(length) ? Eigen::Vector3d(v / length) : Eigen::Vector3d::Zero();
}

Eigen::Vector3d areaVector(const PolygonMesh& mesh, int f)
{
    const int* corners = mesh.face(f);
    const int n = mesh.faceSize(f);
    const Eigen::Vector3d p0 = mesh.positions.col(corners[0]);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int k = 1; k + 1 < n; ++k)
        sum += (mesh.positions.col(corners[k]) - p0).cross(mesh.positions.col(corners[k + 1]) - p0);
    return sum / 2;
}

} // namespace

NormalWeighting parseNormalWeighting(const std::string& text, const std::string& what)
{
    if (text == "uniform") return NormalWeighting::Uniform;
    if (text == "area") return NormalWeighting::Area;
    if (text == "angle") return NormalWeighting::Angle;
    throw Error(what + ": unknown normal weighting \"" + text + "\" (expected uniform, area or angle)");
}

std::string toString(NormalWeighting weighting)
{
    switch (weighting) {
    case NormalWeighting::Uniform: return "uniform";
    case NormalWeighting::Area: return "area";
    case NormalWeighting::Angle: return "angle";
    }
    return "angle";
}

Eigen::Matrix<double, 3, Eigen::Dynamic> faceAreaVectors(const PolygonMesh& mesh)
{
    mesh.validate("mesh");
    Eigen::Matrix<double, 3, Eigen::Dynamic> out(3, mesh.faceCount());
    for (int f = 0; f < mesh.faceCount(); ++f) out.col(f) = areaVector(mesh, f);
    return out;
}

Eigen::Matrix<double, 3, Eigen::Dynamic> faceNormals(const PolygonMesh& mesh)
{
    mesh.validate("mesh");
    Eigen::Matrix<double, 3, Eigen::Dynamic> out(3, mesh.faceCount());
    for (int f = 0; f < mesh.faceCount(); ++f) out.col(f) = unitOrZero(areaVector(mesh, f));
    return out;
}

Eigen::Matrix<double, 3, Eigen::Dynamic> vertexNormals(const PolygonMesh& mesh, NormalWeighting weighting)
{
    mesh.validate("mesh");
    Eigen::Matrix<double, 3, Eigen::Dynamic> sum = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, mesh.vertexCount());
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const Eigen::Vector3d area = areaVector(mesh, f);
        const Eigen::Vector3d normal = unitOrZero(area);
        const int* corners = mesh.face(f);
        const int n = mesh.faceSize(f);
        for (int k = 0; k < n; ++k) {
            const int v = corners[k];
            double w = 1;
            if (weighting == NormalWeighting::Area) {
                w = area.norm();
            } else if (weighting == NormalWeighting::Angle) {
                const Eigen::Vector3d p = mesh.positions.col(v);
                const Eigen::Vector3d a = mesh.positions.col(corners[(k + n - 1) % n]) - p;
                const Eigen::Vector3d b = mesh.positions.col(corners[(k + 1) % n]) - p;
                // The interior angle: atan2 is accurate near 0 and pi; a reflex corner of a
                // non-convex polygon turns against the face normal and gets 2 pi minus it.
                const Eigen::Vector3d axb = a.cross(b);
                w = std::atan2(axb.norm(), a.dot(b));
                if (n > 3 && axb.dot(normal) > 0) w = 2 * std::numbers::pi - w;
            }
            sum.col(v) += w * normal;
        }
    }
    for (int v = 0; v < mesh.vertexCount(); ++v) sum.col(v) = unitOrZero(sum.col(v));
    return sum;
}

} // namespace freeform
