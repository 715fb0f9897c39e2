// NURBS evaluation speed (3D, double, rational): one curve of 40 control points at 10^5 sorted
// parameters, and one surface of 12 x 12 control points on a 300 x 300 parameter grid, degrees 2, 3
// and 5 (clamped uniform knots, weights in [0.5, 2]). The library's single-point evaluators and its
// batch paths (positions; positions + first derivatives) against Open CASCADE's cached evaluators
// GeomAdaptor_Curve / GeomAdaptor_Surface (D0, D1) on the same geometry in the same run, when Open
// CASCADE is installed (optional peer). docs/performance.md has the figures.
//
//   build/bin/bench_nurbs --benchmark_min_time=0.2

#include <benchmark/benchmark.h>

#include <freeform/curve/nurbs_curve.h>
#include <freeform/surface/nurbs_surface.h>

#include <random>
#include <vector>

#ifdef FREEFORM_BENCH_OCCT
#include <GeomAdaptor_Curve.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array2OfPnt.hxx>
#endif

namespace {

using namespace freeform;
using Curve = NurbsCurve<double, 3>;
using Surface = NurbsSurface<double, 3>;

constexpr int kCurvePoints = 40;
constexpr std::size_t kCount = 100000;
constexpr int kSurfacePoints = 12;
constexpr int kGrid = 300;

Eigen::Matrix3Xd randomPoints(int count, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    Eigen::Matrix3Xd p(3, count);
    for (int i = 0; i < count; ++i) p.col(i) = Eigen::Vector3d(u(rng), u(rng), u(rng));
    return p;
}

Eigen::VectorXd randomWeights(int count, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.5, 2.0);
    Eigen::VectorXd w(count);
    for (int i = 0; i < count; ++i) w[i] = u(rng);
    return w;
}

Curve makeCurve(int p)
{
    return Curve(p, KnotVector<double>::clampedUniform(p, kCurvePoints).knots(), randomPoints(kCurvePoints, 1),
                 randomWeights(kCurvePoints, 2));
}

Surface makeSurface(int p)
{
    const auto k = KnotVector<double>::clampedUniform(p, kSurfacePoints).knots();
    return Surface(p, p, k, k, randomPoints(kSurfacePoints * kSurfacePoints, 3),
                   randomWeights(kSurfacePoints * kSurfacePoints, 4));
}

const std::vector<double>& parameters()
{
    static const std::vector<double> ts = [] {
        std::vector<double> t(kCount);
        for (std::size_t j = 0; j < kCount; ++j) t[j] = double(j) / double(kCount - 1);
        return t;
    }();
    return ts;
}

const std::vector<double>& grid()
{
    static const std::vector<double> g = [] {
        std::vector<double> t(kGrid);
        for (int j = 0; j < kGrid; ++j) t[j] = double(j) / double(kGrid - 1);
        return t;
    }();
    return g;
}

void finish(benchmark::State& state, std::size_t count)
{
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(count));
}

// ---------------------------------------------------------------- curves

void BM_CurveEvaluate(benchmark::State& state)
{
    const Curve c = makeCurve(static_cast<int>(state.range(0)));
    const auto& ts = parameters();
    Eigen::Matrix3Xd out(3, kCount);
    for (auto _ : state) {
        for (std::size_t j = 0; j < kCount; ++j) out.col(static_cast<Eigen::Index>(j)) = c.evaluate(ts[j]);
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    finish(state, kCount);
}

void BM_CurveBatchD0(benchmark::State& state)
{
    const Curve c = makeCurve(static_cast<int>(state.range(0)));
    const auto& ts = parameters();
    Eigen::Matrix3Xd out;
    for (auto _ : state) {
        c.evaluateMany(ts.data(), ts.size(), out);
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    finish(state, kCount);
}

void BM_CurveBatchD1(benchmark::State& state)
{
    const Curve c = makeCurve(static_cast<int>(state.range(0)));
    const auto& ts = parameters();
    Eigen::Matrix3Xd pos, d1;
    for (auto _ : state) {
        c.evaluateManyWithDerivative(ts.data(), ts.size(), pos, d1);
        benchmark::DoNotOptimize(pos.data());
        benchmark::DoNotOptimize(d1.data());
        benchmark::ClobberMemory();
    }
    finish(state, kCount);
}

BENCHMARK(BM_CurveEvaluate)->Arg(2)->Arg(3)->Arg(5)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CurveBatchD0)->Arg(2)->Arg(3)->Arg(5)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CurveBatchD1)->Arg(2)->Arg(3)->Arg(5)->Unit(benchmark::kMillisecond);

// ---------------------------------------------------------------- surfaces

void BM_SurfaceEvaluate(benchmark::State& state)
{
    const Surface s = makeSurface(static_cast<int>(state.range(0)));
    const auto& g = grid();
    Eigen::Matrix3Xd out(3, kGrid * kGrid);
    for (auto _ : state) {
        for (int i = 0; i < kGrid; ++i)
            for (int j = 0; j < kGrid; ++j) out.col(i * kGrid + j) = s.evaluate(g[i], g[j]);
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    finish(state, kGrid * kGrid);
}

void BM_SurfaceGridD0(benchmark::State& state)
{
    const Surface s = makeSurface(static_cast<int>(state.range(0)));
    const auto& g = grid();
    Eigen::Matrix3Xd out;
    for (auto _ : state) {
        s.evaluateGrid(g, g, out);
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    finish(state, kGrid * kGrid);
}

void BM_SurfaceGridD1(benchmark::State& state)
{
    const Surface s = makeSurface(static_cast<int>(state.range(0)));
    const auto& g = grid();
    Eigen::Matrix3Xd out, du, dv;
    for (auto _ : state) {
        s.evaluateGrid(g, g, out, &du, &dv);
        benchmark::DoNotOptimize(out.data());
        benchmark::DoNotOptimize(du.data());
        benchmark::ClobberMemory();
    }
    finish(state, kGrid * kGrid);
}

BENCHMARK(BM_SurfaceEvaluate)->Arg(2)->Arg(3)->Arg(5)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SurfaceGridD0)->Arg(2)->Arg(3)->Arg(5)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SurfaceGridD1)->Arg(2)->Arg(3)->Arg(5)->Unit(benchmark::kMillisecond);

#ifdef FREEFORM_BENCH_OCCT
// ---------------------------------------------------------------- Open CASCADE (optional peer)

/// Distinct knots and multiplicities of a knot vector, 1-based OCCT arrays.
void occtKnots(const std::vector<double>& k, TColStd_Array1OfReal*& knots, TColStd_Array1OfInteger*& mults)
{
    std::vector<double> distinct;
    std::vector<int> mult;
    for (double x : k) {
        if (!distinct.empty() && distinct.back() == x) ++mult.back();
        else { distinct.push_back(x); mult.push_back(1); }
    }
    knots = new TColStd_Array1OfReal(1, static_cast<int>(distinct.size()));
    mults = new TColStd_Array1OfInteger(1, static_cast<int>(distinct.size()));
    for (std::size_t i = 0; i < distinct.size(); ++i) {
        knots->SetValue(static_cast<int>(i) + 1, distinct[i]);
        mults->SetValue(static_cast<int>(i) + 1, mult[i]);
    }
}

Handle(Geom_BSplineCurve) occtCurve(const Curve& c)
{
    TColgp_Array1OfPnt poles(1, c.controlCount());
    TColStd_Array1OfReal weights(1, c.controlCount());
    for (int i = 0; i < c.controlCount(); ++i) {
        const auto p = c.controlPoint(i);
        poles.SetValue(i + 1, gp_Pnt(p.x(), p.y(), p.z()));
        weights.SetValue(i + 1, c.weight(i));
    }
    TColStd_Array1OfReal* knots;
    TColStd_Array1OfInteger* mults;
    occtKnots(c.knots(), knots, mults);
    Handle(Geom_BSplineCurve) curve = new Geom_BSplineCurve(poles, weights, *knots, *mults, c.degree());
    delete knots;
    delete mults;
    return curve;
}

Handle(Geom_BSplineSurface) occtSurface(const Surface& s)
{
    TColgp_Array2OfPnt poles(1, s.countU(), 1, s.countV());
    TColStd_Array2OfReal weights(1, s.countU(), 1, s.countV());
    for (int i = 0; i < s.countU(); ++i)
        for (int j = 0; j < s.countV(); ++j) {
            const auto p = s.controlPoint(i, j);
            poles.SetValue(i + 1, j + 1, gp_Pnt(p.x(), p.y(), p.z()));
            weights.SetValue(i + 1, j + 1, s.weight(i, j));
        }
    TColStd_Array1OfReal *uk, *vk;
    TColStd_Array1OfInteger *um, *vm;
    occtKnots(s.knotsU().knots(), uk, um);
    occtKnots(s.knotsV().knots(), vk, vm);
    Handle(Geom_BSplineSurface) surface =
        new Geom_BSplineSurface(poles, weights, *uk, *vk, *um, *vm, s.degreeU(), s.degreeV());
    delete uk;
    delete vk;
    delete um;
    delete vm;
    return surface;
}

void BM_PeerOcctCurveD0(benchmark::State& state)
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
    finish(state, kCount);
}

void BM_PeerOcctCurveD1(benchmark::State& state)
{
    const GeomAdaptor_Curve adaptor(occtCurve(makeCurve(static_cast<int>(state.range(0)))));
    const auto& ts = parameters();
    std::vector<double> out(6 * kCount);
    for (auto _ : state) {
        gp_Pnt p;
        gp_Vec v;
        for (std::size_t j = 0; j < kCount; ++j) {
            adaptor.D1(ts[j], p, v);
            out[6 * j] = p.X();
            out[6 * j + 1] = p.Y();
            out[6 * j + 2] = p.Z();
            out[6 * j + 3] = v.X();
            out[6 * j + 4] = v.Y();
            out[6 * j + 5] = v.Z();
        }
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    finish(state, kCount);
}

void BM_PeerOcctSurfaceD0(benchmark::State& state)
{
    const GeomAdaptor_Surface adaptor(occtSurface(makeSurface(static_cast<int>(state.range(0)))));
    const auto& g = grid();
    std::vector<double> out(3 * kGrid * kGrid);
    for (auto _ : state) {
        gp_Pnt p;
        for (int i = 0; i < kGrid; ++i)
            for (int j = 0; j < kGrid; ++j) {
                adaptor.D0(g[i], g[j], p);
                const std::size_t k = 3 * static_cast<std::size_t>(i * kGrid + j);
                out[k] = p.X();
                out[k + 1] = p.Y();
                out[k + 2] = p.Z();
            }
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    finish(state, kGrid * kGrid);
}

void BM_PeerOcctSurfaceD1(benchmark::State& state)
{
    const GeomAdaptor_Surface adaptor(occtSurface(makeSurface(static_cast<int>(state.range(0)))));
    const auto& g = grid();
    std::vector<double> out(9 * kGrid * kGrid);
    for (auto _ : state) {
        gp_Pnt p;
        gp_Vec du, dv;
        for (int i = 0; i < kGrid; ++i)
            for (int j = 0; j < kGrid; ++j) {
                adaptor.D1(g[i], g[j], p, du, dv);
                const std::size_t k = 9 * static_cast<std::size_t>(i * kGrid + j);
                out[k] = p.X();
                out[k + 1] = p.Y();
                out[k + 2] = p.Z();
                out[k + 3] = du.X();
                out[k + 4] = du.Y();
                out[k + 5] = du.Z();
                out[k + 6] = dv.X();
                out[k + 7] = dv.Y();
                out[k + 8] = dv.Z();
            }
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    finish(state, kGrid * kGrid);
}

BENCHMARK(BM_PeerOcctCurveD0)->Arg(2)->Arg(3)->Arg(5)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PeerOcctCurveD1)->Arg(2)->Arg(3)->Arg(5)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PeerOcctSurfaceD0)->Arg(2)->Arg(3)->Arg(5)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PeerOcctSurfaceD1)->Arg(2)->Arg(3)->Arg(5)->Unit(benchmark::kMillisecond);
#endif

} // namespace
BENCHMARK_MAIN();
