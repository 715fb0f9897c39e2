// Polygon triangulation: fan for convex polygons, ear clipping otherwise, after projecting onto the
// Newell plane.

#include "freeform/mesh/triangulate.h"

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>
#include <string>

#include "freeform/core/error.h"

namespace freeform {

namespace {

using Vec2 = Eigen::Vector2d;


double orient(const Vec2& a, const Vec2& b, const Vec2& c)
{
    return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

/// The corner b turns the polygon's way (sense s) by more than a flat corner does: the sine of the
/// turn exceeds 1e-12, so corners that rounding left almost collinear are not cut off as slivers.
bool isConvexTurn(const Vec2& a, const Vec2& b, const Vec2& c, double s)
{
    return s * orient(a, b, c) > 1e-12 * (b - a).norm() * (c - b).norm();
}

/// d lies left of the line a -> b (sense s), on it, or within the same flatness threshold of it: a
/// corner that close to an ear's side blocks the ear (cutting it would leave a sliver).
bool notRightOf(const Vec2& a, const Vec2& b, const Vec2& d, double s)
{
    return s * orient(a, b, d) >= -1e-12 * (b - a).norm() * (d - a).norm();
}

std::vector<std::array<int, 3>> fan(int n)
{
    std::vector<std::array<int, 3>> out;
    out.reserve(n - 2);
    for (int k = 1; k + 1 < n; ++k) out.push_back({0, k, k + 1});
    return out;
}

void requireCorners(Eigen::Index count, bool finite)
{
    if (count < 3) throw Error("polygon: " + std::to_string(count) + " corners, at least 3 are needed");
    if (!finite) throw Error("polygon: a corner is not finite");
}

} // namespace

std::vector<std::array<int, 3>> triangulatePolygon2(const Eigen::Matrix<double, 2, Eigen::Dynamic>& q)
{
    requireCorners(q.cols(), q.allFinite());
    const int n = static_cast<int>(q.cols());
    if (n == 3) return {{0, 1, 2}};

    // Orientation from the signed area (shoelace around corner 0).
    double area = 0;
    for (int i = 1; i + 1 < n; ++i) area += orient(q.col(0), q.col(i), q.col(i + 1));
    const double s = area < 0 ? -1.0 : 1.0;

    // Strictly convex (and winding once): every corner turns the polygon's way by more than the
    // flatness threshold, and the turns add up to 2 pi. Then a fan has no sliver.
    bool convex = true;
    double turning = 0;
    for (int i = 0; i < n && convex; ++i) {
        const Vec2 a = q.col((i + n - 1) % n), b = q.col(i), c = q.col((i + 1) % n);
        convex = isConvexTurn(a, b, c, s);
        turning += std::atan2(s * orient(a, b, c), (b - a).dot(c - b));
    }
    if (convex && std::abs(turning - 2 * std::numbers::pi) < std::numbers::pi) return fan(n);

    std::vector<int> prev(n), next(n);
    for (int i = 0; i < n; ++i) {
        prev[i] = (i + n - 1) % n;
        next[i] = (i + 1) % n;
    }
    auto turn = [&](int i) { return s * orient(q.col(prev[i]), q.col(i), q.col(next[i])); };
    auto convexAt = [&](int i) { return isConvexTurn(q.col(prev[i]), q.col(i), q.col(next[i]), s); };
    auto isEar = [&](int i) {
        const int p = prev[i], x = next[i];
        if (!convexAt(i)) return false;
        const Vec2 a = q.col(p), b = q.col(i), c = q.col(x);
        for (int r = next[x]; r != p; r = next[r]) {
            const Vec2 d = q.col(r);
            if (d == a || d == b || d == c) continue; // a corner repeated (a bridge), not inside
            if (convexAt(r)) continue;                // only reflex or flat corners can lie inside an ear
            if (notRightOf(a, b, d, s) && notRightOf(b, c, d, s) && notRightOf(c, a, d, s)) return false;
        }
        return true;
    };
    auto clip = [&](int i, std::vector<std::array<int, 3>>& out) {
        out.push_back({prev[i], i, next[i]});
        next[prev[i]] = next[i];
        prev[next[i]] = prev[i];
    };

    std::vector<std::array<int, 3>> out;
    out.reserve(n - 2);
    int current = 0;
    for (int remaining = n; remaining > 3; --remaining) {
        int ear = -1;
        int i = current;
        for (int step = 0; step < remaining; ++step, i = next[i]) {
            if (isEar(i)) {
                ear = i;
                break;
            }
        }
        if (ear < 0) { // not simple or degenerate: clip the most convex corner
            ear = current;
            i = current;
            for (int step = 0; step < remaining; ++step, i = next[i])
                if (turn(i) > turn(ear)) ear = i;
        }
        current = next[ear];
        clip(ear, out);
    }
    out.push_back({prev[current], current, next[current]});
    return out;
}

std::vector<std::array<int, 3>> triangulatePolygon(const Eigen::Matrix<double, 3, Eigen::Dynamic>& corners)
{
    requireCorners(corners.cols(), corners.allFinite());
    const int n = static_cast<int>(corners.cols());
    if (n == 3) return {{0, 1, 2}};
    const Eigen::Vector3d p0 = corners.col(0);
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    for (int k = 1; k + 1 < n; ++k) normal += (corners.col(k) - p0).cross(corners.col(k + 1) - p0);
    const double length = normal.norm();
    if (!(length > 0) || !std::isfinite(length)) return fan(n); // all corners on a line: nothing better
    normal /= length;
    // A right-handed frame (u, w, normal): counter-clockwise about the normal stays counter-clockwise.
    int axis = 0;
    for (int k = 1; k < 3; ++k)
        if (std::abs(normal[k]) < std::abs(normal[axis])) axis = k;
    const Eigen::Vector3d u = normal.cross(Eigen::Vector3d::Unit(axis)).normalized();
    const Eigen::Vector3d w = normal.cross(u);
    const Eigen::Vector3d centroid = corners.rowwise().mean();
    Eigen::Matrix<double, 2, Eigen::Dynamic> q(2, n);
    for (int i = 0; i < n; ++i) {
        const Eigen::Vector3d d = corners.col(i) - centroid;
        q(0, i) = d.dot(u);
        q(1, i) = d.dot(w);
    }
    return triangulatePolygon2(q);
}

PolygonMesh triangulate(const PolygonMesh& mesh, std::vector<int>* triangleFace)
{
    mesh.validate("mesh");
    PolygonMesh out;
    out.positions = mesh.positions;
    out.normals = mesh.normals;
    out.texcoords = mesh.texcoords;
    if (triangleFace) triangleFace->clear();
    Eigen::Matrix<double, 3, Eigen::Dynamic> corners;
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const int* face = mesh.face(f);
        const int n = mesh.faceSize(f);
        corners.resize(3, n);
        for (int k = 0; k < n; ++k) corners.col(k) = mesh.positions.col(face[k]);
        for (const auto& t : triangulatePolygon(corners)) {
            out.addFace({face[t[0]], face[t[1]], face[t[2]]});
            if (triangleFace) triangleFace->push_back(f);
        }
    }
    return out;
}

} // namespace freeform
