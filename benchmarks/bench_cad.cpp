// CAD parts (docs/cad.md): the sample parts Debian ships (occt-misc) read, and tessellated to a
// certified distance (freeform/brep/part_mesh.h) beside Open CASCADE's BRepMesh_IncrementalMesh on
// the same shape at the same linear deflection (angular deflection 0.5, not in parallel), in the
// same run. Counters: triangles; watertight (1 when every mesh edge of the closed shells is in two
// triangles; for BRepMesh, its per-face triangulations joined at equal node positions) and
// open_edges (mesh edges in one triangle or in more than two); bound (the library's certified
// bound; BRepMesh gives none).
//
// Deformation (freeform/brep/part_deform.h): an affine lattice beside Open CASCADE's
// BRepBuilderAPI_GTransform with the same map (the peer: it converts the faces to B-splines and
// transforms their poles); a general quadratic lattice (every point moved by up to 3% of the
// part's size, fixed seed), exact and with faces over degree 25 reduced (no peer: Open CASCADE has
// no FFD). Writing (freeform/cad/cad_file.h) beside STEPControl_Writer on the original shape.
// Figures: docs/performance.md.
//
//   build/bin/bench_cad --benchmark_repetitions=3 --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <freeform/brep/part_deform.h>
#include <freeform/brep/part_mesh.h>
#include <freeform/cad/cad_file.h>

#include <BRepBuilderAPI_GTransform.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <IGESControl_Reader.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <gp_GTrsf.hxx>
#include <TopoDS_Shape.hxx>

#include <array>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

struct Sample {
    const char* file;
    double deflection; // in the part's millimetres
};
// The deflections: about 1e-3 of each part's size (hammer.iges is 40 m across).
constexpr Sample kSamples[] = {
    {"step/screw.step", 0.1},
    {"step/linkrods.step", 0.01},
    {"iges/bearing.iges", 0.1},
    {"iges/hammer.iges", 50},
};

std::string pathOf(int i) { return std::string("/usr/share/opencascade/data/") + kSamples[i].file; }

const freeform::Part& part(int i)
{
    static std::map<int, freeform::Part> parts;
    auto it = parts.find(i);
    if (it == parts.end()) it = parts.emplace(i, freeform::readCadFile(pathOf(i))).first;
    return it->second;
}

TopoDS_Shape occtShape(int i)
{
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_Printer));
    const std::string path = pathOf(i);
    if (path.ends_with(".step")) {
        STEPControl_Reader r;
        r.ReadFile(path.c_str());
        r.TransferRoots();
        return r.OneShape();
    }
    IGESControl_Reader r;
    r.ReadFile(path.c_str());
    r.TransferRoots();
    return r.OneShape();
}

void BM_Read(benchmark::State& state)
{
    const int i = static_cast<int>(state.range(0));
    state.SetLabel(kSamples[i].file);
    for (auto _ : state) benchmark::DoNotOptimize(freeform::readCadFile(pathOf(i)).faces.size());
}

void BM_Tessellate(benchmark::State& state)
{
    const int i = static_cast<int>(state.range(0));
    state.SetLabel(kSamples[i].file);
    freeform::PartMeshOptions options;
    options.tolerance = kSamples[i].deflection;
    const freeform::Part& p = part(i); // read outside the timing
    freeform::PartMesh mesh;
    for (auto _ : state) mesh = freeform::tessellatePart(p, options);
    state.counters["triangles"] = mesh.mesh.faceCount();
    state.counters["watertight"] = mesh.report.watertight ? 1 : 0;
    state.counters["open_edges"] = mesh.report.openMeshEdges;
    state.counters["bound"] = mesh.report.errorBound;
}

/// BRepMesh's triangles, and its mesh edges not in exactly two triangles once the faces'
/// triangulations are joined at equal node positions (read back from BRepTools::Write: Debian's
/// Open CASCADE 7.6.3 lacks a header Poly_Triangulation.hxx includes).
std::array<long, 2> brepMeshCounts(const TopoDS_Shape& shape)
{
    const std::string path = "/tmp/bench_cad_" + std::to_string(::getpid()) + ".brep";
    BRepTools::Write(shape, path.c_str());
    std::ifstream in(path);
    std::string word;
    while (in >> word && word != "Triangulations") {}
    int count = 0;
    in >> count;
    long triangles = 0;
    std::map<std::array<double, 3>, int> ids;
    std::map<std::pair<int, int>, int> edges;
    for (int t = 0; t < count; ++t) {
        int nodes = 0, tris = 0, hasUv = 0;
        in >> nodes >> tris >> hasUv >> word;
        std::string line;
        std::getline(in, line);
        std::vector<int> id(static_cast<std::size_t>(nodes));
        for (int& v : id) {
            std::array<double, 3> p{};
            in >> p[0] >> p[1] >> p[2];
            v = ids.emplace(p, static_cast<int>(ids.size())).first->second;
        }
        if (hasUv)
            for (int k = 0; k < nodes; ++k) in >> word >> word;
        triangles += tris;
        for (int k = 0; k < tris; ++k) {
            int a[3];
            in >> a[0] >> a[1] >> a[2];
            for (int c = 0; c < 3; ++c) {
                const int p = id[static_cast<std::size_t>(a[c] - 1)], q = id[static_cast<std::size_t>(a[(c + 1) % 3] - 1)];
                if (p != q) ++edges[{std::min(p, q), std::max(p, q)}];
            }
        }
    }
    std::remove(path.c_str());
    long open = 0;
    for (const auto& [e, n] : edges) open += n != 2 ? 1 : 0;
    return {triangles, open};
}

void BM_BRepMesh(benchmark::State& state)
{
    const int i = static_cast<int>(state.range(0));
    state.SetLabel(kSamples[i].file);
    TopoDS_Shape shape = occtShape(i);
    for (auto _ : state) {
        state.PauseTiming();
        BRepTools::Clean(shape);
        state.ResumeTiming();
        BRepMesh_IncrementalMesh mesher(shape, kSamples[i].deflection, Standard_False, 0.5, Standard_False);
        benchmark::DoNotOptimize(mesher.IsDone());
    }
    const auto [triangles, open] = brepMeshCounts(shape);
    state.counters["triangles"] = static_cast<double>(triangles);
    state.counters["watertight"] = open == 0 ? 1 : 0;
    state.counters["open_edges"] = static_cast<double>(open);
}


/// The map of the affine benchmarks: a shear with unequal scales.
Eigen::Matrix3d affineLinear()
{
    Eigen::Matrix3d A;
    A << 1.2, 0.3, 0.0, -0.1, 0.8, 0.25, 0.05, 0.0, 1.4;
    return A;
}
const Eigen::Vector3d kAffineOffset(0.5, -2, 1);

freeform::Lattice latticeAround(const freeform::Part& p, int degree)
{
    const freeform::Box<double, 3> box = p.bounds();
    freeform::Lattice::Points corners(3, 2);
    corners.col(0) = box.min();
    corners.col(1) = box.max();
    return freeform::Lattice::fit(corners, {degree, degree, degree}, 0.1);
}

void BM_DeformAffine(benchmark::State& state)
{
    const int i = static_cast<int>(state.range(0));
    state.SetLabel(kSamples[i].file);
    const freeform::Part& p = part(i);
    freeform::Lattice lattice = latticeAround(p, 1);
    for (int a = 0; a <= 1; ++a)
        for (int b = 0; b <= 1; ++b)
            for (int c = 0; c <= 1; ++c)
                lattice.setControlPoint(a, b, c, affineLinear() * lattice.restPoint(a, b, c) + kAffineOffset);
    const freeform::RationalLattice rational(lattice);
    freeform::DeformedPart moved;
    for (auto _ : state) moved = freeform::deformPart(p, rational);
    state.counters["max_degree"] = moved.report.maxDegree;
}

void BM_GTransform(benchmark::State& state)
{
    const int i = static_cast<int>(state.range(0));
    state.SetLabel(kSamples[i].file);
    const TopoDS_Shape shape = occtShape(i);
    const Eigen::Matrix3d A = affineLinear();
    gp_GTrsf g;
    g.SetVectorialPart(gp_Mat(A(0, 0), A(0, 1), A(0, 2), A(1, 0), A(1, 1), A(1, 2), A(2, 0), A(2, 1), A(2, 2)));
    g.SetTranslationPart(gp_XYZ(kAffineOffset.x(), kAffineOffset.y(), kAffineOffset.z()));
    for (auto _ : state) {
        BRepBuilderAPI_GTransform transform(shape, g, Standard_True);
        benchmark::DoNotOptimize(transform.Shape());
    }
}

/// A lattice of `degree` around the part, every point moved by up to 3% of its size (the same
/// random moves for every run).
freeform::Lattice movedAround(const freeform::Part& p, int degree)
{
    freeform::Lattice lattice = latticeAround(p, degree);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    const double size = p.bounds().diagonal().norm();
    for (int a = 0; a <= degree; ++a)
        for (int b = 0; b <= degree; ++b)
            for (int c = 0; c <= degree; ++c)
                lattice.setControlPoint(a, b, c, lattice.controlPoint(a, b, c) + 0.03 * size * Eigen::Vector3d(u(rng), u(rng), u(rng)));
    return lattice;
}

void deformWith(benchmark::State& state, const freeform::Part& p, const freeform::Lattice& lattice, int maxDegree)
{
    freeform::PartDeformOptions options;
    options.maxDegree = maxDegree;
    const freeform::RationalLattice rational(lattice);
    freeform::DeformedPart moved;
    for (auto _ : state) moved = freeform::deformPart(p, rational, options);
    state.counters["max_degree"] = moved.report.maxDegree;
    state.counters["approximated"] = static_cast<double>(moved.report.approximatedFaces.size());
    state.counters["error"] = moved.report.maxApproximationError;
}

/// A moved quadratic lattice; range(1): the degree cap (0: exact).
void BM_Deform(benchmark::State& state)
{
    const int i = static_cast<int>(state.range(0));
    state.SetLabel(kSamples[i].file);
    deformWith(state, part(i), movedAround(part(i), 2), static_cast<int>(state.range(1)));
}

/// A moved cubic lattice, capped at Open CASCADE's 25: on linkrods.step the compositions reach
/// degree (54, 90), over the library's 67, and are reduced from patches of that degree.
void BM_DeformCubic(benchmark::State& state)
{
    const int i = static_cast<int>(state.range(0));
    state.SetLabel(kSamples[i].file);
    deformWith(state, part(i), movedAround(part(i), 3), 25);
}

void BM_WriteStep(benchmark::State& state)
{
    const int i = static_cast<int>(state.range(0));
    state.SetLabel(kSamples[i].file);
    const freeform::Part& p = part(i);
    const std::string path = "/tmp/bench_cad_" + std::to_string(getpid()) + ".step";
    for (auto _ : state) benchmark::DoNotOptimize(freeform::writeCadFile(p, path).valid);
    std::remove(path.c_str());
}

void BM_OcctWriteStep(benchmark::State& state)
{
    const int i = static_cast<int>(state.range(0));
    state.SetLabel(kSamples[i].file);
    const TopoDS_Shape shape = occtShape(i);
    const std::string path = "/tmp/bench_cad_occt_" + std::to_string(getpid()) + ".step";
    for (auto _ : state) {
        STEPControl_Writer writer;
        writer.Transfer(shape, STEPControl_AsIs);
        benchmark::DoNotOptimize(writer.Write(path.c_str()));
    }
    std::remove(path.c_str());
}

constexpr int kParts = static_cast<int>(std::size(kSamples));
BENCHMARK(BM_Read)->DenseRange(0, kParts - 1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Tessellate)->DenseRange(0, kParts - 1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BRepMesh)->DenseRange(0, kParts - 1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DeformAffine)->DenseRange(0, kParts - 1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GTransform)->DenseRange(0, kParts - 1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Deform)->ArgsProduct({benchmark::CreateDenseRange(0, kParts - 1, 1), {0, 25}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DeformCubic)->DenseRange(0, 1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WriteStep)->DenseRange(0, kParts - 1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OcctWriteStep)->DenseRange(0, kParts - 1)->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
