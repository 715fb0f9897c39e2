// Splines at scale (2D, double): C2 cubic interpolation of n points under each end condition
// (chord-length parameters, the result a BezierSpline), the A-frame of n de Boor points under each
// end condition, and as the peer in the same run a plain natural-spline Thomas solve written the
// textbook way (second derivatives per coordinate, Numerical Recipes' `spline`, chord parameters,
// fresh arrays per call, no Bézier output). docs/performance.md has the figures.
//
//   build/bin/bench_spline --benchmark_min_time=0.5

#include <benchmark/benchmark.h>

#include <freeform/curve/aframe.h>
#include <freeform/curve/interpolation.h>

#include <cmath>
#include <random>
#include <vector>

namespace {

using Points = freeform::PointMatrix<double, 2>;

/// A wiggly open polyline without coincident points: x increases, y random.
Points makePoints(Eigen::Index n)
{
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> u(-1, 1);
    Points p(2, n);
    for (Eigen::Index i = 0; i < n; ++i) p.col(i) = Eigen::Vector2d(double(i) + 0.25 * u(rng), u(rng));
    return p;
}

void finish(benchmark::State& state)
{
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * state.range(0));
}

void interpolate(benchmark::State& state, freeform::InterpolationEnd end)
{
    const Points p = makePoints(state.range(0));
    freeform::InterpolationOptions<double, 2> opt;
    opt.end = end;
    opt.parametrization = freeform::Parametrization::Chord;
    opt.startDerivative = Eigen::Vector2d(1, 0);
    opt.endDerivative = Eigen::Vector2d(1, 0);
    for (auto _ : state) {
        auto s = freeform::interpolateCubic(p, opt);
        benchmark::DoNotOptimize(s.controlPoints().data());
    }
    finish(state);
}

void BM_InterpolateNatural(benchmark::State& state) { interpolate(state, freeform::InterpolationEnd::Natural); }
void BM_InterpolateClamped(benchmark::State& state) { interpolate(state, freeform::InterpolationEnd::Clamped); }
void BM_InterpolatePeriodic(benchmark::State& state) { interpolate(state, freeform::InterpolationEnd::Periodic); }

/// The peer: chord parameters, then for x and y separately the natural spline's second
/// derivatives by the textbook tridiagonal sweep.
void BM_PeerThomasNatural(benchmark::State& state)
{
    const Points p = makePoints(state.range(0));
    const std::size_t n = static_cast<std::size_t>(state.range(0));
    for (auto _ : state) {
        // Fresh arrays per call, like the library's (which returns a new spline every call).
        std::vector<double> u(n), y(n), work(n);
        std::vector<std::vector<double>> second(2, std::vector<double>(n));
        u[0] = 0;
        for (std::size_t i = 1; i < n; ++i) u[i] = u[i - 1] + (p.col(i) - p.col(i - 1)).norm();
        for (int k = 0; k < 2; ++k) {
            std::vector<double>& y2 = second[static_cast<std::size_t>(k)];
            for (std::size_t i = 0; i < n; ++i) y[i] = p(k, static_cast<Eigen::Index>(i));
            y2[0] = work[0] = 0;
            for (std::size_t i = 1; i + 1 < n; ++i) {
                const double sig = (u[i] - u[i - 1]) / (u[i + 1] - u[i - 1]);
                const double q = sig * y2[i - 1] + 2;
                y2[i] = (sig - 1) / q;
                work[i] = (y[i + 1] - y[i]) / (u[i + 1] - u[i]) - (y[i] - y[i - 1]) / (u[i] - u[i - 1]);
                work[i] = (6 * work[i] / (u[i + 1] - u[i - 1]) - sig * work[i - 1]) / q;
            }
            y2[n - 1] = 0;
            for (std::size_t i = n - 1; i-- > 0;) y2[i] = y2[i] * y2[i + 1] + work[i];
            benchmark::DoNotOptimize(y2.data());
        }
    }
    finish(state);
}

void aframe(benchmark::State& state, freeform::EndCondition end)
{
    const Points d = makePoints(state.range(0));
    std::vector<double> h(static_cast<std::size_t>(freeform::aframeSegmentCount(static_cast<int>(d.cols()), end)));
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> len(0.5, 2.0);
    for (double& x : h) x = len(rng);
    for (auto _ : state) {
        auto b = freeform::aframeBezierPoints<double, 2>(d, end, h);
        benchmark::DoNotOptimize(b.data());
    }
    finish(state);
}

void BM_AframeOpen(benchmark::State& state) { aframe(state, freeform::EndCondition::Open); }
void BM_AframeClamped(benchmark::State& state) { aframe(state, freeform::EndCondition::Clamped); }
void BM_AframeClosed(benchmark::State& state) { aframe(state, freeform::EndCondition::Closed); }

} // namespace

BENCHMARK(BM_PeerThomasNatural)->Arg(1000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InterpolateNatural)->Arg(1000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InterpolateClamped)->Arg(1000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InterpolatePeriodic)->Arg(1000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AframeOpen)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AframeClamped)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AframeClosed)->Arg(1000000)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
