// Limit-surface tessellation of a 10,000-face cage at 8 x 8 segments per face, two routes in one
// run: OpenSubdiv (Bfr::Surface per face, SubdivisionSurface::tessellate: evaluation of position
// and first derivatives, shared edge points) and the Bézier route for the regular faces (the
// tensor-product A-frame of each face's 4 x 4 de Boor points, then the library's patch
// tessellation, tessellate/tessellate.h). The cage is a 100 x 100 torus-shaped quad grid with a
// bumpy radius: every vertex has valence 4, so every face is regular and both routes cover the
// same surface. Also the set-up cost (cage validation, OpenSubdiv topology, one Bfr::Surface per
// face). Figures: docs/performance.md. BM_CertifiedCube: the certified tessellation of the cube cage
// at 1e-3 (docs/subdivision.md); BM_CertifiedPrism and BM_CertifiedCreasedCube the same for the
// cages whose irregular cells go past OpenSubdiv's depth 10 (valence-5 vertices, sharp corners).
//
//   build/bin/bench_subdivision --benchmark_min_time=1

#include <benchmark/benchmark.h>

#include <array>
#include <cmath>

#include "freeform/subdivision/subdivision_surface.h"
#include "freeform/tessellate/tessellate.h"

namespace {

constexpr int kMajor = 100, kMinor = 100, kLevel = 8;

freeform::SubdivisionCage torusCage()
{
    freeform::SubdivisionCage cage;
    cage.mesh.positions.resize(3, kMajor * kMinor);
    const double pi = 3.14159265358979323846;
    for (int i = 0; i < kMajor; ++i)
        for (int j = 0; j < kMinor; ++j) {
            const double a = 2 * pi * i / kMajor, b = 2 * pi * j / kMinor;
            const double r = 1 + 0.05 * std::sin(7 * a) * std::cos(5 * b);
            const double rr = 3 + r * std::cos(b);
            cage.mesh.positions.col(i * kMinor + j) = Eigen::Vector3d(rr * std::cos(a), rr * std::sin(a), r * std::sin(b));
        }
    auto idx = [](int i, int j) { return (i % kMajor) * kMinor + (j % kMinor); };
    for (int i = 0; i < kMajor; ++i)
        for (int j = 0; j < kMinor; ++j) cage.mesh.addFace({idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)});
    return cage;
}

const freeform::SubdivisionSurface& surface()
{
    static const freeform::SubdivisionSurface s(torusCage(), freeform::SubdivisionScheme::Catmark);
    return s;
}

void counters(benchmark::State& state, const freeform::PolygonMesh& mesh)
{
    state.counters["triangles"] = static_cast<double>(mesh.faceCount());
    state.counters["vertices"] = static_cast<double>(mesh.vertexCount());
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * kMajor * kMinor);
}

void BM_OpenSubdivTessellate(benchmark::State& state)
{
    const auto& s = surface();
    freeform::SubdivisionTessellationOptions o;
    o.level = kLevel;
    freeform::PolygonMesh mesh;
    for (auto _ : state) {
        mesh = s.tessellate(o);
        benchmark::DoNotOptimize(mesh.positions.data());
    }
    counters(state, mesh);
}
BENCHMARK(BM_OpenSubdivTessellate)->Unit(benchmark::kMillisecond);

void BM_BezierRouteTessellate(benchmark::State& state)
{
    const auto& s = surface();
    freeform::PolygonMesh mesh;
    std::size_t patches = 0;
    for (auto _ : state) {
        const freeform::PatchComplex complex = s.regularBezierPatches(); // A-frame, face by face
        mesh = freeform::tessellateUniform(complex, kLevel, kLevel);
        patches = complex.patches.size();
        benchmark::DoNotOptimize(mesh.positions.data());
    }
    if (patches != static_cast<std::size_t>(kMajor * kMinor)) state.SkipWithError("not every face is regular");
    counters(state, mesh);
}
BENCHMARK(BM_BezierRouteTessellate)->Unit(benchmark::kMillisecond);

void BM_BezierRouteConversionOnly(benchmark::State& state)
{
    const auto& s = surface();
    for (auto _ : state) {
        const freeform::PatchComplex complex = s.regularBezierPatches();
        benchmark::DoNotOptimize(complex.patches.data());
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * kMajor * kMinor);
}
BENCHMARK(BM_BezierRouteConversionOnly)->Unit(benchmark::kMillisecond);

// The certified tessellation (docs/subdivision.md, "Certified tessellation") of the cube cage (8
// valence-3 extraordinary vertices, side 2) at 1e-3: triangles, the bound reached, and time.
freeform::SubdivisionCage cubeCage()
{
    freeform::SubdivisionCage cage;
    cage.mesh.positions.resize(3, 8);
    for (int i = 0; i < 8; ++i) cage.mesh.positions.col(i) = Eigen::Vector3d(i & 4 ? 1 : -1, i & 2 ? 1 : -1, i & 1 ? 1 : -1);
    for (auto f : {std::array{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}})
        cage.mesh.addFace(f.begin(), f.end());
    return cage;
}

void certified(benchmark::State& state, const freeform::SubdivisionCage& cage)
{
    const freeform::SubdivisionSurface s(cage, freeform::SubdivisionScheme::Catmark);
    freeform::SubdivisionTessellationOptions o;
    o.tolerance = 1e-3;
    freeform::SubdivisionTessellationReport report;
    freeform::PolygonMesh mesh;
    for (auto _ : state) {
        mesh = s.tessellate(o, &report);
        benchmark::DoNotOptimize(mesh.positions.data());
    }
    state.counters["triangles"] = static_cast<double>(mesh.faceCount());
    state.counters["bound"] = report.errorBound;
    state.counters["leaves"] = static_cast<double>(report.leaves);
    state.counters["depth"] = report.depth;
}

void BM_CertifiedCube(benchmark::State& state) { certified(state, cubeCage()); }
BENCHMARK(BM_CertifiedCube)->Unit(benchmark::kMillisecond);

// The pentagonal prism of tests/test_subdivision_tessellation.cpp (radius 1, height 1.2): refined
// once to quads, ten valence-5 extraordinary vertices.
void BM_CertifiedPrism(benchmark::State& state)
{
    freeform::SubdivisionCage cage;
    cage.mesh.positions.resize(3, 10);
    const double pi = 3.14159265358979323846;
    for (int k = 0; k < 5; ++k) {
        const double a = 2 * pi * k / 5;
        cage.mesh.positions.col(k) = Eigen::Vector3d(std::cos(a), std::sin(a), -0.6);
        cage.mesh.positions.col(k + 5) = Eigen::Vector3d(std::cos(a), std::sin(a), 0.6);
    }
    cage.mesh.addFace({4, 3, 2, 1, 0});
    cage.mesh.addFace({5, 6, 7, 8, 9});
    for (int k = 0; k < 5; ++k) cage.mesh.addFace({k, (k + 1) % 5, (k + 1) % 5 + 5, k + 5});
    certified(state, cage);
}
BENCHMARK(BM_CertifiedPrism)->Unit(benchmark::kMillisecond);

// data/cages/creased_cube.obj: the cube with the four edges of its +z face infinitely sharp and two
// of their corners sharp.
void BM_CertifiedCreasedCube(benchmark::State& state)
{
    freeform::SubdivisionCage cage = cubeCage();
    for (auto [a, b] : {std::array{1, 3}, {3, 7}, {7, 5}, {5, 1}}) cage.creases.push_back({a, b, freeform::kInfiniteSharpness});
    for (int v : {1, 7}) cage.corners.push_back({v, freeform::kInfiniteSharpness});
    certified(state, cage);
}
BENCHMARK(BM_CertifiedCreasedCube)->Unit(benchmark::kMillisecond);

// The certified tessellation of a closed Loop cage (docs/subdivision.md, "Loop cages"): the
// octahedron (6 valence-4 extraordinary vertices, radius 1) at 1e-3.
void BM_CertifiedLoopOctahedron(benchmark::State& state)
{
    freeform::SubdivisionCage cage;
    cage.mesh.positions.resize(3, 6);
    cage.mesh.positions << 1, -1, 0, 0, 0, 0, 0, 0, 1, -1, 0, 0, 0, 0, 0, 0, 1, -1;
    for (auto f : {std::array{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}})
        cage.mesh.addFace(f.begin(), f.end());
    const freeform::SubdivisionSurface s(cage, freeform::SubdivisionScheme::Loop);
    freeform::SubdivisionTessellationOptions o;
    o.tolerance = 1e-3;
    freeform::SubdivisionTessellationReport report;
    freeform::PolygonMesh mesh;
    for (auto _ : state) {
        mesh = s.tessellate(o, &report);
        benchmark::DoNotOptimize(mesh.positions.data());
    }
    state.counters["triangles"] = static_cast<double>(mesh.faceCount());
    state.counters["bound"] = report.errorBound;
    state.counters["leaves"] = static_cast<double>(report.leaves);
}
BENCHMARK(BM_CertifiedLoopOctahedron)->Unit(benchmark::kMillisecond);

void BM_OpenSubdivSetUp(benchmark::State& state)
{
    const freeform::SubdivisionCage cage = torusCage();
    for (auto _ : state) {
        const freeform::SubdivisionSurface s(cage, freeform::SubdivisionScheme::Catmark);
        benchmark::DoNotOptimize(&s);
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * kMajor * kMinor);
}
BENCHMARK(BM_OpenSubdivSetUp)->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
