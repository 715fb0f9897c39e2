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

#ifdef FREEFORM_BENCH_OCCT
#include <GeomAdaptor_Curve.hxx>
#include <Geom_BezierCurve.hxx>
#include <TColgp_Array1OfPnt.hxx>
#endif

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

// Peer: the plain Bernstein loop: powers of t forwards, of (1-t) backwards, then the sum.
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
            double basis[freeform::kMaxDegree + 1];
            double power = 1;
            for (int i = 0; i <= n; ++i, power *= t) basis[i] = binom[i] * power;
            power = 1;
            for (int i = n; i >= 0; --i, power *= 1 - t) basis[i] *= power;
            double x = 0, y = 0, z = 0;
            for (int i = 0; i <= n; ++i) {
                const double b = basis[i];
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

#ifdef FREEFORM_BENCH_OCCT
Handle(Geom_BezierCurve) occtCurve(const Curve& c)
{
    TColgp_Array1OfPnt poles(1, c.degree() + 1);
    for (int i = 0; i <= c.degree(); ++i) {
        const auto p = c.controlPoint(i);
        poles.SetValue(i + 1, gp_Pnt(p.x(), p.y(), p.z()));
    }
    return new Geom_BezierCurve(poles);
}

// Peer: Open CASCADE's Geom_BezierCurve::D0.
void BM_PeerOcctBezierD0(benchmark::State& state)
{
    const Handle(Geom_BezierCurve) curve = occtCurve(makeCurve(static_cast<int>(state.range(0))));
    const auto& ts = parameters();
    std::vector<double> out(3 * kCount);
    for (auto _ : state) {
        gp_Pnt p;
        for (std::size_t j = 0; j < kCount; ++j) {
            curve->D0(ts[j], p);
            out[3 * j] = p.X();
            out[3 * j + 1] = p.Y();
            out[3 * j + 2] = p.Z();
        }
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    finish(state);
}

// Peer: Open CASCADE's cached evaluator GeomAdaptor_Curve::D0 (Horner on a power-basis copy).
void BM_PeerOcctAdaptorD0(benchmark::State& state)
{
    const GeomAdaptor_Curve adaptor(occtCurve(makeCurve(static_cast<int>(state.range(0)))));
    const auto& ts = parameters();
    std::vector<double> out(3 * kCount);
    for (auto _ : state) {
        gp_Pnt p;
        for (std::size_t j = 0; j < kCount; ++j) {
            adaptor.D0(ts[j], p);
            out[3 * j] = p.X();
            out[3 * j + 1] = p.Y();
            out[3 * j + 2] = p.Z();
        }
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    finish(state);
}
BENCHMARK(BM_PeerOcctBezierD0)->Arg(3)->Arg(7)->Arg(15)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PeerOcctAdaptorD0)->Arg(3)->Arg(7)->Arg(15)->Unit(benchmark::kMillisecond);
#endif

} // namespace

BENCHMARK(BM_DeCasteljau)->Arg(3)->Arg(7)->Arg(15)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BernsteinSum)->Arg(3)->Arg(7)->Arg(15)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Batch)->Arg(3)->Arg(7)->Arg(15)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PeerPlainBernstein)->Arg(3)->Arg(7)->Arg(15)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PeerPlainDeCasteljau)->Arg(3)->Arg(7)->Arg(15)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
