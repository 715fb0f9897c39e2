// The Utah teapot (32 bicubic patches, data/teapot.bpt) tessellated to a certified tolerance of
// 1e-2, 1e-3 and 1e-4: triangles, the largest deviation found by sampling every triangle (12 points
// per triangle: the triangle point at (u, v) against f(u, v), and against its foot point on the
// patch by Newton's method, sampleTriangleDeviation), and the time of one tessellation (one thread).
// Rows: the library's local refinement (the default), its older one grid per patch
// (TessellationRefinement::PatchGrid), and, when Open CASCADE's meshing module is installed
// (scripts/install-bench-peers.sh), BRepMesh_IncrementalMesh on the same 32 patches (one face per
// Geom_BezierSurface, linear deflection = the tolerance, angular deflection 0.5, not in parallel),
// sampled the same way through its (u, v) nodes. BM_LocalFreshPages: BM_Local at geometric 1e-3
// with the heap trimmed before every call (see there). Figures: docs/performance.md.
//
//   build/bin/bench_tessellate --benchmark_repetitions=5 --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <freeform/io/bpt.h>
#include <freeform/tessellate/tessellate.h>

#include <cmath>
#include <string>
#include <vector>

#include <malloc.h>
#include <unistd.h>

#ifdef FREEFORM_BENCH_OCCT_MESH
// Debian's OCCT 7.6.3 lacks NCollection_AliasedArray.hxx, which Poly_Triangulation.hxx (and so
// BRep_Builder.hxx, BRep_Tool.hxx) include: the triangulations are read back from BRepTools::Write's
// text instead (section "Triangulations": nodes, (u, v) nodes, triangles), outside the timing.
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <Geom_BezierSurface.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopoDS_Face.hxx>

#include <cstdio>
#include <fstream>
#include <sstream>
#endif

namespace {

const freeform::PatchComplex& teapot()
{
    static const freeform::PatchComplex t = freeform::readBpt(std::string(FREEFORM_SOURCE_DIR) + "/data/teapot.bpt");
    return t;
}

double toleranceOf(const benchmark::State& state) { return std::pow(10.0, -static_cast<double>(state.range(0))); }

void library(benchmark::State& state, freeform::TessellationRefinement refinement)
{
    freeform::TessellationOptions o;
    o.tolerance = toleranceOf(state);
    o.refinement = refinement;
    o.measure = static_cast<freeform::TessellationMeasure>(state.range(1));
    long triangles = 0;
    for (auto _ : state) {
        const auto mesh = freeform::tessellate(teapot(), o);
        triangles = mesh.faceCount();
        benchmark::DoNotOptimize(mesh.positions.data());
    }
    // Deviations measured once, outside the timing.
    o.sampleDeviation = true;
    freeform::TessellationReport report;
    freeform::tessellate(teapot(), o, &report);
    state.counters["triangles"] = static_cast<double>(triangles);
    state.counters["bound"] = report.errorBound;
    state.counters["leaves"] = static_cast<double>(report.leaves);
    state.counters["dev_param"] = report.measuredParametric;
    state.counters["dev_geom"] = report.measuredGeometric;
}

void BM_Local(benchmark::State& state) { library(state, freeform::TessellationRefinement::Local); }
BENCHMARK(BM_Local)->ArgsProduct({{2, 3, 4}, {0, 1}})->Unit(benchmark::kMillisecond);

// BM_Local with the heap given back to the kernel before every call (malloc_trim, outside the
// timing), so that each call faults in every page it writes, as the first call of a process does:
// in a loop, whether glibc keeps the last call's freed mesh for the next one depends on how the
// heap's top happens to be laid out, which moved the page faults per call between 270 and 656
// for the same work (docs/performance.md). Caches stay warm; this bounds the memory side only.
void BM_LocalFreshPages(benchmark::State& state)
{
    freeform::TessellationOptions o;
    o.tolerance = toleranceOf(state);
    o.measure = static_cast<freeform::TessellationMeasure>(state.range(1));
    long triangles = 0;
    for (auto _ : state) {
        state.PauseTiming();
        ::malloc_trim(0);
        state.ResumeTiming();
        const auto mesh = freeform::tessellate(teapot(), o);
        triangles = mesh.faceCount();
        benchmark::DoNotOptimize(mesh.positions.data());
    }
    state.counters["triangles"] = static_cast<double>(triangles);
}
BENCHMARK(BM_LocalFreshPages)->Args({3, 1})->Unit(benchmark::kMillisecond);

void BM_PatchGrid(benchmark::State& state) { library(state, freeform::TessellationRefinement::PatchGrid); }
BENCHMARK(BM_PatchGrid)->ArgsProduct({{2, 3, 4}, {0}})->Unit(benchmark::kMillisecond);

#ifdef FREEFORM_BENCH_OCCT_MESH
std::vector<TopoDS_Face> occtTeapot()
{
    std::vector<TopoDS_Face> faces;
    for (const freeform::Patch& p : teapot().patches) {
        TColgp_Array2OfPnt poles(1, p.degreeU() + 1, 1, p.degreeV() + 1);
        for (int i = 0; i <= p.degreeU(); ++i)
            for (int j = 0; j <= p.degreeV(); ++j) {
                const Eigen::Vector3d q = p.controlPoint(i, j);
                poles.SetValue(i + 1, j + 1, gp_Pnt(q.x(), q.y(), q.z()));
            }
        Handle(Geom_BezierSurface) surface = new Geom_BezierSurface(poles);
        faces.push_back(BRepBuilderAPI_MakeFace(surface, 1e-9).Face());
    }
    return faces;
}

void BM_OcctBRepMesh(benchmark::State& state)
{
    const double tolerance = toleranceOf(state);
    std::vector<TopoDS_Face> faces = occtTeapot();
    for (auto _ : state) {
        state.PauseTiming();
        for (TopoDS_Face& f : faces) BRepTools::Clean(f);
        state.ResumeTiming();
        for (const TopoDS_Face& f : faces) {
            BRepMesh_IncrementalMesh mesher(f, tolerance, Standard_False, 0.5, Standard_False);
            benchmark::DoNotOptimize(mesher.IsDone());
        }
    }
    long triangles = 0;
    freeform::TriangleDeviation worst;
    const std::string path = "/tmp/bench_tessellate_" + std::to_string(::getpid()) + ".brep";
    for (std::size_t face = 0; face < faces.size(); ++face) {
        BRepTools::Write(faces[face], path.c_str());
        std::ifstream in(path);
        std::string word;
        while (in >> word && word != "Triangulations") {}
        int count = 0;
        in >> count;
        for (int t = 0; t < count; ++t) {
            int nodes = 0, tris = 0, hasUv = 0;
            double deflection = 0;
            in >> nodes >> tris >> hasUv;
            in >> word; // normals flag (7.6) or deflection
            std::string line;
            std::getline(in, line);
            std::istringstream rest(line);
            if (rest >> deflection) {}
            std::vector<Eigen::Vector3d> xyz(static_cast<std::size_t>(nodes));
            std::vector<Eigen::Vector2d> uv(static_cast<std::size_t>(nodes));
            for (auto& q : xyz) in >> q.x() >> q.y() >> q.z();
            if (hasUv)
                for (auto& w : uv) in >> w.x() >> w.y();
            triangles += tris;
            for (int k = 0; k < tris; ++k) {
                int a[3];
                in >> a[0] >> a[1] >> a[2];
                if (!hasUv) continue;
                std::array<Eigen::Vector2d, 3> tuv;
                std::array<Eigen::Vector3d, 3> txyz;
                for (int c = 0; c < 3; ++c) {
                    tuv[c] = uv[static_cast<std::size_t>(a[c] - 1)];
                    txyz[c] = xyz[static_cast<std::size_t>(a[c] - 1)];
                }
                const auto d = freeform::sampleTriangleDeviation(teapot().patches[face], tuv, txyz);
                worst.parametric = std::max(worst.parametric, d.parametric);
                worst.geometric = std::max(worst.geometric, d.geometric);
            }
        }
    }
    std::remove(path.c_str());
    state.counters["triangles"] = static_cast<double>(triangles);
    state.counters["dev_param"] = worst.parametric;
    state.counters["dev_geom"] = worst.geometric;
}
BENCHMARK(BM_OcctBRepMesh)->Arg(2)->Arg(3)->Arg(4)->Unit(benchmark::kMillisecond);
#endif

} // namespace

BENCHMARK_MAIN();
