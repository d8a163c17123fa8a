// Separable cross-bilateral blur as one fused pass: McGuire et al. 2011, "The Alchemy Screen-Space Ambient
// Obscurance Algorithm", Fig. 6 (two 1-D passes, horizontal then vertical). Contract in
// include/obscura/bilateral.h.
//
// Cost: the image is cut into tiles. A tile copies its rows of depth, normal (deinterleaved) and AO, with an
// apron of r pixels, into per-thread planes, one row at a time; runs the horizontal pass on each row as it
// arrives (the tile's rows and r more above and below); and runs the vertical pass on a row as soon as the
// r rows below it are filtered. So the G-buffer is read once per frame, the intermediate image never
// leaves the cache (2r + 1 rows of a 256-pixel strip), and nothing is copied whole. 8 centres are filtered
// at a time with their sums kept in registers across all 2r + 1 taps.
#include "bilateral_separable.h"

#include "obscura/parallel.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <vector>

namespace obscura::ssao::detail {

namespace {

// GCC/Clang vector extensions: 8 floats. The default (SSE2) build lowers each operation to two 4-wide
// ones with the same IEEE results, so both builds give the same bits.
typedef float V8f __attribute__((vector_size(32)));
typedef int V8i __attribute__((vector_size(32)));
constexpr int kLanes = 8;

// These small functions are always inlined, so the ABI of passing 32-byte vectors without AVX never applies.
#pragma GCC diagnostic ignored "-Wpsabi"
#define OBSCURA_INLINE inline __attribute__((always_inline))

OBSCURA_INLINE V8f load(const float* p) {
    V8f v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
OBSCURA_INLINE void store(float* p, const V8f& v) { std::memcpy(p, &v, sizeof v); }
OBSCURA_INLINE V8f splat(float x) { return V8f{} + x; }

// From here to filterSegment, products feeding a sum may be fused (see OBSCURA_TARGET_CLONES).
#pragma GCC push_options
#pragma GCC optimize("fp-contract=fast")

// 2^e for e <= 0: 2^floor(e) times a degree-3 minimax polynomial of 2^f, f in [0, 1) (relative error
// 7.5e-5, measured on 1e5 points: far below what a blur weight shows, and two operations per tap fewer than
// degree 4, which reached 2.6e-6). e is clamped at -125 (NaN taken as -125), so a tap with an infinite or
// undefined depth difference weighs 2^-125, a normal float that no sum of real weights can show.
OBSCURA_INLINE V8f exp2Negative(const V8f& x) {
    const V8f e = x > splat(-125.0f) ? x : splat(-125.0f);
    const V8f t = e + splat(127.0f);  // positive, so truncation is floor
    const V8i i = __builtin_convertvector(t, V8i);
    const V8f f = t - __builtin_convertvector(i, V8f);
    const V8f p = ((splat(0.0780245667f) * f + splat(0.226067199f)) * f + splat(0.695833467f)) * f + splat(0.999925233f);
    return p * std::bit_cast<V8f>(i << 23);  // 2^(i - 127) has the biased exponent i
}

// The AVX2 clone also has FMA (x86-64-v3), and products feeding a sum are fused there: a third fewer
// operations per tap. Each clone is deterministic, so results do not depend on the thread count; they
// differ between CPUs with and without FMA in the last bits.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define OBSCURA_TARGET_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define OBSCURA_TARGET_CLONES
#endif

// The planes of one 1-D pass over a row segment: centre x reads c*[x]; its tap t reads t*[x + t stride].
struct Segment {
    const float *dC, *nxC, *nyC, *nzC, *aoC;
    const float *dT, *nxT, *nyT, *nzT, *aoT;
    std::ptrdiff_t stride;
    int tFirst, tLast;  // taps inside the image
};

// The running state of 8 centres.
struct Centres {
    V8f d, c, nx, ny, nz, sum, wsum;
};

template <bool UseNormal>
OBSCURA_INLINE void beginCentres(Centres& q, const Segment& s, std::ptrdiff_t x, float depthScale) {
    q.d = load(s.dC + x);
    q.c = splat(depthScale) / (q.d * q.d);  // 0 on sky: its output is its input anyway
    if constexpr (UseNormal) {
        q.nx = load(s.nxC + x);
        q.ny = load(s.nyC + x);
        q.nz = load(s.nzC + x);
    }
    q.sum = q.wsum = splat(0.0f);
}

// Tap at offset o (from the first centre) of the 8 centres, with log2 of its spatial weight.
template <bool UseNormal>
OBSCURA_INLINE void addTap(Centres& q, const Segment& s, std::ptrdiff_t o, const V8f& logSpatial) {
    const V8f dd = load(s.dT + o) - q.d;
    V8f w = exp2Negative(logSpatial - dd * dd * q.c);
    if constexpr (UseNormal) {
        const V8f dot = q.nx * load(s.nxT + o) + q.ny * load(s.nyT + o) + q.nz * load(s.nzT + o);
        w *= dot > splat(0.0f) ? dot : splat(0.0f);
    }
    q.sum += w * load(s.aoT + o);
    q.wsum += w;
}

// A centre on sky or with no weight (impossible for a surface: its own tap counts) keeps its input.
OBSCURA_INLINE void finishCentres(const Centres& q, const Segment& s, std::ptrdiff_t x, float* out) {
    // A depth below about 1e-19 m makes c = depthScale / d^2 infinite, and every tap's weight 0 * inf: the GPU's
    // weights are then NaN and it keeps the input, where exp2Negative's clamp gave 2^-125 weights here (which
    // flush to 0 with FTZ, so a constant 0.5 came out 0). Keep the input as the GPU does.
    const V8i keep = (q.d < splat(1e30f)) & (q.wsum > splat(0.0f)) & (q.c <= splat(3.40282347e38f));
    store(out + x, keep ? q.sum / q.wsum : load(s.aoC + x));
}

// Whether every tap of the 16 centres at x reads AO 1 (the centres themselves included). Then each output is
// 1 bit for bit, whatever the weights: a surface centre's sum adds w * 1 exactly as its weight sum adds w, and
// a sky centre keeps its input, 1. Unoccluded surfaces (open floors and walls) and sky come out of the
// estimator exactly 1, so this skips most of the work there.
OBSCURA_INLINE bool allOne(const Segment& s, std::ptrdiff_t x) {
    V8i all = V8i{} - 1;
    for (int t = s.tFirst; t <= s.tLast; ++t) {
        const float* v = s.aoT + x + std::ptrdiff_t(t) * s.stride;
        all &= (load(v) == splat(1.0f)) & (load(v + kLanes) == splat(1.0f));
    }
    for (int i = 0; i < kLanes; ++i)
        if (all[i] == 0) return false;
    return true;
}

// n (a multiple of 16) outputs of one pass. logSpatial[t] = log2 of the spatial weight of tap t in [-r, r];
// depthScale = log2(e) / (2 depthSigma^2), so a tap weighs 2^(logSpatial - dd^2 depthScale / d^2)
// = spatial exp(-dd^2 / (2 (depthSigma d)^2)), times max(0, N . Ni) with the normal weight on. Two groups
// of 8 centres go through the taps side by side: one tap's weight is a long chain of dependent
// operations, and the second group fills the pipeline while the first waits.
template <bool UseNormal>
OBSCURA_TARGET_CLONES void filterSegment(int n, const Segment& s, const float* logSpatial, float depthScale,
                                         float* __restrict out) {
    V8f spatial[2 * 32 + 1];
    for (int t = s.tFirst; t <= s.tLast; ++t) spatial[t - s.tFirst] = splat(logSpatial[t]);
    for (std::ptrdiff_t x = 0; x < n; x += 2 * kLanes) {
        if (allOne(s, x)) {
            store(out + x, splat(1.0f));
            store(out + x + kLanes, splat(1.0f));
            continue;
        }
        Centres a, b;
        beginCentres<UseNormal>(a, s, x, depthScale);
        beginCentres<UseNormal>(b, s, x + kLanes, depthScale);
        for (int t = s.tFirst; t <= s.tLast; ++t) {
            const std::ptrdiff_t o = x + std::ptrdiff_t(t) * s.stride;
            addTap<UseNormal>(a, s, o, spatial[t - s.tFirst]);
            addTap<UseNormal>(b, s, o + kLanes, spatial[t - s.tFirst]);
        }
        finishCentres(a, s, x, out);
        finishCentres(b, s, x + kLanes, out);
    }
}
#pragma GCC pop_options

// Per-thread planes of one tile, kept between tiles and calls so that no pass allocates.
struct TilePlanes {
    std::vector<float> d, nx, ny, nz, ao, h, row;
    void reserve(std::size_t n, std::size_t rowLength, bool normals) {
        for (std::vector<float>* v : {&d, &ao, &h, &nx, &ny, &nz})
            if (v->size() < n && (normals || (v != &nx && v != &ny && v != &nz))) v->resize(n);
        if (row.size() < rowLength) row.resize(rowLength);
    }
};

// Tiles of 256 x 256 pixels: the horizontal pass redoes r rows above and below each tile (5% at r = 6),
// and 2r + 1 rows of a strip's six planes (87 KB at r = 6) stay in L2 for the vertical pass.
constexpr int kTileW = 256, kTileH = 256;

struct Job {
    const Image& ao;
    const GBuffer& g;
    const BilateralSettings& s;
    bool horizontal, vertical;
    bool useNormal;
    std::vector<float> logSpatial;  // 2r + 1 entries, tap t at [t + r]
    float depthScale;
    Image& out;
};

void filterRow(const Job& job, int n, const Segment& seg, float* out) {
    const float* logSpatial = job.logSpatial.data() + job.s.radius;
    if (job.useNormal)
        filterSegment<true>(n, seg, logSpatial, job.depthScale, out);
    else
        filterSegment<false>(n, seg, logSpatial, job.depthScale, out);
}

void filterTile(const Job& job, TilePlanes& p, int x0, int x1, int y0, int y1) {
    const int w = job.g.width(), h = job.g.height(), r = job.s.radius;
    const int n = x1 - x0, nv = (n + 2 * kLanes - 1) / (2 * kLanes) * (2 * kLanes);
    // Local column lc is image column x0 - r + lc; centres sit at lc = r .. r + nv, taps reach r either side.
    const int stride = nv + 2 * r;
    const int ya = job.vertical ? std::max(0, y0 - r) : y0, yb = job.vertical ? std::min(h, y1 + r) : y1;
    const bool useNormal = job.useNormal;
    p.reserve(std::size_t(yb - ya) * std::size_t(stride), std::size_t(nv), useNormal);
    const int inFirst = std::max(0, r - x0), inLast = std::min(stride, w - x0 + r);  // local columns in the image
    const float* depth = job.g.depth.pixels.data();
    const float* normal = job.g.normal.pixels.data();
    const float* ao = job.ao.pixels.data();
    auto fillRow = [&](int y) {
        const std::size_t l = std::size_t(y - ya) * std::size_t(stride);
        const std::ptrdiff_t src = std::ptrdiff_t(y) * w + x0 - r;  // image index of lc = 0
        // Outside the image: sky depth, zero normal and AO, so such taps weigh nothing (or 2^-125 without normals).
        auto pad = [&](int from, int to) {
            for (std::size_t i = l + std::size_t(from); i < l + std::size_t(to); ++i) {
                p.d[i] = INFINITY;
                p.ao[i] = 0.0f;
                if (useNormal) p.nx[i] = p.ny[i] = p.nz[i] = 0.0f;
            }
        };
        pad(0, inFirst);
        const std::size_t s0 = std::size_t(src + inFirst), n0 = std::size_t(inLast - inFirst), l0 = l + std::size_t(inFirst);
        std::copy(depth + s0, depth + s0 + n0, &p.d[l0]);
        std::copy(ao + s0, ao + s0 + n0, &p.ao[l0]);
        if (useNormal) {
            float* __restrict nx = &p.nx[l0];
            float* __restrict ny = &p.ny[l0];
            float* __restrict nz = &p.nz[l0];
            const float* __restrict nrm = normal + 3 * s0;
            for (std::size_t i = 0; i < n0; ++i) {
                nx[i] = nrm[3 * i];
                ny[i] = nrm[3 * i + 1];
                nz[i] = nrm[3 * i + 2];
            }
        }
        pad(inLast, stride);
    };
    auto rowSegment = [&](int y, const std::vector<float>& values) {
        const std::size_t l = std::size_t(y - ya) * std::size_t(stride) + std::size_t(r);
        Segment seg{};
        seg.dC = seg.dT = &p.d[l];
        if (useNormal) {  // the normal planes are not filled (nor sized) otherwise
            seg.nxC = seg.nxT = &p.nx[l];
            seg.nyC = seg.nyT = &p.ny[l];
            seg.nzC = seg.nzT = &p.nz[l];
        }
        seg.aoC = seg.aoT = &values[l];
        return seg;
    };
    auto emit = [&](const float* row, int y) {
        std::copy(row, row + n, &job.out.pixels[std::size_t(y) * std::size_t(w) + std::size_t(x0)]);
    };
    int nextY = y0;  // next row of the vertical pass
    for (int y = ya; y < yb; ++y) {
        fillRow(y);
        const std::size_t l = std::size_t(y - ya) * std::size_t(stride) + std::size_t(r);
        if (job.horizontal) {
            Segment seg = rowSegment(y, p.ao);
            seg.stride = 1;
            seg.tFirst = -r;
            seg.tLast = r;
            filterRow(job, nv, seg, &p.h[l]);
        } else {
            std::copy(&p.ao[l], &p.ao[l] + nv, &p.h[l]);
        }
        if (!job.vertical) {
            emit(&p.h[l], y);
            continue;
        }
        // Row nextY needs the filtered rows up to nextY + r (or the last row).
        for (; nextY < y1 && std::min(nextY + r, h - 1) <= y; ++nextY) {
            Segment seg = rowSegment(nextY, p.h);
            seg.stride = stride;
            seg.tFirst = std::max(-r, -nextY);
            seg.tLast = std::min(r, h - 1 - nextY);
            filterRow(job, nv, seg, p.row.data());
            emit(p.row.data(), nextY);
        }
    }
}

} // namespace

SeparableWeights separableWeights(const BilateralSettings& s) {
    SeparableWeights weights;
    const std::vector<float> kernel = gaussianHalfKernel(s.radius);
    weights.logSpatial.resize(2 * std::size_t(s.radius) + 1);
    for (int t = -s.radius; t <= s.radius; ++t)
        weights.logSpatial[std::size_t(t + s.radius)] = std::log2(kernel[std::size_t(std::abs(t))]);
    weights.depthScale = 1.44269504f / (2.0f * s.depthSigma * s.depthSigma);
    return weights;
}

Image separableBlur(const Image& ao, const GBuffer& g, const BilateralSettings& s, bool horizontal, bool vertical) {
    const int w = g.width(), h = g.height();
    Image out(w, h, 1);
    SeparableWeights weights = separableWeights(s);
    const Job job{ao, g, s, horizontal, vertical, s.usesNormals(), std::move(weights.logSpatial), weights.depthScale, out};
    const int tilesX = (w + kTileW - 1) / kTileW, tilesY = (h + kTileH - 1) / kTileH;
    parallelFor(std::size_t(tilesX) * std::size_t(tilesY), [&](std::size_t t0, std::size_t t1) {
        static thread_local TilePlanes planes;
        for (std::size_t t = t0; t < t1; ++t) {
            const int x0 = int(t % std::size_t(tilesX)) * kTileW, y0 = int(t / std::size_t(tilesX)) * kTileH;
            filterTile(job, planes, x0, std::min(w, x0 + kTileW), y0, std::min(h, y0 + kTileH));
        }
    });
    return out;
}

} // namespace obscura::ssao::detail
