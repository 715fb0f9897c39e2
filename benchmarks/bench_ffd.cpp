// Free-form deformation throughput: V vertices (10^5, 10^6, 10^7, uniform in a box) through a
// cubic lattice (4 x 4 x 4 control points, every one displaced), with the library's FfdBinding
// (float and double, 1 and 2 threads, positions only and positions + normals) and, measured in the
// same run, the plain peer: per vertex the Bernstein values of each axis and the 64-term sum,
// written the textbook way (the compiler leaves it scalar). docs/performance.md has the figures.
//
//   build/bin/bench_ffd --benchmark_min_time=0.5 --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <freeform/core/parallel.h>
#include <freeform/volume/deform.h>

#include <map>
#include <memory>
#include <random>
#include <vector>

namespace {

using freeform::FfdBinding;
using freeform::Lattice;

Eigen::Matrix<double, 3, Eigen::Dynamic> makePoints(std::size_t count)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    Eigen::Matrix<double, 3, Eigen::Dynamic> p(3, static_cast<Eigen::Index>(count));
    for (Eigen::Index i = 0; i < p.cols(); ++i) p.col(i) = Eigen::Vector3d(u(rng), u(rng), u(rng));
    return p;
}

Lattice makeLattice(int degree)
{
    Lattice lat = Lattice::identity({degree, degree, degree}, Eigen::Vector3d(-1.1, -1.1, -1.1),
                                    Eigen::Matrix3d::Identity() * 2.2);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-0.15, 0.15);
    Eigen::Matrix<double, 3, Eigen::Dynamic> pts = lat.controlPoints();
    for (Eigen::Index i = 0; i < pts.cols(); ++i) pts.col(i) += Eigen::Vector3d(u(rng), u(rng), u(rng));
    lat.setControlPoints(pts);
    return lat;
}

/// Bindings are built once per (scalar, count) and kept: binding is not what is measured.
template <typename Scalar>
const FfdBinding<Scalar>& binding(std::size_t count)
{
    static std::map<std::size_t, std::unique_ptr<FfdBinding<Scalar>>> cache;
    auto& slot = cache[count];
    if (!slot) {
        const auto points = makePoints(count);
        slot = std::make_unique<FfdBinding<Scalar>>(makeLattice(3), points);
    }
    return *slot;
}

template <typename Scalar>
void BM_Ffd(benchmark::State& state)
{
    const std::size_t count = static_cast<std::size_t>(state.range(0));
    const int threads = static_cast<int>(state.range(1));
    const Lattice lat = makeLattice(3);
    const auto& b = binding<Scalar>(count);
    std::vector<Scalar> out(3 * count);
    freeform::FfdOutputs<Scalar> o;
    o.positions = out.data();
    freeform::DeformOptions options;
    options.threads = threads;
    for (auto _ : state) {
        b.deform(lat, o, options);
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(count));
}

template <typename Scalar>
void BM_FfdNormals(benchmark::State& state)
{
    const std::size_t count = static_cast<std::size_t>(state.range(0));
    const int threads = static_cast<int>(state.range(1));
    const Lattice lat = makeLattice(3);
    const auto& b = binding<Scalar>(count);
    std::vector<Scalar> out(3 * count), normals(3 * count, Scalar(0)), nout(3 * count);
    for (std::size_t i = 0; i < count; ++i) normals[3 * i + 2] = Scalar(1);
    freeform::FfdOutputs<Scalar> o;
    o.positions = out.data();
    o.normalsIn = normals.data();
    o.normalsOut = nout.data();
    freeform::DeformOptions options;
    options.threads = threads;
    for (auto _ : state) {
        b.deform(lat, o, options);
        benchmark::DoNotOptimize(nout.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(count));
}

// Peer: the plain loop. Per vertex: lattice coordinates, Bernstein values per axis by the
// closed form, then the 64-term sum of weight * control point (full control points, not the
// displacement form). Threads through the same parallelFor as the library.
void BM_PeerPlain(benchmark::State& state)
{
    const std::size_t count = static_cast<std::size_t>(state.range(0));
    const int threads = static_cast<int>(state.range(1));
    const Lattice lat = makeLattice(3);
    const auto points = makePoints(count);
    const Eigen::Matrix<double, 3, Eigen::Dynamic> cp = lat.controlPoints();
    const Eigen::Vector3d origin = lat.origin();
    const Eigen::Matrix3d dual = lat.dual();
    std::vector<double> out(3 * count);
    for (auto _ : state) {
        freeform::parallelFor(0, count, 4096, threads, [&](int, std::size_t first, std::size_t last) {
            for (std::size_t v = first; v < last; ++v) {
                const Eigen::Vector3d stu = dual * (points.col(static_cast<Eigen::Index>(v)) - origin);
                double b[3][4];
                for (int a = 0; a < 3; ++a) {
                    const double t = stu[a], s = 1 - t;
                    b[a][0] = s * s * s;
                    b[a][1] = 3 * t * s * s;
                    b[a][2] = 3 * t * t * s;
                    b[a][3] = t * t * t;
                }
                double x = 0, y = 0, z = 0;
                for (int i = 0; i < 4; ++i)
                    for (int j = 0; j < 4; ++j)
                        for (int k = 0; k < 4; ++k) {
                            const double w = b[0][i] * b[1][j] * b[2][k];
                            const double* p = cp.data() + 3 * (16 * i + 4 * j + k);
                            x += w * p[0];
                            y += w * p[1];
                            z += w * p[2];
                        }
                out[3 * v] = x;
                out[3 * v + 1] = y;
                out[3 * v + 2] = z;
            }
        });
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(count));
}

void sizes(benchmark::internal::Benchmark* b)
{
    for (long count : {100000L, 1000000L, 10000000L})
        for (long threads : {1L, 2L}) b->Args({count, threads});
    b->Unit(benchmark::kMillisecond)->UseRealTime();
}

} // namespace

BENCHMARK_TEMPLATE(BM_Ffd, double)->Apply(sizes);
BENCHMARK_TEMPLATE(BM_Ffd, float)->Apply(sizes);
BENCHMARK_TEMPLATE(BM_FfdNormals, double)->Args({1000000, 1})->Args({1000000, 2})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_TEMPLATE(BM_FfdNormals, float)->Args({1000000, 1})->Args({1000000, 2})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PeerPlain)->Apply(sizes);

BENCHMARK_MAIN();
