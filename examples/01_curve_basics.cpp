// The curve API in one page: build a cubic, evaluate it two ways, take derivatives, split it,
// elevate it and measure it.
//
//   build/bin/example_01_curve_basics

#include <freeform/curve/bezier_curve.h>

#include <iostream>

int main()
{
    using Curve = freeform::BezierCurve<double, 2>;
    const Curve arch({{0, 0}, {1, 2}, {3, 2}, {4, 0}});

    std::cout << "degree " << arch.degree() << "\n";
    std::cout << "f(1/2) by de Casteljau  = " << arch.deCasteljau(0.5).transpose() << "\n";
    std::cout << "f(1/2) by Bernstein sum = " << arch.bernsteinSum(0.5).transpose() << "\n";

    const auto d = arch.derivatives(0.5, 2); // columns: f, f', f''
    std::cout << "f'(1/2) = " << d.col(1).transpose() << ", f''(1/2) = " << d.col(2).transpose() << "\n";
    std::cout << "curvature at 1/2 = " << arch.curvature(0.5) << " (negative: turning right)\n";

    const auto [left, right] = arch.split(0.25);
    std::cout << "split at 1/4: left ends at " << left.controlPoint(3).transpose() << ", right starts at "
              << right.controlPoint(0).transpose() << "\n";

    const Curve quartic = arch.elevated();
    std::cout << "elevated to degree " << quartic.degree() << ", f(0.3) unchanged: "
              << (quartic.evaluate(0.3) - arch.evaluate(0.3)).norm() << "\n";

    std::cout << "arc length = " << arch.arcLength(1e-12) << "\n";
    const auto box = arch.boundingBox();
    std::cout << "tight box = [" << box.min().transpose() << "] .. [" << box.max().transpose() << "]\n";
    const auto nearest = arch.closestPoint({2, 3});
    std::cout << "closest to (2, 3): t = " << nearest.t << ", distance " << nearest.distance << "\n";
    return 0;
}
