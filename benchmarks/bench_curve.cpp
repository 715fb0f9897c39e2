// Points per second for one Bézier curve (3D, double) at 10^6 parameters: the library's de
// Casteljau, Bernstein sum and batch path, and two plain peers written the textbook way (a
// Bernstein loop and a de Casteljau loop), measured in the same run. docs/performance.md has the
// figures.
//
//   build/bin/bench_curve --benchmark_min_time=0.5

#include <benchmark/benchmark.h>

#include <freeform/curve/bezier_curve.h>

#include <random>
#include <vector>

namespace {

using Curve = freeform::BezierCurve<double, 3>;
constexpr std::size_t kCount = 1000000;

Curve makeCurve(int n)
{
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> u(-1, 1);
    Curve::Points p(3, n + 1);
    for (int i = 0; i <= n; ++i) p.col(i) = Eigen::Vector3d(u(rng), u(rng), u(rng));
    return Curve(p);
}

const std::vector<double>& parameters()
{
    static const std::vector<double> ts = [] {
        std::vector<double> v(kCount);
        for (std::size_t i = 0; i < kCount; ++i) v[i] = double(i) / double(kCount - 1);
        return v;
    }();
    return ts;
}

void finish(benchmark::State& state)
{
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(kCount));
}

void BM_DeCasteljau(benchmark::State& state)
{
    const Curve c = makeCurve(static_cast<int>(state.range(0)));
    const auto& ts = parameters();
    for (auto _ : state) {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        for (double t : ts) sum += c.deCasteljau(t);
        benchmark::DoNotOptimize(sum);
    }
    finish(state);
}

void BM_BernsteinSum(benchmark::State& state)
{
    const Curve c = makeCurve(static_cast<int>(state.range(0)));
    const auto& ts = parameters();
    for (auto _ : state) {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        for (double t : ts) sum += c.bernsteinSum(t);
        benchmark::DoNotOptimize(sum);
    }
    finish(state);
}

void BM_Batch(benchmark::State& state)
{
    const Curve c = makeCurve(static_cast<int>(state.range(0)));
    const auto& ts = parameters();
    Curve::Points out;
    for (auto _ : state) {
        c.evaluateMany(ts.data(), ts.size(), out);
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    finish(state);
}

// Peer: the plain Bernstein loop (binomial * t^i * (1-t)^(n-i) with std::pow), arrays of doubles.
void BM_PeerPlainBernstein(benchmark::State& state)
{
    const int n = static_cast<int>(state.range(0));
    const Curve c = makeCurve(n);
    std::vector<double> pts(c.controlPoints().data(), c.controlPoints().data() + 3 * (n + 1));
    std::vector<double> binom(n + 1);
    for (int i = 0; i <= n; ++i) binom[i] = double(freeform::binomial(n, i));
    const auto& ts = parameters();
    std::vector<double> out(3 * kCount);
    for (auto _ : state) {
        for (std::size_t j = 0; j < kCount; ++j) {
            const double t = ts[j];
            double x = 0, y = 0, z = 0;
            for (int i = 0; i <= n; ++i) {
                const double b = binom[i] * std::pow(t, i) * std::pow(1 - t, n - i);
                x += b * pts[3 * i];
                y += b * pts[3 * i + 1];
                z += b * pts[3 * i + 2];
            }
            out[3 * j] = x;
            out[3 * j + 1] = y;
            out[3 * j + 2] = z;
        }
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    finish(state);
}

// Peer: the plain de Casteljau loop on a scratch array.
void BM_PeerPlainDeCasteljau(benchmark::State& state)
{
    const int n = static_cast<int>(state.range(0));
    const Curve c = makeCurve(n);
    std::vector<double> pts(c.controlPoints().data(), c.controlPoints().data() + 3 * (n + 1));
    std::vector<double> w(pts.size());
    const auto& ts = parameters();
    std::vector<double> out(3 * kCount);
    for (auto _ : state) {
        for (std::size_t j = 0; j < kCount; ++j) {
            const double t = ts[j], s = 1 - t;
            std::copy(pts.begin(), pts.end(), w.begin());
            for (int k = 1; k <= n; ++k)
                for (int i = 0; i <= n - k; ++i)
                    for (int d = 0; d < 3; ++d) w[3 * i + d] = s * w[3 * i + d] + t * w[3 * (i + 1) + d];
            out[3 * j] = w[0];
            out[3 * j + 1] = w[1];
            out[3 * j + 2] = w[2];
        }
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    finish(state);
}

} // namespace

BENCHMARK(BM_DeCasteljau)->Arg(3)->Arg(7)->Arg(15)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BernsteinSum)->Arg(3)->Arg(7)->Arg(15)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Batch)->Arg(3)->Arg(7)->Arg(15)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PeerPlainBernstein)->Arg(3)->Arg(7)->Arg(15)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PeerPlainDeCasteljau)->Arg(3)->Arg(7)->Arg(15)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
