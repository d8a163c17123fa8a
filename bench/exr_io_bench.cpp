// Writing and reading a 3-channel float EXR (ZIP, as writeExr stores every AOV), on one thread and on all of
// them: OpenEXR's own pool compresses and decompresses the chunks, sized by ThreadLimit like parallelFor.
// Arguments: image width (16:9), threads (0 = all hardware threads).
#include "obscura/image_io.h"
#include "obscura/parallel.h"

#include <benchmark/benchmark.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

using namespace obscura;

namespace {

// Smooth with fine detail, like lighting or normals: ZIP finds some redundancy but not runs of zeros.
Image aovLike(int width) {
    Image image(width, width * 9 / 16, 3);
    image.channelNames = {"R", "G", "B"};
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c)
                image.at(x, y, c) = 0.5f + 0.4f * std::sin(0.013f * float(x) + 0.7f * float(c)) * std::cos(0.021f * float(y)) +
                                    1e-3f * float((x * 7 + y * 13 + c) % 17);
    return image;
}

std::string benchPath() {
    return (std::filesystem::temp_directory_path() / ("obscura_exr_bench_" + std::to_string(getpid()) + ".exr")).string();
}

void BM_WriteExr(benchmark::State& state) {
    const Image image = aovLike(int(state.range(0)));
    const ThreadLimit limit(int(state.range(1)));
    const std::string path = benchPath();
    for (auto _ : state) writeExr(path, image);
    std::filesystem::remove(path);
    state.SetItemsProcessed(state.iterations() * std::int64_t(image.pixelCount()));
    state.counters["threads"] = allowedThreads();
}

void BM_ReadExr(benchmark::State& state) {
    const Image image = aovLike(int(state.range(0)));
    const std::string path = benchPath();
    writeExr(path, image);
    const ThreadLimit limit(int(state.range(1)));
    for (auto _ : state) {
        Image back = readExr(path);
        benchmark::DoNotOptimize(back.pixels.data());
    }
    std::filesystem::remove(path);
    state.SetItemsProcessed(state.iterations() * std::int64_t(image.pixelCount()));
    state.counters["threads"] = allowedThreads();
}

} // namespace

BENCHMARK(BM_WriteExr)->ArgsProduct({{1920, 3840}, {1, 0}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ReadExr)->ArgsProduct({{1920, 3840}, {1, 0}})->Unit(benchmark::kMillisecond)->UseRealTime();
