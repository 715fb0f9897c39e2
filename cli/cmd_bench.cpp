// freeform bench: measure the deformation on a generated point set.

#include <algorithm>
#include <chrono>
#include <memory>
#include <random>

#include "command.h"
#include "freeform/core/parallel.h"
#include "freeform/volume/deform.h"

namespace freeform::cli {

std::array<int, 3> parseDegrees(const std::string& text, const std::string& option); // cmd_lattice.cpp

namespace {

template <typename Scalar>
double medianMs(const Lattice& lattice, const Eigen::Matrix<double, 3, Eigen::Dynamic>& points, bool normals,
                int threads, int runs)
{
    const FfdBinding<Scalar> binding(lattice, points.data(), static_cast<std::size_t>(points.cols()));
    const std::size_t n = static_cast<std::size_t>(points.cols());
    std::vector<Scalar> out(3 * n), nin(3 * n, Scalar(0)), nout;
    for (std::size_t i = 0; i < n; ++i) nin[3 * i + 2] = Scalar(1);
    FfdOutputs<Scalar> o;
    o.positions = out.data();
    if (normals) {
        nout.resize(3 * n);
        o.normalsIn = nin.data();
        o.normalsOut = nout.data();
    }
    DeformOptions options;
    options.threads = threads;
    binding.deform(lattice, o, options); // warm-up: first touch of the output pages
    std::vector<double> ms;
    for (int r = 0; r < runs; ++r) {
        const auto start = std::chrono::steady_clock::now();
        binding.deform(lattice, o, options);
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(ms.begin(), ms.end());
    return ms.size() % 2 ? ms[ms.size() / 2] : 0.5 * (ms[ms.size() / 2 - 1] + ms[ms.size() / 2]);
}

struct BenchOptions {
    long vertices = 1000000;
    std::string degree = "3,3,3";
    int threads = 0;
    int runs = 21;
    bool useFloat = false, normals = false;
};

Json bench(const BenchOptions& o)
{
    const long vertices = o.vertices;
    if (vertices < 1) throw UsageError("option --vertices: must be at least 1");
    const std::array<int, 3> degree = parseDegrees(o.degree, "--degree");
    const int threads = o.threads;
    if (threads < 0) throw UsageError("option --threads: must not be negative");
    const int runs = o.runs;
    if (runs < 1) throw UsageError("option --runs: must be at least 1");
    const bool useFloat = o.useFloat, normals = o.normals;

    // Uniform points in [-1, 1]^3, the identity lattice around them, every control point moved.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    Eigen::Matrix<double, 3, Eigen::Dynamic> points(3, vertices);
    for (long i = 0; i < vertices; ++i) points.col(i) = Eigen::Vector3d(u(rng), u(rng), u(rng));
    Lattice lattice = Lattice::identity(degree, Eigen::Vector3d(-1.1, -1.1, -1.1), 2.2 * Eigen::Matrix3d::Identity());
    std::uniform_real_distribution<double> wobble(-0.15, 0.15);
    Eigen::Matrix<double, 3, Eigen::Dynamic> cp = lattice.controlPoints();
    for (Eigen::Index i = 0; i < cp.cols(); ++i) cp.col(i) += Eigen::Vector3d(wobble(rng), wobble(rng), wobble(rng));
    lattice.setControlPoints(cp);

    const double ms = useFloat ? medianMs<float>(lattice, points, normals, threads, runs)
                               : medianMs<double>(lattice, points, normals, threads, runs);
    Json out;
    out["vertices"] = vertices;
    out["degree"] = Json::array({degree[0], degree[1], degree[2]});
    out["threads"] = resolveThreadCount(threads);
    out["median_ms"] = ms;
    out["vertices_per_second"] = ms > 0 ? double(vertices) / (ms / 1000.0) : 0.0;
    out["scalar"] = useFloat ? "float" : "double";
    out["normals"] = normals;
    out["runs"] = runs;
    return out;
}

} // namespace

Action defineBench(CLI::App& app)
{
    auto o = std::make_shared<BenchOptions>();
    app.footer("Deforms N generated vertices (uniform in a cube) through a lattice of degrees\n"
               "(L, M, N) with every control point moved, R times, and prints the median time of\n"
               "one deformation (lattice coordinates are bound once, as in the editor).\n"
               "\n"
               "Prints {\"vertices\", \"degree\", \"threads\", \"median_ms\", \"vertices_per_second\",\n"
               "\"scalar\", \"normals\", \"runs\"}.");
    addNumber(app, "--vertices", o->vertices, "vertex count (at least 1)")->type_name("N")->capture_default_str();
    app.add_option("--degree", o->degree, "lattice degrees")->type_name("L,M,N")->capture_default_str();
    addNumber(app, "--threads", o->threads, "worker threads (0: all cores)")->type_name("T")->capture_default_str();
    addFlag(app, "--float", o->useFloat, "the single-precision path (default double)");
    addFlag(app, "--normals", o->normals, "also transform per-vertex normals (cof(J) n)");
    addNumber(app, "--runs", o->runs, "timed runs after one warm-up (at least 1)")->type_name("R")->capture_default_str();
    return [o] { return bench(*o); };
}

} // namespace freeform::cli
