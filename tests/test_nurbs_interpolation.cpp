// Global interpolation and least-squares approximation: through the data (1e-12), reproduction of
// polynomials of the degree (sampled from a Bézier curve, so the reference is independent),
// agreement of the cubic with end derivatives with the O(n) C2 interpolant of curve/interpolation.h,
// and validation.

#include <catch2/catch.hpp>

#include <freeform/curve/nurbs_interpolation.h>

#include <cmath>

#include "support/random.h"

namespace test_nurbs_interpolation {

using namespace freeform;
using freeform::test::randomPoints;

TEST_CASE("interpolation passes through the data for degrees 1-7 and every parametrisation", "[nurbs][interpolation]")
{
    const auto data = randomPoints<double, 3>(12, 5);
    for (int p = 1; p <= 7; ++p)
        for (Parametrization param : {Parametrization::Uniform, Parametrization::Chord, Parametrization::Centripetal}) {
            NurbsFitOptions<double, 3> options;
            options.parametrization = param;
            const auto c = interpolateNurbs<double, 3>(data, p, options);
            // The parameters, recomputed here independently.
            std::vector<double> u(12, 0.0);
            for (int i = 1; i < 12; ++i) {
                const double chord = (data.col(i) - data.col(i - 1)).norm();
                u[i] = u[i - 1] + (param == Parametrization::Uniform ? 1.0 : param == Parametrization::Chord ? chord : std::sqrt(chord));
            }
            CAPTURE(p, toString(param));
            for (int i = 0; i < 12; ++i) CHECK((c(u[i] / u[11]) - data.col(i)).norm() <= 1e-12);
            CHECK(c.degree() == p);
            CHECK(c.controlCount() == 12);
        }
}

TEST_CASE("interpolation and approximation reproduce polynomials of their degree", "[nurbs][interpolation]")
{
    for (int p = 1; p <= 6; ++p) {
        const BezierCurve<double, 2> poly(randomPoints<double, 2>(p + 1, 70u + p));
        std::vector<double> t;
        for (int i = 0; i < 15; ++i) t.push_back(std::pow(i / 14.0, 1.3)); // non-uniform parameters
        PointMatrix<double, 2> data(2, 15);
        for (int i = 0; i < 15; ++i) data.col(i) = poly(t[i]);
        NurbsFitOptions<double, 2> options;
        options.params = t;
        const auto c = interpolateNurbs<double, 2>(data, p, options);
        const auto a = approximateNurbs<double, 2>(data, p, p + 3, options);
        for (int i = 0; i <= 100; ++i) {
            CAPTURE(p, i);
            CHECK((c(i / 100.0) - poly(i / 100.0)).norm() <= 1e-12);
            CHECK((a(i / 100.0) - poly(i / 100.0)).norm() <= 1e-12);
        }
    }
}

TEST_CASE("the cubic with end derivatives is the clamped C2 interpolant of interpolateCubic", "[nurbs][interpolation]")
{
    const auto data = randomPoints<double, 2>(9, 11);
    InterpolationOptions<double, 2> cubicOptions;
    cubicOptions.end = InterpolationEnd::Clamped;
    cubicOptions.parametrization = Parametrization::Chord;
    // interpolateCubic's derivatives are with respect to the chord-length parameter; the NURBS
    // ones with respect to the normalised one: scale by the total length.
    double total = 0;
    for (int i = 1; i < 9; ++i) total += (data.col(i) - data.col(i - 1)).norm();
    cubicOptions.startDerivative = Eigen::Vector2d(1, 2);
    cubicOptions.endDerivative = Eigen::Vector2d(-0.5, 1);
    const auto spline = interpolateCubic<double, 2>(data, cubicOptions);
    NurbsFitOptions<double, 2> options;
    options.startDerivative = Eigen::Vector2d(1, 2) * total;
    options.endDerivative = Eigen::Vector2d(-0.5, 1) * total;
    const auto c = interpolateNurbs<double, 2>(data, 3, options);
    const auto pieces = c.bezierPieces();
    REQUIRE(static_cast<int>(pieces.size()) == spline.segmentCount());
    for (int i = 0; i < spline.segmentCount(); ++i)
        for (int j = 0; j <= 3; ++j) CHECK((pieces[i].controlPoint(j) - spline.controlPoints().col(3 * i + j)).norm() <= 1e-13);
}

TEST_CASE("least squares: ends exact, residual no larger than with fewer control points, validation", "[nurbs][interpolation]")
{
    PointMatrix<double, 2> data(2, 40);
    for (int i = 0; i < 40; ++i) data.col(i) = Eigen::Vector2d(i / 39.0, std::sin(6 * i / 39.0));
    NurbsFitOptions<double, 2> options;
    options.parametrization = Parametrization::Uniform;
    double previous = 1e300;
    for (int count : {5, 8, 12, 20}) {
        const auto a = approximateNurbs<double, 2>(data, 3, count, options);
        CHECK((a(0.0) - data.col(0)).norm() == 0.0);
        CHECK((a(1.0) - data.col(39)).norm() <= 1e-15);
        double residual = 0;
        for (int i = 0; i < 40; ++i) residual += (a(i / 39.0) - data.col(i)).squaredNorm();
        CHECK(residual <= previous * (1 + 1e-12));
        previous = residual;
    }
    CHECK(previous <= 1e-8);
    CHECK_THROWS_WITH((interpolateNurbs<double, 2>(data.leftCols(3), 3)), Catch::Contains("too few"));
    NurbsFitOptions<double, 2> half;
    half.startDerivative = Eigen::Vector2d(1, 0);
    CHECK_THROWS_WITH((interpolateNurbs<double, 2>(data, 3, half)), Catch::Contains("both end derivatives"));
    CHECK_THROWS_WITH((approximateNurbs<double, 2>(data, 3, 40)), Catch::Contains("control points"));
    PointMatrix<double, 2> dup = data.leftCols(5);
    dup.col(2) = dup.col(1);
    CHECK_THROWS_WITH((interpolateNurbs<double, 2>(dup, 2)), Catch::Contains("points 1 and 2 coincide"));
}

} // namespace test_nurbs_interpolation
