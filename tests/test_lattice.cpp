// Lattice: frames, lattice coordinates, identity lattices, fitting, the document object, outside
// policies and degree elevation.

#include <catch2/catch.hpp>

#include <freeform/volume/lattice.h>

#include <cmath>

#include "freeform/io/geometry_data.h"
#include "support/random.h"

namespace test_lattice {

using freeform::Lattice;
using freeform::OutsidePolicy;
using Points = Lattice::Points;

namespace {

struct Frame {
    const char* name;
    Eigen::Vector3d origin;
    Eigen::Matrix3d axes;
};

std::vector<Frame> frames()
{
    Eigen::Matrix3d sheared;
    sheared << 2.0, 0.7, -0.3, 0.1, 1.5, 0.4, 0.2, -0.6, 0.9; // columns S, T, U, not orthogonal
    Eigen::Matrix3d leftHanded = Eigen::Vector3d(1.0, 3.0, -2.0).asDiagonal();
    return {{"unit cube", Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()},
            {"box", Eigen::Vector3d(-3.25, 1.5, 10.0), Eigen::Vector3d(0.3, 7.0, 2.5).asDiagonal()},
            {"sheared", Eigen::Vector3d(0.5, -1.0, 2.0), sheared},
            {"left-handed", Eigen::Vector3d(1.0, 1.0, 1.0), leftHanded}};
}

Points randomPointsIn(const Lattice& lat, int count, std::uint32_t seed, double lo = 0, double hi = 1)
{
    const Points stu = freeform::test::randomPoints<double, 3>(count, seed, lo, hi);
    Points p(3, count);
    for (int i = 0; i < count; ++i) p.col(i) = lat.origin() + lat.axes() * stu.col(i);
    return p;
}

} // namespace

TEST_CASE("lattice coordinates follow the docs/math.md formulas and invert the frame", "[unit]")
{
    for (const Frame& f : frames()) {
        CAPTURE(f.name);
        const Lattice lat = Lattice::identity({2, 2, 2}, f.origin, f.axes);
        const Points p = randomPointsIn(lat, 20, 5, -0.5, 1.5);
        // Independent: solve axes * stu = p - X0 by LU in long double.
        const Eigen::Matrix<long double, 3, 3> a = f.axes.cast<long double>();
        for (int i = 0; i < p.cols(); ++i) {
            const Eigen::Matrix<long double, 3, 1> rhs = (p.col(i) - f.origin).cast<long double>();
            const Eigen::Vector3d ref = a.partialPivLu().solve(rhs).cast<double>();
            CHECK((lat.toLattice(p.col(i)) - ref).norm() < 1e-14 * (1 + ref.norm()));
            CHECK((lat.toWorld(lat.toLattice(p.col(i))) - p.col(i)).norm() < 1e-13 * (1 + p.col(i).norm()));
        }
        CHECK((lat.dual() * f.axes - Eigen::Matrix3d::Identity()).norm() < 1e-14);
    }
}

TEST_CASE("the outside rule: where each policy evaluates a point, which axes follow it, whether it moves", "[unit]")
{
    using freeform::outsideRule;
    // Inside the box every policy evaluates the point itself and every axis follows it.
    for (OutsidePolicy p : {OutsidePolicy::Keep, OutsidePolicy::Clamp, OutsidePolicy::Extrapolate}) {
        const auto r = outsideRule({0.2, 0.3, 1.0}, p);
        CHECK(r.at == Eigen::Vector3d(0.2, 0.3, 1.0));
        CHECK(r.mask == 0x0fu);
        CHECK_FALSE(r.outside);
    }
    // (-0.5, 0.5, 1.5) leaves the box along s and u: only t follows it under keep and clamp.
    const Eigen::Vector3d stu(-0.5, 0.5, 1.5);
    const auto keep = outsideRule(stu, OutsidePolicy::Keep), clamp = outsideRule(stu, OutsidePolicy::Clamp),
               extrapolate = outsideRule(stu, OutsidePolicy::Extrapolate);
    CHECK((keep.outside && clamp.outside && extrapolate.outside));
    CHECK(keep.mask == 0x02u); // t only, and it does not move
    CHECK_FALSE(keep.moves());
    CHECK(clamp.mask == 0x0au); // t, and it moves
    CHECK((clamp.moves() && !clamp.follows(0) && clamp.follows(1) && !clamp.follows(2)));
    CHECK(clamp.at == Eigen::Vector3d(0, 0.5, 1));
    CHECK(keep.at == clamp.at);
    CHECK(extrapolate.mask == 0x0fu);
    CHECK(extrapolate.at == stu);
    // clampsOutside, which the vectorised kernels read, says what the rule does with the point.
    CHECK(freeform::clampsOutside(OutsidePolicy::Keep) == (keep.at != stu));
    CHECK(freeform::clampsOutside(OutsidePolicy::Clamp) == (clamp.at != stu));
    CHECK(freeform::clampsOutside(OutsidePolicy::Extrapolate) == (extrapolate.at != stu));
}

TEST_CASE("rest control points are X0 + (i/l) S + (j/m) T + (k/n) U", "[unit]")
{
    const Lattice lat = Lattice::identity({2, 1, 4}, Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(2, 4, 8).asDiagonal());
    CHECK(lat.pointCount() == 3 * 2 * 5);
    CHECK(lat.index(1, 1, 3) == 1 * 10 + 1 * 5 + 3);
    CHECK(lat.controlPoint(0, 0, 0) == Eigen::Vector3d(1, 2, 3));
    CHECK(lat.controlPoint(1, 1, 3) == Eigen::Vector3d(2, 6, 9));
    CHECK(lat.controlPoint(2, 1, 4) == Eigen::Vector3d(3, 6, 11));
    CHECK(lat.isRest());
    CHECK(lat.displacements().isZero(0.0));
}

TEST_CASE("identity lattices of several degrees and frames reproduce every point", "[unit]")
{
    for (const Frame& f : frames()) {
        for (const auto& d : {std::array<int, 3>{1, 1, 1}, {2, 3, 1}, {3, 3, 3}, {5, 2, 4}}) {
            CAPTURE(f.name, d[0], d[1], d[2]);
            const Lattice lat = Lattice::identity(d, f.origin, f.axes, OutsidePolicy::Extrapolate);
            const Points p = randomPointsIn(lat, 30, 9, -0.2, 1.2);
            const auto vol = lat.volume(); // the plain volume form f(s,t,u) = sum B P, no displacement form
            for (int i = 0; i < p.cols(); ++i) {
                const Eigen::Vector3d x = p.col(i);
                const auto jet = lat.deform(x);
                CHECK(jet.point == x); // displacement form: exact
                CHECK((jet.jacobian - Eigen::Matrix3d::Identity()).norm() == 0.0);
                const Eigen::Vector3d stu = lat.toLattice(x);
                CHECK((vol.evaluate(stu[0], stu[1], stu[2]) - x).norm() < 1e-12 * (1 + x.norm()));
            }
        }
    }
}

TEST_CASE("fit wraps a point set's bounding box with a margin", "[unit]")
{
    Points p(3, 3);
    p << 0, 2, 1,  //
        -1, 1, 0,  //
        0, 0.5, 4; // box [0,2] x [-1,1] x [0,4], largest extent 4
    const Lattice lat = Lattice::fit(p, {3, 2, 1}, 0.25);
    CHECK(lat.origin() == Eigen::Vector3d(-1, -2, -1));
    CHECK(lat.axes() == Eigen::Matrix3d(Eigen::Vector3d(4, 4, 6).asDiagonal()));
    CHECK(lat.degrees() == std::array<int, 3>{3, 2, 1});
    CHECK(lat.isRest());
    CHECK(lat.outside() == OutsidePolicy::Clamp);
    for (int i = 0; i < 3; ++i) CHECK(Lattice::insideBox(lat.toLattice(p.col(i))));

    // A flat point set (z = 5): the flat axis gets the largest extent, centred.
    Points flat(3, 2);
    flat << 0, 2, 0, 1, 5, 5;
    const Lattice f = Lattice::fit(flat, {1, 1, 1}, 0.0);
    CHECK(f.origin() == Eigen::Vector3d(0, 0, 4));
    CHECK(f.axes() == Eigen::Matrix3d(Eigen::Vector3d(2, 1, 2).asDiagonal()));
    // One point: a unit cube around it.
    const Lattice one = Lattice::fit(Points(Eigen::Vector3d(1, 1, 1)), {1, 1, 1}, 0.1);
    CHECK(one.origin() == Eigen::Vector3d(0.5, 0.5, 0.5));

    CHECK_THROWS_AS(Lattice::fit(Points(3, 0), {1, 1, 1}), freeform::Error);
    CHECK_THROWS_AS(Lattice::fit(p, {1, 1, 1}, -1), freeform::Error);
}

TEST_CASE("document data round trip and validation", "[unit]")
{
    const freeform::Document doc = freeform::parseDocument(R"({"format": "freeform", "version": 1, "objects": [
        {"name": "L", "type": "lattice", "degree": [1, 1, 1], "origin": [0, 0, 0],
         "axes": [[2, 0, 0], [0, 2, 0], [0, 0, 2]],
         "points": [[0,0,0],[0,0,2],[0,2,0],[0,2,2],[2,0,0],[2,0,2],[2,2,0],[3,2,2]],
         "outside": "keep"}]})");
    const Lattice lat = latticeFromData(std::get<freeform::LatticeData>(doc.object("L").data));
    CHECK(lat.outside() == OutsidePolicy::Keep);
    CHECK(lat.displacements().col(7) == Eigen::Vector3d(1, 0, 0));
    CHECK(lat.displacements().leftCols(7).isZero(0.0));
    const freeform::LatticeData back = latticeToData(lat);
    CHECK(back.points == std::get<freeform::LatticeData>(doc.object("L").data).points);
    CHECK(back.outside == OutsidePolicy::Keep);
    CHECK(back.axes == Eigen::Matrix3d(Eigen::Vector3d(2, 2, 2).asDiagonal()));

    using Catch::Matchers::Contains;
    Eigen::Matrix3d dependent;
    dependent << 1, 2, 3, 0, 0, 0, 1, 2, 3.0000000000001;
    dependent.col(2) = dependent.col(0) + dependent.col(1) * (1 + 1e-15);
    CHECK_THROWS_WITH(Lattice::identity({1, 1, 1}, Eigen::Vector3d::Zero(), dependent), Contains("linearly dependent"));
    CHECK_THROWS_WITH(Lattice::identity({0, 1, 1}, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()), Contains("degree l = 0"));
    CHECK_THROWS_WITH(Lattice({1, 1, 1}, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), Points::Zero(3, 9)),
                      Contains("has 9 points, degree needs 8"));
    Lattice editable = lat;
    CHECK_THROWS_WITH(editable.setControlPoint(2, 0, 0, Eigen::Vector3d::Zero()), Contains("out of range"));
    CHECK_THROWS_WITH(editable.setControlPoint(0, 0, 0, Eigen::Vector3d(0, std::nan(""), 0)), Contains("not finite"));
    editable.setControlPoint(1, 1, 1, Eigen::Vector3d(2, 2, 2));
    CHECK(editable.isRest());
    CHECK_THROWS_WITH(freeform::parseOutsidePolicy("wrap", "doc"), Contains("\"wrap\""));
}

TEST_CASE("outside policies: keep, clamp (continuous) and extrapolate", "[unit]")
{
    Lattice lat = Lattice::identity({2, 2, 2}, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
    Points pts = lat.controlPoints();
    const Points offsets = freeform::test::randomPoints<double, 3>(static_cast<int>(pts.cols()), 3, -0.1, 0.1);
    lat.setControlPoints(pts + offsets);
    const auto dvol = lat.displacementVolume();
    const Eigen::Vector3d outsidePoint(1.3, 0.4, -0.2); // beyond s = 1 and u = 0

    lat.setOutside(OutsidePolicy::Keep);
    auto keep = lat.deform(outsidePoint);
    CHECK(keep.outside);
    CHECK(keep.point == outsidePoint);
    CHECK(keep.jacobian == Eigen::Matrix3d::Identity());

    lat.setOutside(OutsidePolicy::Clamp);
    const auto clamp = lat.deform(outsidePoint);
    const Eigen::Vector3d dAtBox = dvol.evaluate(1.0, 0.4, 0.0);
    CHECK((clamp.point - (outsidePoint + dAtBox)).norm() < 1e-15);
    // Continuity across the face s = 1: the displacement just inside tends to the clamped one.
    const auto inside = lat.deform(Eigen::Vector3d(1 - 1e-9, 0.4, 1e-9));
    CHECK(((inside.point - Eigen::Vector3d(1 - 1e-9, 0.4, 1e-9)) - dAtBox).norm() < 1e-8);
    // The Jacobian keeps only the derivative along t (s and u are clamped).
    const auto jet = dvol.derivatives(1.0, 0.4, 0.0);
    const Eigen::Matrix3d expected = Eigen::Matrix3d::Identity() + jet.dt * Eigen::RowVector3d(0, 1, 0);
    CHECK((clamp.jacobian - expected).norm() < 1e-15);

    lat.setOutside(OutsidePolicy::Extrapolate);
    const auto ext = lat.deform(outsidePoint);
    CHECK((ext.point - lat.volume().evaluate(1.3, 0.4, -0.2)).norm() < 1e-13);
}

TEST_CASE("degree elevation of a deformed lattice leaves the deformation unchanged", "[unit]")
{
    for (const Frame& f : frames()) {
        CAPTURE(f.name);
        Lattice lat = Lattice::identity({2, 1, 3}, f.origin, f.axes);
        const Points offsets =
            freeform::test::randomPoints<double, 3>(lat.pointCount(), 17, -0.2, 0.2) * f.axes.norm();
        lat.setControlPoints(lat.controlPoints() + offsets);
        const Lattice up = lat.elevated(1, 2, 0);
        CHECK(up.degrees() == std::array<int, 3>{3, 3, 3});
        const Points p = randomPointsIn(lat, 40, 23, -0.1, 1.1);
        for (int i = 0; i < p.cols(); ++i) {
            const auto a = lat.deform(p.col(i)), b = up.deform(p.col(i));
            CHECK((a.point - b.point).norm() < 1e-13 * (1 + p.col(i).norm()));
            CHECK((a.jacobian - b.jacobian).norm() < 1e-12);
        }
        CHECK(Lattice::identity({1, 1, 1}, f.origin, f.axes).elevated(2, 0, 1).isRest());
    }
}

} // namespace test_lattice

namespace test_lattice {

TEST_CASE("sensitivities: d p' / d P_q = strength * B_q, against moving each point", "[lattice][ffd]")
{
    Eigen::Matrix3d axes;
    axes << 2.0, 0.7, -0.3, 0.1, 1.5, 0.4, 0.2, -0.6, 0.9;
    for (const OutsidePolicy policy : {OutsidePolicy::Keep, OutsidePolicy::Clamp, OutsidePolicy::Extrapolate}) {
        CAPTURE(static_cast<int>(policy));
        Lattice lattice = Lattice::identity({2, 3, 1}, Eigen::Vector3d(0.5, -1, 0.25), axes, policy);
        lattice.setControlPoint(1, 2, 0, lattice.controlPoint(1, 2, 0) + Eigen::Vector3d(0.2, -0.1, 0.3));
        const int K = lattice.pointCount();
        const double strength = 0.7;
        // Inside, on a face, and outside along one and two axes.
        const std::vector<Eigen::Vector3d> stus = {{0.3, 0.6, 0.45}, {1.0, 0.2, 0.7}, {1.2, 0.5, 0.5}, {-0.3, 0.4, 1.5}};
        Points block(3, Lattice::kSensitivityLanes);
        for (std::size_t n = 0; n < stus.size(); ++n) block.col(static_cast<Eigen::Index>(n)) = lattice.toWorld(stus[n]);
        std::vector<double> fromBlock(static_cast<std::size_t>(K * Lattice::kSensitivityLanes), -1.0);
        lattice.sensitivityBlock(block.data(), stus.size(), strength, fromBlock.data());
        for (std::size_t n = 0; n < stus.size(); ++n) {
            CAPTURE(n);
            const Eigen::Vector3d p = lattice.toWorld(stus[n]);
            std::vector<double> s(static_cast<std::size_t>(K));
            lattice.sensitivities(p, strength, s.data());
            double sum = 0;
            for (int q = 0; q < K; ++q) {
                sum += s[static_cast<std::size_t>(q)];
                // The block gives the same bits.
                CHECK(fromBlock[static_cast<std::size_t>(q * Lattice::kSensitivityLanes) + n] == s[static_cast<std::size_t>(q)]);
            }
            const bool moves = policy != OutsidePolicy::Keep || Lattice::insideBox(stus[n]);
            // Partition of unity: the factors sum to the strength (0 when p stays put).
            CHECK(sum == Approx(moves ? strength : 0.0).margin(1e-15));
            // FFD is linear in the points: moving P_q by e moves p' by s_q e, exactly up to rounding.
            const Eigen::Vector3d e(0.5, -0.25, 0.125);
            const Eigen::Vector3d before = lattice.deform(p, strength).point;
            for (int q = 0; q < K; ++q) {
                Lattice moved = lattice;
                Points points = moved.controlPoints();
                points.col(q) += e;
                moved.setControlPoints(points);
                const Eigen::Vector3d change = moved.deform(p, strength).point - before;
                CHECK((change - s[static_cast<std::size_t>(q)] * e).norm() <= 1e-14);
            }
        }
        // Lanes past count are zero.
        for (int q = 0; q < K; ++q)
            for (int lane = static_cast<int>(stus.size()); lane < Lattice::kSensitivityLanes; ++lane)
                CHECK(fromBlock[static_cast<std::size_t>(q * Lattice::kSensitivityLanes + lane)] == 0.0);
    }
}

} // namespace test_lattice
