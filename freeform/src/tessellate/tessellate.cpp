// Patch complexes to triangle meshes: certified counts per patch, matched across shared sides,
// vertices welded on shared sides (docs/surfaces.md, "Tessellation"). This file: the entry points
// (tessellate, tessellateUniform, tessellateAdaptive), the global bound and one grid per patch
// (Refinement::PatchGrid, and the uniform mode), and the verification (sampleTriangleDeviation,
// netErrorBound). The local refinement: tessellate_tree.cpp (the trees of sub-nets and their
// bounds), tessellate_geometric.cpp (the geometric measure), tessellate_local.cpp (the mesh of the
// leaves); what the pieces share is in tessellate_internal.h.

#include "freeform/tessellate/tessellate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "freeform/core/error.h"
#include "tessellate_internal.h"

namespace freeform {

namespace tessellate_detail {

namespace {

struct DerivativeBounds {
    double uu = 0, uv = 0, vv = 0;
};

/// Bounds of |f_uu|, |f_uv|, |f_vv| over the patch from the control net (convex hull property of
/// the second-derivative patches).
DerivativeBounds derivativeBounds(const Patch& p)
{
    const int m = p.degreeU(), n = p.degreeV();
    DerivativeBounds b;
    for (int i = 0; i <= m; ++i) {
        for (int j = 0; j <= n; ++j) {
            if (i + 2 <= m)
                b.uu = std::max(b.uu, (p.controlPoint(i + 2, j) - 2 * p.controlPoint(i + 1, j) + p.controlPoint(i, j)).norm());
            if (j + 2 <= n)
                b.vv = std::max(b.vv, (p.controlPoint(i, j + 2) - 2 * p.controlPoint(i, j + 1) + p.controlPoint(i, j)).norm());
            if (i + 1 <= m && j + 1 <= n)
                b.uv = std::max(b.uv, (p.controlPoint(i + 1, j + 1) - p.controlPoint(i + 1, j) - p.controlPoint(i, j + 1) +
                                       p.controlPoint(i, j)).norm());
        }
    }
    b.uu *= m * (m - 1.0);
    b.vv *= n * (n - 1.0);
    b.uv *= static_cast<double>(m) * n;
    return b;
}

double bound(const DerivativeBounds& b, int nu, int nv)
{
    const double x = 1.0 / nu, y = 1.0 / nv;
    return b.uu * x * x / 8 + b.uv * x * y / 4 + b.vv * y * y / 8;
}

/// Which count governs a side: sides U0/U1 run along v (count nv), V0/V1 along u (count nu).
int countOf(const PatchEdge& e)
{
    return 2 * e.patch + ((e.side == PatchSide::U0 || e.side == PatchSide::U1) ? 1 : 0);
}

/// Position and first partial derivatives (tensor-product Bernstein sums).
Jet1 jet1(const Patch& patch, double u, double v)
{
    const int m = patch.degreeU(), n = patch.degreeV();
    double bu[kMaxDegree + 1], dbu[kMaxDegree + 1], bv[kMaxDegree + 1], dbv[kMaxDegree + 1];
    basisWithDerivative(m, u, bu, dbu);
    basisWithDerivative(n, v, bv, dbv);
    const double* P = patch.controlPoints().data();
    Jet1 r{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    for (int i = 0; i <= m; ++i) {
        Eigen::Vector3d row = Eigen::Vector3d::Zero(), rowV = Eigen::Vector3d::Zero();
        for (int j = 0; j <= n; ++j) {
            const Eigen::Map<const Eigen::Vector3d> q(P + 3 * (i * (n + 1) + j));
            row += bv[j] * q;
            rowV += dbv[j] * q;
        }
        r.p += bu[i] * row;
        r.fu += dbu[i] * row;
        r.fv += bu[i] * rowV;
    }
    return r;
}

} // namespace

/// The side's curve in canonical orientation (the lexicographically smaller point sequence) and
/// whether that is the side's own order reversed.
std::pair<BezierCurve<double, 3>, bool> canonicalEdge(const Patch& p, PatchSide side)
{
    const BezierCurve<double, 3> c = edgeCurve(p, side);
    const auto& pts = c.controlPoints();
    const Eigen::Index count = pts.cols();
    for (Eigen::Index k = 0; k < count; ++k) {
        for (int d = 0; d < 3; ++d) {
            const double a = pts(d, k) + 0.0, b = pts(d, count - 1 - k) + 0.0;
            if (a < b) return {c, false};
            if (a > b) return {c.reversed(), true};
        }
    }
    return {c, false};
}

namespace {

/// The mesh from the collected arrays (normals normalised, flipped on request); the report out.
PolygonMesh finishMesh(std::vector<Eigen::Vector3d>&& positions, std::vector<Eigen::Vector3d>&& normals,
                       std::vector<Eigen::Vector2d>&& texcoords, std::vector<int>&& faces, const TessellationOptions& options,
                       TessellationReport& rep, TessellationReport* report)
{
    PolygonMesh mesh;
    const int v = static_cast<int>(positions.size());
    mesh.positions.resize(3, v);
    mesh.normals.resize(3, v);
    mesh.texcoords.resize(2, v);
    for (int k = 0; k < v; ++k) {
        mesh.positions.col(k) = positions[k];
        Eigen::Vector3d n = normals[k];
        const double len = n.norm();
        n = len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
        mesh.normals.col(k) = options.flipNormals ? Eigen::Vector3d(-n) : n;
        mesh.texcoords.col(k) = texcoords[k];
    }
    mesh.faceVertices = std::move(faces);
    mesh.faceStart.resize(mesh.faceVertices.size() / 3 + 1);
    for (std::size_t f = 0; f < mesh.faceStart.size(); ++f) mesh.faceStart[f] = static_cast<int>(3 * f);
    if (report) *report = std::move(rep);
    return mesh;
}

/// One grid per patch (uniform mode, and adaptive mode with Refinement::PatchGrid).
PolygonMesh tessellateGrid(const PatchComplex& complex, const TessellationOptions& options, TessellationReport* report)
{
    const int count = static_cast<int>(complex.patches.size());

    // 1. Counts each patch asks for, then the maximum over every chain of shared sides.
    std::vector<int> counts(static_cast<std::size_t>(2 * count));
    TessellationReport rep;
    for (int p = 0; p < count; ++p) {
        const bool adaptive = options.tolerance > 0 || !options.patchTolerance.empty();
        const std::array<int, 2> want = adaptive ? adaptiveSegments(complex.patches[p], toleranceOf(options, p), options.maxSegments)
                                                 : std::array<int, 2>{options.segmentsU, options.segmentsV};
        rep.required.push_back(want);
        counts[2 * p] = want[0];
        counts[2 * p + 1] = want[1];
    }
    Classes classes(2 * count);
    for (const SharedEdge& e : sharedEdges(complex, 0)) classes.join(countOf(e.a), countOf(e.b));
    std::vector<int> classMax(counts.size(), 0);
    for (int k = 0; k < 2 * count; ++k) classMax[classes.find(k)] = std::max(classMax[classes.find(k)], counts[k]);
    for (int k = 0; k < 2 * count; ++k) counts[k] = classMax[classes.find(k)];
    long long triangles = 0;
    for (int p = 0; p < count; ++p) triangles += 2LL * counts[2 * p] * counts[2 * p + 1];
    if (options.maxTriangles > 0 && triangles > options.maxTriangles)
        throw Error("tessellate: the mesh would have " + std::to_string(triangles) + " triangles, more than maxTriangles = " +
                    std::to_string(options.maxTriangles) + " (raise the limit, --max-triangles, or the tolerance)");

    // 2. Vertices and triangles, patch by patch; boundary vertices welded by exact position.
    std::vector<Eigen::Vector3d> positions, normals;
    std::vector<Eigen::Vector2d> texcoords;
    std::unordered_map<PositionKey, int, PositionHash> welded;
    std::vector<int> faces;
    for (int p = 0; p < count; ++p) {
        const Patch& patch = complex.patches[p];
        const int nu = counts[2 * p], nv = counts[2 * p + 1];
        rep.segments.push_back({nu, nv});
        const double patchBound = tessellationErrorBound(patch, nu, nv);
        rep.errorBound = std::max(rep.errorBound, patchBound);
        if (options.tolerance > 0 || !options.patchTolerance.empty()) {
            rep.patchBound.push_back(patchBound);
            rep.worstRatio = std::max(rep.worstRatio, patchBound / toleranceOf(options, p));
        }
        std::vector<double> us(static_cast<std::size_t>(nu + 1)), vs(static_cast<std::size_t>(nv + 1));
        for (int i = 0; i <= nu; ++i) us[i] = static_cast<double>(i) / nu;
        for (int j = 0; j <= nv; ++j) vs[j] = static_cast<double>(j) / nv;
        PointMatrix<double, 3> gridPos, gridNrm;
        patch.evaluateGrid(us, vs, gridPos, &gridNrm);
        const int rowLength = nv + 1;
        // Boundary positions from the canonical side curves (identical in every patch sharing it).
        for (int s = 0; s < 4; ++s) {
            const PatchSide side = static_cast<PatchSide>(s);
            const bool alongV = side == PatchSide::U0 || side == PatchSide::U1;
            const int segs = alongV ? nv : nu;
            const auto [curve, reversed] = canonicalEdge(patch, side);
            // A collapsed side is its one point exactly ((1-t) p + t p need not round to p).
            const bool collapsed = isCollapsedEdge(patch, side);
            for (int k = 0; k <= segs; ++k) {
                const int kc = reversed ? segs - k : k;
                const Eigen::Vector3d q = collapsed ? Eigen::Vector3d(curve.controlPoint(0))
                                                    : curve.evaluate(static_cast<double>(kc) / segs);
                int i = 0, j = 0;
                switch (side) {
                case PatchSide::U0: i = 0; j = k; break;
                case PatchSide::U1: i = nu; j = k; break;
                case PatchSide::V0: i = k; j = 0; break;
                case PatchSide::V1: i = k; j = nv; break;
                }
                gridPos.col(i * rowLength + j) = q;
            }
        }
        std::vector<int> ids(static_cast<std::size_t>((nu + 1) * (nv + 1)));
        for (int i = 0; i <= nu; ++i) {
            for (int j = 0; j <= nv; ++j) {
                const int g = i * rowLength + j;
                const Eigen::Vector3d q = gridPos.col(g);
                const Eigen::Vector3d nrm = gridNrm.col(g);
                const bool boundary = i == 0 || j == 0 || i == nu || j == nv;
                if (boundary) {
                    const PositionKey key{q.x() + 0.0, q.y() + 0.0, q.z() + 0.0};
                    const auto [it, inserted] = welded.try_emplace(key, static_cast<int>(positions.size()));
                    ids[g] = it->second;
                    if (!inserted) {
                        normals[static_cast<std::size_t>(it->second)] += nrm;
                        continue;
                    }
                } else {
                    ids[g] = static_cast<int>(positions.size());
                }
                positions.push_back(q);
                normals.push_back(nrm);
                texcoords.emplace_back(us[i], vs[j]);
            }
        }
        for (int i = 0; i < nu; ++i) {
            for (int j = 0; j < nv; ++j) {
                const int g00 = i * rowLength + j, g10 = g00 + rowLength, g01 = g00 + 1, g11 = g10 + 1;
                const int a = ids[g00], b = ids[g10], c = ids[g11], d = ids[g01];
                // The shorter diagonal (the error bound holds for either).
                const double d1 = (gridPos.col(g00) - gridPos.col(g11)).squaredNorm();
                const double d2 = (gridPos.col(g10) - gridPos.col(g01)).squaredNorm();
                const int tri[2][3] = {{a, b, c}, {a, c, d}};
                const int alt[2][3] = {{a, b, d}, {b, c, d}};
                const auto& use = d1 <= d2 ? tri : alt;
                const int gtri[2][3] = {{g00, g10, g11}, {g00, g11, g01}}, galt[2][3] = {{g00, g10, g01}, {g10, g11, g01}};
                const auto& guse = d1 <= d2 ? gtri : galt;
                for (int h = 0; h < 2; ++h) {
                    const auto& t = use[h];
                    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue; // at a collapsed side
                    if (options.flipNormals) faces.insert(faces.end(), {t[0], t[2], t[1]});
                    else faces.insert(faces.end(), {t[0], t[1], t[2]});
                    if (options.sampleDeviation) {
                        std::array<Eigen::Vector2d, 3> uv;
                        std::array<Eigen::Vector3d, 3> xyz;
                        for (int c = 0; c < 3; ++c) {
                            const int g = guse[h][c];
                            uv[c] = Eigen::Vector2d(us[g / rowLength], vs[g % rowLength]);
                            xyz[c] = gridPos.col(g);
                        }
                        const TriangleDeviation dev = sampleTriangleDeviation(patch, uv, xyz);
                        rep.measuredParametric = std::max(rep.measuredParametric, dev.parametric);
                        rep.measuredGeometric = std::max(rep.measuredGeometric, dev.geometric);
                    }
                }
            }
        }
    }
    return finishMesh(std::move(positions), std::move(normals), std::move(texcoords), std::move(faces), options, rep, report);
}

} // namespace

} // namespace tessellate_detail

double tessellationErrorBound(const Patch& patch, int segmentsU, int segmentsV)
{
    if (segmentsU < 1 || segmentsV < 1) throw Error("tessellationErrorBound: segment counts must be at least 1");
    return tessellate_detail::bound(tessellate_detail::derivativeBounds(patch), segmentsU, segmentsV);
}

std::array<int, 2> adaptiveSegments(const Patch& patch, double tolerance, int maxSegments)
{
    if (!(tolerance > 0) || !std::isfinite(tolerance)) throw Error("adaptiveSegments: tolerance must be positive and finite");
    if (maxSegments < 1) throw Error("adaptiveSegments: maxSegments must be at least 1");
    using tessellate_detail::bound;
    const tessellate_detail::DerivativeBounds b = tessellate_detail::derivativeBounds(patch);
    // Every nu with the smallest nv that meets the tolerance; then the fewest cells, preferring
    // (within 25 % more cells) the grid whose cells are closest to square in the parameters.
    std::vector<std::array<int, 2>> candidates;
    for (int nu = 1; nu <= maxSegments; ++nu) {
        const double x = 1.0 / nu;
        const double rest = tolerance - b.uu * x * x / 8;
        if (rest <= 0) continue;
        // Largest y with (M_vv/8) y^2 + (M_uv/4) x y <= rest.
        const double qa = b.vv / 8, qb = b.uv * x / 4;
        double y;
        if (qa > 0) y = (-qb + std::sqrt(qb * qb + 4 * qa * rest)) / (2 * qa);
        else if (qb > 0) y = rest / qb;
        else y = 1;
        int nv = std::max(1, static_cast<int>(std::ceil(1.0 / std::min(y, 1.0) - 1e-9)));
        while (nv <= maxSegments && bound(b, nu, nv) > tolerance) ++nv;
        if (nv > maxSegments) continue;
        candidates.push_back({nu, nv});
        if (nv == 1) break; // more u segments cannot help
    }
    if (candidates.empty()) return {maxSegments, maxSegments};
    long fewest = -1;
    for (const auto& c : candidates) {
        const long cells = static_cast<long>(c[0]) * c[1];
        if (fewest < 0 || cells < fewest) fewest = cells;
    }
    std::array<int, 2> best = candidates.front();
    double bestShape = std::numeric_limits<double>::infinity();
    for (const auto& c : candidates) {
        const long cells = static_cast<long>(c[0]) * c[1];
        if (cells * 4 > fewest * 5) continue;
        const double shape = std::abs(std::log(static_cast<double>(c[0]) / c[1]));
        if (shape < bestShape || (shape == bestShape && cells < static_cast<long>(best[0]) * best[1])) {
            bestShape = shape;
            best = c;
        }
    }
    return best;
}

TriangleDeviation sampleTriangleDeviation(const Patch& patch, const std::array<Eigen::Vector2d, 3>& uv,
                                          const std::array<Eigen::Vector3d, 3>& xyz, int samples)
{
    if (samples < 1) throw Error("sampleTriangleDeviation: samples must be at least 1");
    using tessellate_detail::Jet1, tessellate_detail::jet1;
    TriangleDeviation d;
    for (int i = 0; i <= samples; ++i)
        for (int j = 0; i + j <= samples; ++j) {
            const int k = samples - i - j;
            if (i == samples || j == samples || k == samples) continue;
            const double a = double(i) / samples, b = double(j) / samples, c = double(k) / samples;
            const Eigen::Vector2d x = a * uv[0] + b * uv[1] + c * uv[2];
            const Eigen::Vector3d target = a * xyz[0] + b * xyz[1] + c * xyz[2];
            Jet1 f = jet1(patch, x.x(), x.y());
            const double parametric = (f.p - target).norm();
            double best = parametric;
            // Gauss-Newton towards the foot point, kept in the domain.
            Eigen::Vector2d y = x;
            for (int it = 0; it < 12; ++it) {
                const Eigen::Vector3d r = f.p - target;
                Eigen::Matrix2d h;
                h << f.fu.dot(f.fu), f.fu.dot(f.fv), f.fu.dot(f.fv), f.fv.dot(f.fv);
                const Eigen::Vector2d g(f.fu.dot(r), f.fv.dot(r));
                const double det = h.determinant();
                if (!(std::abs(det) > 0)) break;
                const Eigen::Vector2d step = h.inverse() * g;
                y = (y - step).cwiseMax(0.0).cwiseMin(1.0);
                f = jet1(patch, y.x(), y.y());
                best = std::min(best, (f.p - target).norm());
                if (step.norm() < 1e-15) break;
            }
            d.parametric = std::max(d.parametric, parametric);
            d.geometric = std::max(d.geometric, best);
        }
    return d;
}

double netErrorBound(const Patch& patch)
{
    const auto t = tessellate_detail::netTerms(tessellate_detail::netOf(patch).data(), patch.degreeU(),
                            patch.degreeV());
    return (t[0] + t[1] + t[2]) / 8;
}

PolygonMesh tessellate(const PatchComplex& complex, const TessellationOptions& options, TessellationReport* report)
{
    if (options.tolerance < 0 || !std::isfinite(options.tolerance))
        throw Error("tessellate: tolerance must be positive and finite");
    if (options.tolerance == 0 && options.patchTolerance.empty() && (options.segmentsU < 1 || options.segmentsV < 1))
        throw Error("tessellate: segment counts must be at least 1");
    if (options.maxSegments < 1) throw Error("tessellate: maxSegments must be at least 1");
    if (options.maxTriangles < 0) throw Error("tessellate: maxTriangles must be 0 (no limit) or positive");
    if (!options.patchTolerance.empty()) {
        if (options.patchTolerance.size() != complex.patches.size())
            throw Error("tessellate: patchTolerance has " + std::to_string(options.patchTolerance.size()) + " entries for " +
                        std::to_string(complex.patches.size()) + " patches");
        for (std::size_t p = 0; p < options.patchTolerance.size(); ++p)
            if (!(options.patchTolerance[p] > 0) || !std::isfinite(options.patchTolerance[p]))
                throw Error("tessellate: patchTolerance[" + std::to_string(p) + "] must be positive and finite");
    }
    const bool adaptive = options.tolerance > 0 || !options.patchTolerance.empty();
    if (adaptive && options.refinement == TessellationRefinement::Local)
        return tessellate_detail::tessellateLocal(complex, options, report);
    return tessellate_detail::tessellateGrid(complex, options, report);
}

PolygonMesh tessellateUniform(const PatchComplex& complex, int segmentsU, int segmentsV)
{
    TessellationOptions o;
    o.segmentsU = segmentsU;
    o.segmentsV = segmentsV;
    return tessellate(complex, o);
}

PolygonMesh tessellateAdaptive(const PatchComplex& complex, double tolerance)
{
    if (!(tolerance > 0)) throw Error("tessellateAdaptive: tolerance must be positive");
    TessellationOptions o;
    o.tolerance = tolerance;
    return tessellate(complex, o);
}

} // namespace freeform
