// The drag pass (volume/drag_pass.h), the editor's per-frame lattice drag, against the lattice's
// own deformation map in double (Lattice::deform, an independent path: a full tensor sum and its
// Jacobian): after a set of points moves by one delta since the base, every vertex's position,
// det J and unit normal cof(J) n / |cof(J) n| agree to float precision. Both bases (the rest
// mesh, and a lattice already deformed), a sheared frame, degrees (3, 2, 3) (the cubic's closed
// form and the general recursion), and vertices outside the box under clamp (the masks).

#include <catch2/catch.hpp>

#include <freeform/volume/drag_pass.h>
#include <freeform/volume/lattice.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>


namespace test_drag_pass {

using namespace freeform;

namespace {

struct Mesh {
    Eigen::Matrix3Xd positions, normals;
};

/// count vertices: most inside the lattice's box, every fifth up to 0.3 outside along some axis.
Mesh vertices(const Lattice& lattice, int count)
{
    std::mt19937 rng(20261205);
    auto uniform = [&rng](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
    Mesh m;
    m.positions.resize(3, count);
    m.normals.resize(3, count);
    for (int v = 0; v < count; ++v) {
        Eigen::Vector3d stu(uniform(0.02, 0.98), uniform(0.02, 0.98), uniform(0.02, 0.98));
        if (v % 5 == 0) stu[v % 3] = v % 2 ? -0.3 * uniform(0.1, 1) : 1 + 0.3 * uniform(0.1, 1);
        m.positions.col(v) = lattice.origin() + lattice.axes() * stu;
        m.normals.col(v) = Eigen::Vector3d(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)).normalized();
    }
    return m;
}

/// The pass's coordinate blocks (outside policy applied) and masks, as FfdSession makes them.
void blocks(const Lattice& lattice, const Mesh& m, std::vector<float>& coords, std::vector<unsigned char>& masks)
{
    constexpr int W = kDragLanes;
    const std::size_t count = static_cast<std::size_t>(m.positions.cols());
    coords.assign(((count + W - 1) / W) * kDragCoordFields * W, 0.5f);
    masks.assign(count, 0x0f);
    for (std::size_t v = 0; v < count + (W - count % W) % W; ++v) {
        const std::size_t source = std::min(v, count - 1); // padding repeats the last vertex
        const Eigen::Index e = static_cast<Eigen::Index>(source);
        const OutsideRule rule = outsideRule(lattice.dual() * (m.positions.col(e) - lattice.origin()), lattice.outside());
        if (v < count) masks[v] = static_cast<unsigned char>(rule.mask);
        float* b = coords.data() + (v / W) * kDragCoordFields * W + v % W;
        for (int x = 0; x < 3; ++x) {
            b[x * W] = static_cast<float>(rule.at[x]);
            b[(3 + x) * W] = static_cast<float>(m.normals(x, e));
        }
    }
}

Eigen::Vector3d unitCofactorNormal(const Eigen::Matrix3d& J, const Eigen::Vector3d& n)
{
    return (J.determinant() * J.inverse().transpose() * n).normalized(); // cof(J) = det J J^-T
}

} // namespace

TEST_CASE("drag pass: positions, det J and normals equal the lattice's map in double", "[ffd]")
{
    Eigen::Matrix3d axes;
    axes << 2.0, 0.7, -0.3, 0.1, 1.5, 0.4, 0.2, -0.6, 0.9; // sheared: S, T, U not orthogonal
    const Lattice rest = Lattice::identity({3, 2, 3}, Eigen::Vector3d(-1, 0.5, 2), axes, OutsidePolicy::Clamp);
    const Mesh m = vertices(rest, 83); // five full blocks and a part block
    std::vector<float> coords;
    std::vector<unsigned char> masks;
    blocks(rest, m, coords, masks);
    const std::vector<std::array<int, 3>> ijk = {{1, 1, 2}, {2, 1, 2}, {3, 0, 1}};
    const Eigen::Vector3d delta(0.21, -0.13, 0.34);
    const double strength = 0.8;

    for (const bool identityBase : {true, false}) {
        INFO((identityBase ? "base: the rest mesh" : "base: a deformed lattice"));
        // The base lattice: at rest, or with two other points already moved.
        Lattice base = rest;
        if (!identityBase) {
            base.setControlPoint(0, 2, 1, base.controlPoint(0, 2, 1) + Eigen::Vector3d(0.3, 0.1, -0.2));
            base.setControlPoint(2, 0, 3, base.controlPoint(2, 0, 3) + Eigen::Vector3d(-0.1, 0.25, 0.15));
        }
        Lattice moved = base;
        for (const auto& p : ijk) moved.setControlPoint(p[0], p[1], p[2], moved.controlPoint(p[0], p[1], p[2]) + delta);

        const std::size_t count = static_cast<std::size_t>(m.positions.cols());
        constexpr int W = kDragLanes;
        std::vector<float> baseBlocks(((count + W - 1) / W) * kDragBaseFields * W, 0.0f);
        for (std::size_t v = 0; v < baseBlocks.size() / kDragBaseFields; ++v) {
            const Eigen::Index e = static_cast<Eigen::Index>(std::min(v, count - 1));
            const Lattice::PointJet jet = base.deform(m.positions.col(e), strength);
            float* b = baseBlocks.data() + (v / W) * kDragBaseFields * W + v % W;
            for (int x = 0; x < 3; ++x) b[x * W] = static_cast<float>(jet.point[x]);
            for (int c = 0; c < 9; ++c) b[(3 + c) * W] = static_cast<float>(jet.jacobian(c % 3, c / 3)); // column-major
            b[12 * W] = static_cast<float>(jet.jacobian.determinant());
        }

        Eigen::Matrix3Xd pos(3, m.positions.cols()), nor(3, m.positions.cols());
        std::vector<float> det(count);
        std::vector<int> folds;
        DragPass f;
        f.count = count;
        f.coords = coords.data();
        f.masks = masks.data();
        f.base = baseBlocks.data();
        f.rest = m.positions.data();
        for (int x = 0; x < 3; ++x) f.deg[x] = rest.degree(x);
        f.ijk = ijk.data();
        f.moved = ijk.size();
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) f.dual[3 * r + c] = static_cast<float>(rest.dual()(r, c));
        for (int x = 0; x < 3; ++x) f.u[x] = static_cast<float>(strength * delta[x]);
        f.pos = pos.data();
        f.nor = nor.data();
        f.det = det.data();
        f.folds = &folds;
        runDragPass(f, identityBase);

        double lo = 1e300, hi = -1e300;
        Eigen::AlignedBox3d box;
        for (Eigen::Index v = 0; v < m.positions.cols(); ++v) {
            INFO("vertex " << v);
            const Lattice::PointJet jet = moved.deform(m.positions.col(v), strength);
            CHECK((pos.col(v) - jet.point).norm() <= 2e-5);
            const double d = jet.jacobian.determinant();
            CHECK(std::abs(det[static_cast<std::size_t>(v)] - d) <= 2e-5 * std::max(1.0, std::abs(d)));
            CHECK((nor.col(v) - unitCofactorNormal(jet.jacobian, m.normals.col(v))).norm() <= 2e-5);
            lo = std::min(lo, double(det[static_cast<std::size_t>(v)]));
            hi = std::max(hi, double(det[static_cast<std::size_t>(v)]));
            box.extend(pos.col(v));
        }
        // What the pass finds is what it wrote: det J's range, no folds here, the box.
        CHECK(f.lo == lo);
        CHECK(f.hi == hi);
        CHECK(lo > 0);
        CHECK(folds.empty());
        for (int x = 0; x < 3; ++x) {
            CHECK(f.mn[x] == float(box.min()[x]));
            CHECK(f.mx[x] == float(box.max()[x]));
        }
    }
}

} // namespace test_drag_pass
