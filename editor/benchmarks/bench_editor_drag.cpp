// The CPU side of one frame of a lattice drag in the editor (issue 7: at most 20 ms for a
// 1,000,000-vertex mesh on the 2-core test machine). The scene holds an imported triangle mesh of
// V vertices (a 1000 x 1000 sphere grid written as OBJ once, read through Scene::importFile as the
// editor reads it) and a cubic lattice fitted to it by the tools (fitLattice, key L). Each
// iteration is what a frame does while a lattice point is dragged:
//   - Scene::setControlPoint on the lattice inside a merged undo step (the drag),
//   - Tools::update: the tools' per-frame follow-up and overlays,
//   - Scene::updateGeometry: the rebuild of what changed (the lattice's net), then the derived
//     items: the FFD link notices the new control points and deforms positions, normals and det J
//     of every vertex through the binding made at fit time (no lattice coordinates are computed
//     again), the det J colour scalars and the bounds. While the drag goes on (the scene merges
//     its changes) the link may update the mesh linearly from the drag's last full evaluation
//     (FfdSession::deform, live): every frame, the grab included, is one pass over the vertices
//     from the last full evaluation (the base).
// BM_DragFrame's CPU column is the benchmark thread's; BM_DragFrameProcessCpu is the same loop with
// the CPU time of every thread of the process (the full evaluation runs on all cores).
// BM_DragRelease times the frame of the release (the exact evaluation the drag owes starts on a
// worker thread, as in the editor's window), BM_DragReleaseApply the frame that takes its result,
// BM_DragReleaseBackground the whole background evaluation (not a frame), BM_DragReleaseSynchronous
// the release evaluated on the frame (background work off), BM_DragGrab the first frame of a
// drag (the grab), all with the CPU time of every thread.
// Spline and patch drags (issue 12): a handle of a cubic spline of 4, 16 and 64 segments dragged, its joints
// all C2, all mirrored, or mixed; each frame the spline tool enforces every joint's mode.
// BM_DragFrameDrawn adds SceneDrawer::draw (what the drawer hands the renderer, the recording
// renderer's copy standing for the driver's); the driver's own work is not included. Nothing here
// is a test: docs/performance.md has the figures.
//
//   build/bin/bench_editor_drag --benchmark_repetitions=5 --benchmark_report_aggregates_only=true

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <thread>

#include "interaction/selection.h"
#include "render/recording_renderer.h"
#include "scene/overlay.h"
#include "scene/scene.h"
#include "scene/scene_drawer.h"
#include "tools/tools.h"

namespace {

using namespace freeform;
using namespace freeform::editor;

constexpr int kGrid = 1000; // kGrid x kGrid vertices

/// A closed-ish sphere grid (latitude x longitude, poles not merged) as an OBJ file, written once.
std::string meshFile()
{
    static const std::string path = (std::filesystem::temp_directory_path() / "freeform_bench_drag_1m.obj").string();
    static bool written = false;
    if (written) return path;
    std::ofstream out(path);
    char line[96];
    for (int i = 0; i < kGrid; ++i) {
        const double theta = std::numbers::pi * (i + 0.5) / kGrid;
        for (int j = 0; j < kGrid; ++j) {
            const double phi = 2 * std::numbers::pi * j / kGrid;
            std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                          std::cos(theta));
            out << line;
        }
    }
    for (int i = 0; i + 1 < kGrid; ++i)
        for (int j = 0; j < kGrid; ++j) {
            const int a = i * kGrid + j + 1, b = i * kGrid + (j + 1) % kGrid + 1, c = a + kGrid, d = b + kGrid;
            std::snprintf(line, sizeof line, "f %d %d %d\nf %d %d %d\n", a, b, d, a, d, c);
            out << line;
        }
    written = true;
    return path;
}

struct DragScene {
    Scene scene;
    Selection selection;
    Tools tools;
    Overlay overlay;
    int lattice = -1, mesh = -1;

    DragScene()
    {
        scene.importFile(meshFile());
        ToolContext context{scene, selection};
        tools.lattice().degree[0] = tools.lattice().degree[1] = tools.lattice().degree[2] = 3;
        if (!tools.lattice().fitLattice(context, scene.itemCount() - 1)) throw Error("fit: " + tools.message());
        lattice = selection.item;
        mesh = findItem(scene, std::filesystem::path(meshFile()).stem().string());
        tools.update(context, overlay);
        scene.updateGeometry(); // binds the mesh once, as the first frame after the fit does
    }
    /// A frame's input: point k moved to its next place on the drag's path from `rest`, the
    /// tools' update and overlays (not the geometry update).
    void moveAlongPath(int k, const Eigen::Vector3d& rest, int& frame)
    {
        const double offset = 0.1 * std::sin(0.05 * ++frame);
        scene.setControlPoint(lattice, k, rest + Eigen::Vector3d(offset, 0.5 * offset, 0));
        overlay = Overlay{};
        ToolContext context{scene, selection};
        tools.update(context, overlay);
    }
    /// A first drag of another point (42), released: its full evaluation becomes the base of the
    /// drags measured after it (a deformed lattice rather than the rest one).
    void deformOnce()
    {
        const int first = 42;
        scene.beginMerge();
        scene.setControlPoint(lattice, first, scene.controlPoints(lattice).col(first) + Eigen::Vector3d(0.05, -0.04, 0.03));
        scene.updateGeometry();
        scene.endMerge();
    }
};

void BM_DragFrame(benchmark::State& state)
{
    static DragScene d; // made once: reading the mesh and binding it are not what is measured
    const int k = 21; // an inner control point of the 4 x 4 x 4 lattice
    const Eigen::Vector3d rest = d.scene.controlPoints(d.lattice).col(k);
    d.scene.beginMerge();
    int frame = 0;
    for (auto _ : state) {
        d.moveAlongPath(k, rest, frame);
        d.scene.updateGeometry();
        benchmark::DoNotOptimize(d.scene.item(d.mesh).geometry.surface->positions.data());
    }
    d.scene.endMerge();
    state.counters["vertices"] = double(kGrid) * kGrid;
    const auto& links = d.scene.ffdLinks();
    if (!links.empty()) state.counters["deform_ms_last"] = links.begin()->second.deformMs;
}
BENCHMARK(BM_DragFrame)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
void BM_DragFrameProcessCpu(benchmark::State& state) { BM_DragFrame(state); }
BENCHMARK(BM_DragFrameProcessCpu)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime()->MinTime(2.0);

/// BM_DragFrame from a deformed lattice: the frames of a drag whose base is a full evaluation
/// (a first drag of another point, released, made before the loop) rather than the identity of
/// the rest lattice: each frame reads p0, A and det A of that evaluation (the usual case once a
/// lattice has been edited). Process CPU of every thread.
void BM_DragFrameFromDeformed(benchmark::State& state)
{
    static DragScene& d = *new DragScene;
    const int k = 21;
    d.deformOnce();
    d.scene.updateGeometry(); // the full evaluation: the base of the drag below
    const Eigen::Vector3d rest = d.scene.controlPoints(d.lattice).col(k);
    d.scene.beginMerge();
    int frame = 0;
    for (auto _ : state) {
        d.moveAlongPath(k, rest, frame);
        d.scene.updateGeometry();
        benchmark::DoNotOptimize(d.scene.item(d.mesh).geometry.surface->positions.data());
    }
    d.scene.endMerge();
    const auto& links = d.scene.ffdLinks();
    if (!links.empty()) state.counters["approximate"] = links.begin()->second.approximate;
}
BENCHMARK(BM_DragFrameFromDeformed)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime()->MinTime(2.0);

/// BM_DragFrameFromDeformed with the drawer: each frame also goes through SceneDrawer::draw, which
/// hands the renderer the vertices it uploads (here the recording renderer, whose copy of them
/// stands for the driver's glBufferSubData copy; nothing is rasterised). This is the whole CPU
/// side of a frame of the drag but the driver's own work. Process CPU of every thread.
void BM_DragFrameDrawn(benchmark::State& state)
{
    static DragScene& d = *new DragScene;
    static RecordingRenderer renderer;
    static SceneDrawer drawer(renderer);
    const int k = 21;
    d.deformOnce();
    drawer.draw(d.scene, 1280, 800, d.lattice, &d.overlay); // the full evaluation, uploaded: the base of the drag below
    const Eigen::Vector3d rest = d.scene.controlPoints(d.lattice).col(k);
    d.scene.beginMerge();
    int frame = 0;
    for (auto _ : state) {
        d.moveAlongPath(k, rest, frame);
        drawer.draw(d.scene, 1280, 800, d.lattice, &d.overlay);
        benchmark::DoNotOptimize(renderer.counters());
    }
    d.scene.endMerge();
    const auto& links = d.scene.ffdLinks();
    if (!links.empty()) state.counters["approximate"] = links.begin()->second.approximate;
}
BENCHMARK(BM_DragFrameDrawn)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime()->MinTime(2.0);

/// A short drag (frames frames, not timed) of point k, then its release (endMerge): what the
/// release benchmarks below start from.
void shortDrag(DragScene& d, int k, const Eigen::Vector3d& rest, int& frame, int frames)
{
    d.scene.beginMerge();
    for (int f = 0; f < frames; ++f) {
        const double offset = 0.1 * std::sin(0.05 * ++frame);
        d.scene.setControlPoint(d.lattice, k, rest + Eigen::Vector3d(offset, 0.5 * offset, 0));
        d.scene.updateGeometry();
    }
    d.scene.endMerge();
}

bool backgroundDone(const DragScene& d)
{
    const auto& links = d.scene.ffdLinks();
    return links.empty() || !links.begin()->second.pending || links.begin()->second.session->backgroundDone();
}

/// The frame of the release of a drag (with the process's CPU time): as in the editor's window
/// (background work on), it keeps the drag's last linear frame and starts the exact evaluation
/// on a worker thread. Each iteration is a short drag (three frames, not timed), its release
/// frame (timed), then, not timed, the wait for the worker and the frame that takes its result.
/// (The worker's CPU while the release frame runs is counted in it.)
void BM_DragRelease(benchmark::State& state)
{
    static DragScene& d = *new DragScene; // one more scene: the other benchmarks' is local to them
    d.scene.setBackgroundTessellation(true);
    ToolContext context{d.scene, d.selection};
    const int k = 21;
    const Eigen::Vector3d rest = d.scene.controlPoints(d.lattice).col(k);
    int frame = 0;
    for (auto _ : state) {
        state.PauseTiming();
        shortDrag(d, k, rest, frame, 3);
        state.ResumeTiming();
        d.overlay = Overlay{};
        d.tools.update(context, d.overlay);
        d.scene.updateGeometry();
        benchmark::DoNotOptimize(d.scene.item(d.mesh).geometry.surface->positions.data());
        state.PauseTiming();
        d.scene.finishDeformation();
        state.ResumeTiming();
    }
}
BENCHMARK(BM_DragRelease)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime()->Iterations(20);

/// The frame that shows the exact result (with the process's CPU time): the worker has finished
/// (waited for, not timed); the frame swaps its positions, normals and det J into the mesh.
void BM_DragReleaseApply(benchmark::State& state)
{
    static DragScene& d = *new DragScene;
    d.scene.setBackgroundTessellation(true);
    ToolContext context{d.scene, d.selection};
    const int k = 21;
    const Eigen::Vector3d rest = d.scene.controlPoints(d.lattice).col(k);
    int frame = 0;
    for (auto _ : state) {
        state.PauseTiming();
        shortDrag(d, k, rest, frame, 3);
        d.scene.updateGeometry(); // the release frame
        while (!backgroundDone(d)) std::this_thread::sleep_for(std::chrono::microseconds(100));
        state.ResumeTiming();
        d.overlay = Overlay{};
        d.tools.update(context, d.overlay);
        d.scene.updateGeometry();
        benchmark::DoNotOptimize(d.scene.item(d.mesh).geometry.surface->positions.data());
        state.PauseTiming();
        if (!d.scene.ffdLinks().empty() && d.scene.ffdLinks().begin()->second.pending) state.SkipWithError("result not taken");
        state.ResumeTiming();
    }
}
BENCHMARK(BM_DragReleaseApply)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime()->Iterations(20);

/// The background exact evaluation, not on a frame: from the release frame to the result taken
/// (Scene::finishDeformation waits for it), with the process's CPU time: the worker's evaluation
/// (on one thread fewer than the machine has) plus the release and apply frames measured above.
void BM_DragReleaseBackground(benchmark::State& state)
{
    static DragScene& d = *new DragScene;
    d.scene.setBackgroundTessellation(true);
    const int k = 21;
    const Eigen::Vector3d rest = d.scene.controlPoints(d.lattice).col(k);
    int frame = 0;
    for (auto _ : state) {
        state.PauseTiming();
        shortDrag(d, k, rest, frame, 3);
        state.ResumeTiming();
        d.scene.updateGeometry();
        d.scene.finishDeformation();
        benchmark::DoNotOptimize(d.scene.item(d.mesh).geometry.surface->positions.data());
    }
}
BENCHMARK(BM_DragReleaseBackground)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime()->Iterations(20);

/// The release evaluated on the frame itself (background work off, as headless runs and tests
/// without it do): the full evaluation, what the release frame cost before the worker.
void BM_DragReleaseSynchronous(benchmark::State& state)
{
    static DragScene& d = *new DragScene;
    ToolContext context{d.scene, d.selection};
    const int k = 21;
    const Eigen::Vector3d rest = d.scene.controlPoints(d.lattice).col(k);
    int frame = 0;
    for (auto _ : state) {
        state.PauseTiming();
        shortDrag(d, k, rest, frame, 3);
        state.ResumeTiming();
        d.overlay = Overlay{};
        d.tools.update(context, d.overlay);
        d.scene.updateGeometry();
        benchmark::DoNotOptimize(d.scene.item(d.mesh).geometry.surface->positions.data());
    }
}
BENCHMARK(BM_DragReleaseSynchronous)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime()->Iterations(20);

/// The grab: the first frame of a drag (with the process's CPU time), the one that moves a point
/// away from the last full evaluation (made at fit, at every release and at undo). Each iteration
/// is a short drag and its release, the exact result taken (not timed), then the first frame of
/// a new drag: one pass over the vertices straight from that evaluation.
void BM_DragGrab(benchmark::State& state)
{
    static DragScene& d = *new DragScene;
    d.scene.setBackgroundTessellation(true);
    const int k = 21;
    const Eigen::Vector3d rest = d.scene.controlPoints(d.lattice).col(k);
    int frame = 0;
    double deformMs = 0; // the deformation's share (FfdLink::deformMs, wall time)
    for (auto _ : state) {
        state.PauseTiming();
        shortDrag(d, k, rest, frame, 2); // a short drag (two frames) and its release
        d.scene.updateGeometry();
        d.scene.finishDeformation();
        d.scene.beginMerge();
        state.ResumeTiming();
        d.moveAlongPath(k, rest, frame);
        d.scene.updateGeometry();
        benchmark::DoNotOptimize(d.scene.item(d.mesh).geometry.surface->positions.data());
        state.PauseTiming();
        if (!d.scene.ffdLinks().empty()) deformMs += d.scene.ffdLinks().begin()->second.deformMs;
        d.scene.endMerge();
        state.ResumeTiming();
    }
    const auto& links = d.scene.ffdLinks();
    state.counters["deform_ms"] = deformMs / double(state.iterations());
    if (!links.empty()) state.counters["approximate"] = links.begin()->second.session && links.begin()->second.session->approximate();
}
BENCHMARK(BM_DragGrab)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime()->Iterations(20);

/// A cubic spline of `segments` segments (a zigzag in the xy plane) whose inner joints are all in
/// `mode` ("c2", "mirrored", "aligned") or, for "mixed", C2, aligned and mirrored in turn, as a
/// document file: the spline tool keeps every joint in its mode while a handle is dragged
/// (issue 12). Each iteration is one frame of the drag: the handle moved, Tools::update (the
/// joint modes enforced on the whole spline), Scene::updateGeometry.
std::string splineFile(int segments, const std::string& mode)
{
    const std::string path =
        (std::filesystem::temp_directory_path() / ("freeform_bench_spline_" + mode + "_" + std::to_string(segments) + ".json")).string();
    std::ofstream out(path);
    out << R"({"format": "freeform", "version": 1, "objects": [{"name": "s", "type": "bezier_spline", "degree": 3, "points": [)";
    for (int k = 0; k <= 3 * segments; ++k) {
        const double x = k / 3.0, y = (k % 6 < 3 ? 1.0 : -1.0) * (k % 3 == 0 ? 0.5 : 1.0) + 0.1 * std::sin(k);
        out << (k ? ", " : "") << "[" << x << ", " << y << ", " << 0.05 * std::cos(2.0 * k) << "]";
    }
    out << R"(], "editor": {"joints": ["free")";
    const char* cycle[] = {"c2", "aligned", "mirrored"};
    for (int j = 1; j < segments; ++j) out << ", \"" << (mode == "mixed" ? cycle[j % 3] : mode.c_str()) << "\"";
    out << R"(, "free"]}}]})";
    return path;
}

void BM_SplineHandleDrag(benchmark::State& state, const std::string& mode)
{
    const int segments = static_cast<int>(state.range(0));
    Scene scene = Scene::load(splineFile(segments, mode));
    Selection selection;
    Tools tools;
    Overlay overlay;
    ToolContext context{scene, selection};
    selection.selectItem(0);
    tools.update(context, overlay);
    const int k = 3 * (segments / 2) + 1; // the handle after the middle joint
    selection.setPoints({k});
    const Eigen::Vector3d rest = scene.controlPoints(0).col(k);
    scene.beginMerge();
    int frame = 0;
    for (auto _ : state) {
        const double offset = 0.05 * std::sin(0.05 * ++frame);
        scene.setControlPoint(0, k, rest + Eigen::Vector3d(offset, 0.5 * offset, 0));
        overlay = Overlay{};
        tools.update(context, overlay);
        scene.updateGeometry();
        benchmark::DoNotOptimize(scene.controlPoints(0).data());
    }
    scene.endMerge();
}
BENCHMARK_CAPTURE(BM_SplineHandleDrag, c2, std::string("c2"))->Arg(4)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_SplineHandleDrag, mirrored, std::string("mirrored"))->Arg(4)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_SplineHandleDrag, mixed, std::string("mixed"))->Arg(4)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime();

/// A document of `n` x `n` bicubic patches (a wavy sheet), each an object, written once.
std::string patchFile(int n)
{
    const std::string path = (std::filesystem::temp_directory_path() / ("freeform_bench_patches_" + std::to_string(n) + ".json")).string();
    std::ofstream out(path);
    out << R"({"format": "freeform", "version": 1, "objects": [)";
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            out << (a || b ? ", " : "") << R"({"name": "p)" << a << "_" << b << R"(", "type": "bezier_surface", "degree": [3, 3], "points": [)";
            for (int i = 0; i <= 3; ++i) {
                out << (i ? ", [" : "[");
                for (int j = 0; j <= 3; ++j) {
                    const double x = a + i / 3.0, y = b + j / 3.0;
                    out << (j ? ", " : "") << "[" << x << ", " << y << ", " << 0.3 * std::sin(x) * std::cos(y) << "]";
                }
                out << "]";
            }
            out << "]}";
        }
    out << "]}";
    return path;
}

/// One frame of dragging an inner control point of one patch of an 8 x 8 sheet (the patch is
/// tessellated again at the display tolerance; the others are not touched).
void BM_PatchDrag(benchmark::State& state)
{
    Scene scene = Scene::load(patchFile(8));
    Selection selection;
    Tools tools;
    Overlay overlay;
    ToolContext context{scene, selection};
    scene.updateGeometry();
    const int item = 27, k = 5;
    selection.selectItem(item);
    selection.setPoints({k});
    tools.update(context, overlay);
    const Eigen::Vector3d rest = scene.controlPoints(item).col(k);
    scene.beginMerge();
    int frame = 0;
    for (auto _ : state) {
        const double offset = 0.2 * std::sin(0.05 * ++frame);
        scene.setControlPoint(item, k, rest + Eigen::Vector3d(0, 0, offset));
        overlay = Overlay{};
        tools.update(context, overlay);
        scene.updateGeometry();
        benchmark::DoNotOptimize(scene.item(item).geometry.surface->positions.data());
    }
    scene.endMerge();
}
BENCHMARK(BM_PatchDrag)->Unit(benchmark::kMillisecond)->UseRealTime();

} // namespace

BENCHMARK_MAIN();
