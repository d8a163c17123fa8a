// Cost of generating one hemisphere direction: Owen-scrambled Sobol point and concentric map, against the
// shifted precomputed set the ray-traced estimator uses.
#include "obscura/sampling.h"

#include <benchmark/benchmark.h>

using namespace obscura;

static void BM_Sobol2D(benchmark::State& state) {
    std::uint32_t i = 0;
    for (auto _ : state) {
        Vec2 p = sobol2D(i & 255u, 12345u + (i >> 8));
        ++i;
        benchmark::DoNotOptimize(p);
    }
}
BENCHMARK(BM_Sobol2D);

static void BM_CosineHemisphere(benchmark::State& state) {
    float u = 0.1f;
    for (auto _ : state) {
        u += 0.0001f;
        if (u > 1.0f) u -= 1.0f;
        Vec3 d = cosineHemisphere({u, 1.0f - u});
        benchmark::DoNotOptimize(d);
    }
}
BENCHMARK(BM_CosineHemisphere);

static void BM_Direction(benchmark::State& state) {
    std::uint32_t i = 0;
    for (auto _ : state) {
        Vec3 d = cosineHemisphere(sobol2D(i & 255u, 777u + (i >> 8)));
        ++i;
        benchmark::DoNotOptimize(d);
    }
}
BENCHMARK(BM_Direction);

static void BM_ShiftedSetDirection(benchmark::State& state) {
    CosineHemisphereSet set(256);
    CosineHemisphereSet::Shift shift = CosineHemisphereSet::shift(99);
    int i = 0;
    for (auto _ : state) {
        Vec3 d = set.direction(i, shift);
        benchmark::DoNotOptimize(d);
        i = (i + 1) & 255;
    }
}
BENCHMARK(BM_ShiftedSetDirection);
