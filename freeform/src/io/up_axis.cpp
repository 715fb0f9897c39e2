#include "freeform/io/up_axis.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "freeform/core/error.h"

namespace freeform {

UpAxis parseUpAxis(const std::string& text, const std::string& where)
{
    if (text == "z") return UpAxis::Z;
    if (text == "y") return UpAxis::Y;
    throw Error(where + ": expected \"z\" or \"y\", not \"" + text + "\"");
}

const char* toString(UpAxis up)
{
    return up == UpAxis::Y ? "y" : "z";
}

std::optional<UpAxis> formatUpAxis(const std::string& path)
{
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".gltf" || ext == ".glb") return UpAxis::Y;
    return std::nullopt;
}

Eigen::Matrix3d upAxisToWorld(UpAxis up)
{
    Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
    if (up == UpAxis::Y) r << 1, 0, 0, //
                             0, 0, -1, //
                             0, 1, 0;
    return r;
}

void meshToWorld(PolygonMesh& mesh, UpAxis up)
{
    if (up == UpAxis::Z) return;
    const Eigen::Matrix3d r = upAxisToWorld(up);
    mesh.positions = (r * mesh.positions).eval();
    if (mesh.normals.cols() > 0) mesh.normals = (r * mesh.normals).eval();
}

LatticeData latticeToFile(const LatticeData& lattice, UpAxis up)
{
    if (up == UpAxis::Z) return lattice;
    const Eigen::Matrix3d back = upAxisToWorld(up).transpose();
    LatticeData out = lattice;
    out.origin = back * lattice.origin;
    out.axes = back * lattice.axes;
    out.points = back * lattice.points;
    return out;
}

Lattice latticeToFile(const Lattice& lattice, UpAxis up)
{
    if (up == UpAxis::Z) return lattice;
    const Eigen::Matrix3d back = upAxisToWorld(up).transpose();
    return Lattice(lattice.degrees(), back * lattice.origin(), back * lattice.axes(), back * lattice.controlPoints(), lattice.outside());
}

} // namespace freeform
