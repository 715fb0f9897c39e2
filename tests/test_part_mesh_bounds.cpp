// The part tessellation's cell bounds from a patch's curves (src/brep/part_mesh_internal.h:
// revolutionCellBound, conicalCellBound): every point of every triangle whose corners lie in a
// cell is within the cell's bound of the exact surface, the distance taken in closed form (torus,
// sphere, cone), and the bounds are near that distance, not merely above it.

#include <catch2/catch.hpp>

#include <freeform/brep/exact_forms.h>

#include <cmath>
#include <functional>
#include <random>

#include "../freeform/src/brep/part_mesh_internal.h"

namespace test_part_mesh_bounds {
namespace {

using freeform::RationalPatch;
using Distance = std::function<double(const Eigen::Vector3d&)>;

/// The sub-patch over [u0, u1] x [v0, v1] of [0, 1]^2.
RationalPatch cut(const RationalPatch& p, double u0, double u1, double v0, double v1)
{
    RationalPatch q = p;
    if (u1 < 1) q = q.splitU(u1).first;
    if (u0 > 0) q = q.splitU(u0 / u1).second;
    if (v1 < 1) q = q.splitV(v1).first;
    if (v0 > 0) q = q.splitV(v0 / v1).second;
    return q;
}

struct Worst {
    double distance = 0; // the largest distance found from a triangle point to the surface
    double ratio = 0;    // the largest of distance / bound
    double bound = 0;     // the largest cell bound
};

/// For every cell of an nu x nv grid on each patch: triangles from the cell's corners and from
/// random points in it, points of each at fixed and random barycentrics, against bound(cell).
Worst sample(const std::vector<RationalPatch>& patches, int nu, int nv, const Distance& distance,
             const std::function<double(const RationalPatch& patch, int i, int j)>& bound)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(0, 1);
    Worst w;
    for (const RationalPatch& p : patches)
        for (int i = 0; i < nu; ++i)
            for (int j = 0; j < nv; ++j) {
                const double b = bound(p, i, j);
                const RationalPatch cell = cut(p, double(i) / nu, double(i + 1) / nu, double(j) / nv, double(j + 1) / nv);
                std::vector<std::array<Eigen::Vector2d, 3>> triangles = {
                    {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(1, 1)},
                    {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), Eigen::Vector2d(0, 1)},
                    {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 1)}};
                for (int t = 0; t < 6; ++t)
                    triangles.push_back({Eigen::Vector2d(unit(rng), unit(rng)), Eigen::Vector2d(unit(rng), unit(rng)),
                                         Eigen::Vector2d(unit(rng), unit(rng))});
                double cellWorst = 0;
                for (const auto& tri : triangles) {
                    std::vector<Eigen::Vector3d> bary = {{1.0 / 3, 1.0 / 3, 1.0 / 3}, {0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}};
                    for (int k = 0; k < 6; ++k) {
                        const double a = unit(rng), c = unit(rng) * (1 - a);
                        bary.emplace_back(a, c, 1 - a - c);
                    }
                    for (const Eigen::Vector3d& l : bary) {
                        Eigen::Vector3d point = Eigen::Vector3d::Zero();
                        for (int k = 0; k < 3; ++k) point += l[k] * cell.evaluate(tri[static_cast<std::size_t>(k)].x(), tri[static_cast<std::size_t>(k)].y());
                        cellWorst = std::max(cellWorst, distance(point));
                    }
                }
                w.distance = std::max(w.distance, cellWorst);
                w.ratio = std::max(w.ratio, cellWorst / b);
                w.bound = std::max(w.bound, b);
            }
    return w;
}

freeform::MappedCurve<3> circle(const Eigen::Vector3d& centre, double radius, double t0, double t1)
{
    return freeform::exactEllipse<3>(centre, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ(), radius, radius, t0, t1);
}

std::vector<RationalPatch> patchesOf(const freeform::MappedCurve<3>& meridian)
{
    return freeform::exactRevolution(meridian, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 0, 2 * M_PI).nurbs.bezierPatches();
}

} // namespace

TEST_CASE("a surface of revolution's cells are within their bound of it, and the bound is near the truth", "[part_mesh]")
{
    using freeform::part_mesh::revolutionCellBound;
    auto revolution = [](const RationalPatch& p, int nu, int nv) {
        return [p, nu, nv](const RationalPatch& patch, int i, int j) {
            (void)p;
            return revolutionCellBound(cut(patch, double(i) / nu, double(i + 1) / nu, double(j) / nv, double(j + 1) / nv));
        };
    };
    struct Surface {
        const char* name;
        freeform::MappedCurve<3> meridian;
        Distance distance;
    };
    const double R = 4, r = 1, rs = 3, r0 = 1, r1 = 3, H = 5;
    const std::vector<Surface> surfaces = {
        {"torus", circle(Eigen::Vector3d(R, 0, 0), r, 0, 2 * M_PI),
         [&](const Eigen::Vector3d& x) { return std::abs(std::hypot(std::hypot(x.x(), x.y()) - R, x.z()) - r); }},
        {"sphere", circle(Eigen::Vector3d::Zero(), rs, -M_PI / 2, M_PI / 2), [&](const Eigen::Vector3d& x) { return std::abs(x.norm() - rs); }},
        {"cone", freeform::exactLine<3>(Eigen::Vector3d(r0, 0, 0), Eigen::Vector3d(r1 - r0, 0, H), 0, 1),
         [&](const Eigen::Vector3d& x) { return std::abs((std::hypot(x.x(), x.y()) - r0) * H - x.z() * (r1 - r0)) / std::hypot(H, r1 - r0); }},
    };
    for (const Surface& s : surfaces) {
        const std::vector<RationalPatch> patches = patchesOf(s.meridian);
        REQUIRE(!patches.empty());
        for (const auto& [nu, nv] : {std::pair{1, 1}, std::pair{3, 2}, std::pair{8, 6}}) {
            INFO(s.name << ", " << patches.size() << " patches, cells " << nu << " x " << nv);
            const Worst w = sample(patches, nu, nv, s.distance, revolution(patches.front(), nu, nv));
            INFO("largest distance " << w.distance << ", largest distance / bound " << w.ratio << ", largest bound " << w.bound);
            CHECK(std::isfinite(w.bound));       // every cell is recognised (a finite bound)
            CHECK(w.ratio <= 1 + 1e-9);          // and holds
            // Near the truth: the chords of the two circles, without a twist term. Measured:
            // 1.22 (torus), 1.27 (sphere), 1.25 (cone) times the largest distance found on 8 x 6
            // cells per patch; 1.65, 1.76, 1.55 on 3 x 2; 5.2, 4.5, 2.9 on one cell per patch
            // (a quarter turn of both circles).
            if (nu * nv > 1) CHECK(w.bound <= (nu * nv >= 16 ? 1.35 : 1.85) * w.distance);
        }
    }
}

TEST_CASE("a cone's cells are within their conical bound, which does not grow with the height", "[part_mesh]")
{
    using freeform::part_mesh::conicalCellBound;
    const double r0 = 0.5, r1 = 6, H = 80; // a tall cone, as in test_cad_mesh
    const auto meridian = freeform::exactLine<3>(Eigen::Vector3d(r0, 0, 0), Eigen::Vector3d(r1 - r0, 0, H), 0, 1);
    const std::vector<RationalPatch> patches = patchesOf(meridian);
    const Distance distance = [&](const Eigen::Vector3d& x) {
        return std::abs((std::hypot(x.x(), x.y()) - r0) * H - x.z() * (r1 - r0)) / std::hypot(H, r1 - r0);
    };
    for (const auto& grid : {std::pair{4, 1}, std::pair{16, 1}, std::pair{16, 3}}) {
        const int nu = grid.first, nv = grid.second; // (clang 14 cannot capture a structured binding)
        INFO("cells " << nu << " x " << nv);
        const Worst w = sample(patches, nu, nv, distance, [&](const RationalPatch& p, int i, int j) {
            return conicalCellBound(cut(p, double(i) / nu, double(i + 1) / nu, 0, 1), double(j) / nv, double(j + 1) / nv);
        });
        INFO("largest distance " << w.distance << ", distance / bound " << w.ratio << ", largest bound " << w.bound);
        CHECK(std::isfinite(w.bound));
        CHECK(w.ratio <= 1 + 1e-9);
        // Measured: 1.32, 1.08 and 1.08 times the largest distance found. Without equal end
        // weights (endWeightsEqual) it was 2.0 to 2.3: the cells' weights differ by their width.
        CHECK(w.bound <= 1.4 * w.distance);
    }
    // A cell whose rows run across the apex has no conical bound (the rulings change side there).
    const auto through = freeform::exactLine<3>(Eigen::Vector3d(-2, 0, 0), Eigen::Vector3d(4, 0, 4), 0, 1);
    const RationalPatch p = patchesOf(through).front();
    CHECK(std::isinf(conicalCellBound(p, 0, 1)));
    CHECK(std::isfinite(conicalCellBound(p, 0, 0.5)));
    // A cylinder's rulings are parallel: no apex (its ruled bound has no spread term instead).
    const auto side = freeform::exactLine<3>(Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(0, 0, 4), 0, 1);
    CHECK(std::isinf(conicalCellBound(patchesOf(side).front(), 0, 1)));
}

TEST_CASE("a patch that is no surface of revolution gets no revolution bound", "[part_mesh]")
{
    using freeform::part_mesh::revolutionCellBound;
    // The torus's patch with one control point moved off the structure: the fit leaves it, and
    // the bound grows by at least twice the move (or is infinite), so it still holds.
    const RationalPatch torus = patchesOf(circle(Eigen::Vector3d(4, 0, 0), 1, 0, 2 * M_PI)).front();
    const double exact = revolutionCellBound(torus);
    REQUIRE(std::isfinite(exact));
    const int m = torus.degreeU(), n = torus.degreeV();
    RationalPatch::Points points(3, (m + 1) * (n + 1));
    RationalPatch::Weights weights((m + 1) * (n + 1));
    for (int i = 0; i <= m; ++i)
        for (int j = 0; j <= n; ++j) {
            points.col(i * (n + 1) + j) = torus.controlPoint(i, j);
            weights[i * (n + 1) + j] = torus.weight(i, j);
        }
    points.col(1 * (n + 1) + 1) += Eigen::Vector3d(0, 0, 0.25);
    const double moved = revolutionCellBound(RationalPatch(m, n, points, weights));
    CHECK(moved >= exact + 2 * 0.25 * 0.999);
    // Degree 3 along the circles' direction: not recognised.
    CHECK(std::isinf(revolutionCellBound(torus.elevatedU(1))));
}

} // namespace test_part_mesh_bounds

namespace test_part_mesh_bounds {

TEST_CASE("uneven columns are narrow only where a trim holds cells to their parametric bound", "[part_mesh]")
{
    using namespace freeform::part_mesh;
    // A quarter of a cone (radius 1 to 3 over a height of 5) with a trim through its middle, as
    // screw.step's slot runs through its head's cone.
    const double r0 = 1, r1 = 3, H = 5, target = 0.01;
    const RationalPatch p = patchesOf(freeform::exactLine<3>(Eigen::Vector3d(r0, 0, 0), Eigen::Vector3d(r1 - r0, 0, H), 0, 1)).front();
    TrimZones zones;
    zones.boxes.emplace_back(Eigen::Vector2d(0.45, 0.2), Eigen::Vector2d(0.5, 0.8));
    const std::array<int, 2> even = patchSegments(p, target, zones);
    double bound = 0;
    const std::vector<double> breaks = unevenColumns({&p}, {even[1]}, {&zones}, target, even[0], bound);
    INFO("even " << even[0] << " x " << even[1] << ", uneven " << breaks.size() - 1 << " columns");
    REQUIRE(breaks.size() >= 2);
    CHECK(breaks.front() == 0);
    CHECK(breaks.back() == 1);
    CHECK(static_cast<int>(breaks.size()) - 1 < even[0]);
    CHECK(bound <= target);
    double narrowest = 1, widest = 0, widestTrimmed = 0;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> unit(0, 1);
    for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
        const double u0 = breaks[i], u1 = breaks[i + 1];
        REQUIRE(u1 > u0);
        const bool trimmed = zones.meets(u0, u1, 0, 1);
        narrowest = std::min(narrowest, u1 - u0);
        widest = std::max(widest, u1 - u0);
        if (trimmed) widestTrimmed = std::max(widestTrimmed, u1 - u0);
        for (int j = 0; j < even[1]; ++j) {
            const double v0 = double(j) / even[1], v1 = double(j + 1) / even[1];
            // Every triangle point against the surface at its own parameters (what a trim through
            // the cell needs), and against the cone in closed form (what every cell needs).
            for (int t = 0; t < 200; ++t) {
                Eigen::Vector3d point = Eigen::Vector3d::Zero();
                Eigen::Vector2d at = Eigen::Vector2d::Zero();
                const double a = unit(rng), c = unit(rng) * (1 - a);
                const double l[3] = {a, c, 1 - a - c};
                for (int k = 0; k < 3; ++k) {
                    const Eigen::Vector2d x(u0 + (u1 - u0) * (t < 3 ? (k == 1) : unit(rng)), v0 + (v1 - v0) * (t < 3 ? (k == 2) : unit(rng)));
                    point += l[k] * p.evaluate(x.x(), x.y());
                    at += l[k] * x;
                }
                const double cone = std::abs((std::hypot(point.x(), point.y()) - r0) * H - point.z() * (r1 - r0)) / std::hypot(H, r1 - r0);
                CHECK(cone <= bound * (1 + 1e-9));
                if (trimmed) CHECK((point - p.evaluate(at.x(), at.y())).norm() <= bound * (1 + 1e-9));
            }
        }
    }
    // The columns through the trim are held to the parametric bound, linear in their width; the
    // others take the far circle's chords.
    CHECK(widestTrimmed > 0);
    CHECK(widestTrimmed < 0.5 * widest);
}

} // namespace test_part_mesh_bounds

namespace test_part_mesh_bounds {

TEST_CASE("a grid search that starts from a like patch's answers finds the grid a fresh search finds", "[part_mesh]")
{
    using namespace freeform::part_mesh;
    // A torus's 16 patches (four kinds, each four times along the turn), a sphere's and a cone's,
    // and nine copies of a torus patch flattened in part (its control points moved a tenth, two
    // tenths, ..., nine tenths of the way to the bilinear patch of its corners): their corners and
    // weights are those of a patch seen before, so they look alike and start from answers over
    // their own.
    std::vector<RationalPatch> patches = patchesOf(circle(Eigen::Vector3d(4, 0, 0), 1, 0, 2 * M_PI));
    const RationalPatch first = patches.front();
    const int m = first.degreeU(), n = first.degreeV();
    auto flattened = [&](double lambda) {
        RationalPatch::Points points(3, (m + 1) * (n + 1));
        RationalPatch::Weights weights((m + 1) * (n + 1));
        for (int i = 0; i <= m; ++i)
            for (int j = 0; j <= n; ++j) {
                const double s = double(i) / m, t = double(j) / n;
                const Eigen::Vector3d flat = (1 - s) * (1 - t) * first.controlPoint(0, 0) + s * (1 - t) * first.controlPoint(m, 0) +
                                             (1 - s) * t * first.controlPoint(0, n) + s * t * first.controlPoint(m, n);
                points.col(i * (n + 1) + j) = first.controlPoint(i, j) + lambda * (flat - first.controlPoint(i, j));
                weights[i * (n + 1) + j] = first.weight(i, j);
            }
        return RationalPatch(m, n, points, weights);
    };
    const std::size_t torus = patches.size();
    for (const RationalPatch& p : patchesOf(circle(Eigen::Vector3d::Zero(), 2, -M_PI / 2, M_PI / 2))) patches.push_back(p);
    for (const RationalPatch& p : patchesOf(freeform::exactLine<3>(Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(2, 0, 5), 0, 1)))
        patches.push_back(p);
    const std::size_t alikeFrom = patches.size();
    for (int tenths = 1; tenths <= 9; ++tenths) patches.push_back(flattened(0.1 * tenths));
    REQUIRE(torus == 16);
    TrimZones none, slot;
    slot.boxes.emplace_back(Eigen::Vector2d(0.45, 0.2), Eigen::Vector2d(0.5, 0.8));
    for (const double target : {0.05, 0.01, 0.002})
        for (const TrimZones* zones : {&none, &slot}) {
            SearchHints hints;
            int alike = 0;
            for (std::size_t k = 0; k < patches.size(); ++k) {
                const bool seen = hints.like(patches[k]) != nullptr;
                if (k < torus) alike += seen;
                if (k >= alikeFrom) CHECK(seen);
                INFO("target " << target << ", patch " << k);
                CHECK(patchSegments(patches[k], target, *zones, &hints) == patchSegments(patches[k], target, *zones));
            }
            CHECK(alike == 12);
        }
}

} // namespace test_part_mesh_bounds
