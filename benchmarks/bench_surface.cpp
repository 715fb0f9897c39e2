// One bicubic patch on a 1024 x 1024 grid, position + unit normal per point (vertices per second):
// the library's grid path (basis rows and columns tabulated once, SIMD across the row), the same
// patch point by point (jet + normal), and OpenSubdiv's Bfr::Surface evaluating the regular
// Catmull-Clark face whose limit is the same kind of patch (a uniform bicubic B-spline), position
// and first derivatives, with the same cross product and normalisation. Also the Utah teapot
// tessellated to 1e-4 (time and triangle count). Figures: docs/performance.md.
//
//   build/bin/bench_surface --benchmark_min_time=0.5

#include <benchmark/benchmark.h>

#include <freeform/surface/bezier_surface.h>
#include <freeform/io/bpt.h>
#include <freeform/tessellate/tessellate.h>

#include <cmath>
#include <vector>

#ifdef FREEFORM_BENCH_OSD
#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>
#endif

namespace {

constexpr int kGrid = 1024;

std::vector<double> gridParameters()
{
    std::vector<double> t(kGrid);
    for (int i = 0; i < kGrid; ++i) t[i] = static_cast<double>(i) / (kGrid - 1);
    return t;
}

/// 4 x 4 points (i, j, height): the control net of the Bézier patch and the de Boor points of the
/// Catmull-Clark face.
Eigen::Matrix<double, 3, Eigen::Dynamic> net()
{
    Eigen::Matrix<double, 3, Eigen::Dynamic> p(3, 16);
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) p.col(i * 4 + j) = Eigen::Vector3d(i, j, std::sin(1.3 * i + 0.7 * j));
    return p;
}

void finish(benchmark::State& state)
{
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * kGrid * kGrid);
}

void BM_FreeformGrid(benchmark::State& state)
{
    const freeform::BezierSurface<double, 3> s(3, 3, net());
    const auto us = gridParameters();
    Eigen::Matrix<double, 3, Eigen::Dynamic> pos, nrm;
    for (auto _ : state) {
        s.evaluateGrid(us, us, pos, &nrm);
        benchmark::DoNotOptimize(pos.data());
        benchmark::DoNotOptimize(nrm.data());
    }
    finish(state);
}
BENCHMARK(BM_FreeformGrid)->Unit(benchmark::kMillisecond);

void BM_FreeformPointwise(benchmark::State& state)
{
    const freeform::BezierSurface<double, 3> s(3, 3, net());
    const auto us = gridParameters();
    Eigen::Matrix<double, 3, Eigen::Dynamic> pos(3, kGrid * kGrid), nrm(3, kGrid * kGrid);
    for (auto _ : state) {
        for (int i = 0; i < kGrid; ++i)
            for (int j = 0; j < kGrid; ++j) {
                const auto d = s.jet(us[i], us[j], 1);
                pos.col(i * kGrid + j) = d.col(0);
                nrm.col(i * kGrid + j) = Eigen::Vector3d(d.col(1)).cross(Eigen::Vector3d(d.col(2))).normalized();
            }
        benchmark::DoNotOptimize(pos.data());
        benchmark::DoNotOptimize(nrm.data());
    }
    finish(state);
}
BENCHMARK(BM_FreeformPointwise)->Unit(benchmark::kMillisecond);

#ifdef FREEFORM_BENCH_OSD
void BM_OpenSubdivBfr(benchmark::State& state)
{
    using namespace OpenSubdiv;
    // A 3 x 3 grid of quads on 4 x 4 vertices: the centre face (4) is regular.
    std::vector<int> counts(9, 4), indices;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) indices.insert(indices.end(), {r * 4 + c, r * 4 + c + 1, (r + 1) * 4 + c + 1, (r + 1) * 4 + c});
    Far::TopologyDescriptor desc;
    desc.numVertices = 16;
    desc.numFaces = 9;
    desc.numVertsPerFace = counts.data();
    desc.vertIndicesPerFace = indices.data();
    Sdc::Options sdc;
    sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
    Far::TopologyRefiner* refiner = Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Create(
        desc, Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Options(Sdc::SCHEME_CATMARK, sdc));
    Bfr::RefinerSurfaceFactory<> factory(*refiner);
    Bfr::Surface<double> surface;
    if (!factory.InitVertexSurface<double>(4, &surface) || !surface.IsRegular()) {
        state.SkipWithError("OpenSubdiv: the centre face is not a regular surface");
        delete refiner;
        return;
    }
    const auto p = net();
    std::vector<double> mesh(p.data(), p.data() + 48);
    std::vector<double> patch(static_cast<std::size_t>(surface.GetNumPatchPoints()) * 3);
    const Bfr::Surface<double>::PointDescriptor pd(3);
    surface.PreparePatchPoints(mesh.data(), pd, patch.data(), pd);
    const auto us = gridParameters();
    Eigen::Matrix<double, 3, Eigen::Dynamic> pos(3, kGrid * kGrid), nrm(3, kGrid * kGrid);
    for (auto _ : state) {
        for (int i = 0; i < kGrid; ++i)
            for (int j = 0; j < kGrid; ++j) {
                const double uv[2] = {us[i], us[j]};
                double P[3], du[3], dv[3];
                surface.Evaluate(uv, patch.data(), pd, P, du, dv);
                const Eigen::Vector3d n = Eigen::Vector3d(du[0], du[1], du[2]).cross(Eigen::Vector3d(dv[0], dv[1], dv[2]));
                pos.col(i * kGrid + j) = Eigen::Vector3d(P[0], P[1], P[2]);
                nrm.col(i * kGrid + j) = n.normalized();
            }
        benchmark::DoNotOptimize(pos.data());
        benchmark::DoNotOptimize(nrm.data());
    }
    finish(state);
    delete refiner;
}
BENCHMARK(BM_OpenSubdivBfr)->Unit(benchmark::kMillisecond);
#endif

void BM_TeapotAdaptive(benchmark::State& state)
{
    const freeform::PatchComplex teapot = freeform::readBpt(std::string(FREEFORM_SOURCE_DIR) + "/data/teapot.bpt");
    freeform::TessellationOptions o;
    o.tolerance = 1e-4;
    long triangles = 0, vertices = 0;
    for (auto _ : state) {
        const auto mesh = freeform::tessellate(teapot, o);
        triangles = mesh.faceCount();
        vertices = mesh.vertexCount();
        benchmark::DoNotOptimize(mesh.positions.data());
    }
    state.counters["triangles"] = static_cast<double>(triangles);
    state.counters["vertices"] = static_cast<double>(vertices);
}
BENCHMARK(BM_TeapotAdaptive)->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
