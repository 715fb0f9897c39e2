// Reading glTF files with many accessors (issue 16, "a valid glTF with 8,000 accessors takes 20 s
// because each lookup copies the whole accessor array"). One mesh of N triangle primitives, each
// with its own POSITION accessor over one shared 36-byte buffer view, read by MeshFile::read.
// The time per accessor must stay flat as N grows (linear, not quadratic, in the accessor count):
// the benchmark reports the fitted complexity. Speed is measured here, never asserted in a test.

#include <benchmark/benchmark.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "freeform/io/mesh_io.h"

namespace {

namespace fs = std::filesystem;

std::string writeManyAccessors(int count)
{
    const fs::path dir = fs::temp_directory_path() / "freeform_bench_mesh_io";
    fs::create_directories(dir);
    {
        std::ofstream bin(dir / "tri.bin", std::ios::binary);
        for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) bin.write(reinterpret_cast<const char*>(&v), sizeof v);
    }
    std::string primitives, accessors;
    for (int k = 0; k < count; ++k) {
        if (k) {
            primitives += ',';
            accessors += ',';
        }
        primitives += "{\"attributes\":{\"POSITION\":" + std::to_string(k) + "}}";
        accessors += "{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
                     "\"min\":[0,0,0],\"max\":[1,1,0]}";
    }
    const std::string path = (dir / ("many" + std::to_string(count) + ".gltf")).string();
    std::ofstream(path) << "{\"asset\":{\"version\":\"2.0\"},\"meshes\":[{\"primitives\":[" << primitives
                        << "]}],\"buffers\":[{\"uri\":\"tri.bin\",\"byteLength\":36}],"
                        << "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],\"accessors\":[" << accessors << "]}";
    return path;
}

void BM_GltfManyAccessors(benchmark::State& state)
{
    const int count = static_cast<int>(state.range(0));
    const std::string path = writeManyAccessors(count);
    for (auto _ : state) {
        const freeform::MeshFile file = freeform::MeshFile::read(path);
        benchmark::DoNotOptimize(file.positions().data());
    }
    state.SetComplexityN(count);
    state.counters["accessors"] = count;
}
BENCHMARK(BM_GltfManyAccessors)->Arg(1000)->Arg(2000)->Arg(4000)->Arg(8000)->Complexity()->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
