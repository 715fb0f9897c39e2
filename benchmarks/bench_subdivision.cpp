// Limit-surface tessellation of a 10,000-face cage at 8 x 8 segments per face, two routes in one
// run: OpenSubdiv (Bfr::Surface per face, SubdivisionSurface::tessellate: evaluation of position
// and first derivatives, shared edge points) and the Bézier route for the regular faces (the
// tensor-product A-frame of each face's 4 x 4 de Boor points, then the library's patch
// tessellation, tessellate/tessellate.h). The cage is a 100 x 100 torus-shaped quad grid with a
// bumpy radius: every vertex has valence 4, so every face is regular and both routes cover the
// same surface. Also the set-up cost (cage validation, OpenSubdiv topology, one Bfr::Surface per
// face). Figures: docs/performance.md. BM_CertifiedCube: the certified tessellation of the cube cage
// at 1e-3 (docs/subdivision.md); BM_CertifiedPrism and BM_CertifiedCreasedCube the same for the
// cages whose irregular cells go past OpenSubdiv's depth 10 (valence-5 vertices, sharp corners);
// BM_CertifiedLoopOctahedron a closed Loop cage. The rows with an argument (2: 1e-2, 3: 1e-3):
// data/cages/torus.obj (every cell regular) and the cages certified later: a Catmull-Clark cube
// with a hole, a 6 x 6 open grid under edge_only (one-face corners) and under edge_and_corner, a
// Loop open fan and a Loop octahedron with infinitely sharp creases and a corner. Every certified
// row reports triangles, bound, leaves, depth, and faces_certified of faces as counters.
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

// Runs the certified tessellation of `cage` at `tolerance` and reports the triangles, the bound
// reached, the leaves, the depth of the irregular cells and how many cage faces are certified
// (report.faceCertified; a hole or a face without a limit surface counts as certified, see
// docs/subdivision.md).
void certified(benchmark::State& state, const freeform::SubdivisionCage& cage, double tolerance = 1e-3,
               freeform::SubdivisionScheme scheme = freeform::SubdivisionScheme::Catmark,
               freeform::BoundaryInterpolation boundary = freeform::BoundaryInterpolation::EdgeOnly)
{
    const freeform::SubdivisionSurface s(cage, scheme, boundary);
    freeform::SubdivisionTessellationOptions o;
    o.tolerance = tolerance;
    freeform::SubdivisionTessellationReport report;
    freeform::PolygonMesh mesh;
    for (auto _ : state) {
        mesh = s.tessellate(o, &report);
        benchmark::DoNotOptimize(mesh.positions.data());
    }
    if (!report.certifiedPath) state.SkipWithError("the certified path did not run");
    int faces = 0;
    for (char f : report.faceCertified) faces += f;
    state.counters["triangles"] = static_cast<double>(mesh.faceCount());
    state.counters["bound"] = report.errorBound;
    state.counters["leaves"] = static_cast<double>(report.leaves);
    state.counters["depth"] = report.depth;
    state.counters["faces_certified"] = faces;
    state.counters["faces"] = static_cast<double>(report.faceCertified.size());
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
freeform::SubdivisionCage octahedronCage()
{
    freeform::SubdivisionCage cage;
    cage.mesh.positions.resize(3, 6);
    cage.mesh.positions << 1, -1, 0, 0, 0, 0, 0, 0, 1, -1, 0, 0, 0, 0, 0, 0, 1, -1;
    for (auto f : {std::array{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}})
        cage.mesh.addFace(f.begin(), f.end());
    return cage;
}

void BM_CertifiedLoopOctahedron(benchmark::State& state)
{
    certified(state, octahedronCage(), 1e-3, freeform::SubdivisionScheme::Loop);
}
BENCHMARK(BM_CertifiedLoopOctahedron)->Unit(benchmark::kMillisecond);

// data/cages/torus.obj (scripts/make_cages.py): an 8 x 4 quad cage, radii 2 and 0.75, every vertex
// regular, so every cell is a bicubic patch split by de Casteljau (docs/subdivision.md, the
// one-direction last split: 65,536 -> 35,264 triangles at 1e-3). Argument as below.
void BM_CertifiedTorus(benchmark::State& state)
{
    freeform::SubdivisionCage cage;
    const int nMajor = 8, nMinor = 4;
    const double pi = 3.14159265358979323846;
    cage.mesh.positions.resize(3, nMajor * nMinor);
    for (int i = 0; i < nMajor; ++i)
        for (int j = 0; j < nMinor; ++j) {
            const double a = 2 * pi * i / nMajor, b = 2 * pi * j / nMinor, r = 2.0 + 0.75 * std::cos(b);
            cage.mesh.positions.col(i * nMinor + j) = Eigen::Vector3d(r * std::cos(a), r * std::sin(a), 0.75 * std::sin(b));
        }
    auto idx = [&](int i, int j) { return (i % nMajor) * nMinor + (j % nMinor); };
    for (int i = 0; i < nMajor; ++i)
        for (int j = 0; j < nMinor; ++j) cage.mesh.addFace({idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)});
    certified(state, cage, std::pow(10.0, -static_cast<double>(state.range(0))));
}
BENCHMARK(BM_CertifiedTorus)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond);

// The cages certified since (docs/subdivision.md: "Holes", "Smooth boundary corners", "Loop
// cages"), each at 1e-2 and 1e-3 (the argument: 2 or 3, the tolerance 10^-arg).
double tolerance(const benchmark::State& state) { return std::pow(10.0, -static_cast<double>(state.range(0))); }

// The cube with face 2 a hole (tests/test_subdivision_tessellation_features.cpp): an open disc, the
// faces next to the hole keep their limit surface.
void BM_CertifiedCubeWithHole(benchmark::State& state)
{
    freeform::SubdivisionCage cage = cubeCage();
    cage.holes = {2};
    certified(state, cage, tolerance(state));
}
BENCHMARK(BM_CertifiedCubeWithHole)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond);

// The 6 x 6 open grid of tests/test_subdivision_tessellation.cpp (spacing 0.4, heights 0.3 sin(1.3 r
// + 0.7 c^2)): under edge_only its four corner vertices have one face each (bounded by their
// 1-ring hull, docs/subdivision.md "Smooth boundary corners"); under edge_and_corner they are sharp
// corners.
freeform::SubdivisionCage openGridCage()
{
    freeform::SubdivisionCage cage;
    const int n = 6;
    cage.mesh.positions.resize(3, n * n);
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c)
            cage.mesh.positions.col(r * n + c) = Eigen::Vector3d(0.4 * r, 0.4 * c, 0.3 * std::sin(1.3 * r + 0.7 * c * c));
    for (int r = 0; r + 1 < n; ++r)
        for (int c = 0; c + 1 < n; ++c) cage.mesh.addFace({r * n + c, (r + 1) * n + c, (r + 1) * n + c + 1, r * n + c + 1});
    return cage;
}

void BM_CertifiedGridEdgeOnly(benchmark::State& state)
{
    certified(state, openGridCage(), tolerance(state), freeform::SubdivisionScheme::Catmark, freeform::BoundaryInterpolation::EdgeOnly);
}
BENCHMARK(BM_CertifiedGridEdgeOnly)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond);

void BM_CertifiedGridEdgeAndCorner(benchmark::State& state)
{
    certified(state, openGridCage(), tolerance(state), freeform::SubdivisionScheme::Catmark,
              freeform::BoundaryInterpolation::EdgeAndCorner);
}
BENCHMARK(BM_CertifiedGridEdgeAndCorner)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond);

// The open Loop fan of tests/test_subdivision_tessellation_loop.cpp, radius 1: six triangles around a
// centre raised by 0.5, one boundary loop under edge_only (its cells bounded to first order).
void BM_CertifiedLoopFan(benchmark::State& state)
{
    freeform::SubdivisionCage cage;
    cage.mesh.positions.resize(3, 7);
    const double pi = 3.14159265358979323846;
    cage.mesh.positions.col(0) = Eigen::Vector3d(0, 0, 0.5);
    for (int k = 0; k < 6; ++k) cage.mesh.positions.col(k + 1) = Eigen::Vector3d(std::cos(k * pi / 3), std::sin(k * pi / 3), 0);
    for (int k = 0; k < 6; ++k) cage.mesh.addFace({0, k + 1, (k + 1) % 6 + 1});
    certified(state, cage, tolerance(state), freeform::SubdivisionScheme::Loop, freeform::BoundaryInterpolation::EdgeOnly);
}
BENCHMARK(BM_CertifiedLoopFan)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond);

// The octahedron with half its equator (+x, +y, -x) infinitely sharp, ending at two darts, and its
// top an infinitely sharp corner (tests/test_subdivision_tessellation_loop.cpp).
void BM_CertifiedLoopCreasedOctahedron(benchmark::State& state)
{
    freeform::SubdivisionCage cage = octahedronCage();
    cage.creases = {{0, 2, freeform::kInfiniteSharpness}, {2, 1, freeform::kInfiniteSharpness}};
    cage.corners = {{4, freeform::kInfiniteSharpness}};
    certified(state, cage, tolerance(state), freeform::SubdivisionScheme::Loop);
}
BENCHMARK(BM_CertifiedLoopCreasedOctahedron)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond);

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
