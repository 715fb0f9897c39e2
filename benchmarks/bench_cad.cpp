// CAD parts (docs/cad.md): the sample parts Debian ships (occt-misc) read, and tessellated to a
// certified distance (freeform/brep/part_mesh.h) beside Open CASCADE's BRepMesh_IncrementalMesh on
// the same shape at the same linear deflection (angular deflection 0.5, not in parallel), in the
// same run. Counters: triangles; watertight (1 when every mesh edge of the closed shells is in two
// triangles; for BRepMesh, its per-face triangulations joined at equal node positions) and
// open_edges (mesh edges in one triangle or in more than two); bound (the library's certified
// bound; BRepMesh gives none). Figures: docs/performance.md.
//
//   build/bin/bench_cad --benchmark_repetitions=3 --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <freeform/brep/part_mesh.h>
#include <freeform/cad/cad_file.h>

#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <IGESControl_Reader.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>
#include <STEPControl_Reader.hxx>
#include <TopoDS_Shape.hxx>

#include <array>
#include <cstdio>
#include <fstream>
#include <map>
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

constexpr int kParts = static_cast<int>(std::size(kSamples));
BENCHMARK(BM_Read)->DenseRange(0, kParts - 1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Tessellate)->DenseRange(0, kParts - 1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BRepMesh)->DenseRange(0, kParts - 1)->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
