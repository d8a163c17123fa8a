// Spatio-temporal GTAO: Jimenez et al. 2016, §4.1 (4x4 interleave with bilateral reconstruction, 6
// rotations with reprojection into an exponential accumulation buffer, half-resolution evaluation).
#include "obscura/gtao_temporal.h"

#include "obscura/bilateral.h"
#include "obscura/error.h"
#include "obscura/history_packing.h"
#include "obscura/reconstruct_window.h"
#include "obscura/parallel.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace obscura::ssao {

namespace {

bool finiteDepth(float d) { return d < 1e30f; }

std::string imageShape(const Image& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height) + "x" + std::to_string(image.channels);
}

Vec3 vec3At(const Image& image, int x, int y) { return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)}; }
void setVec3(Image& image, int x, int y, Vec3 v) {
    image.at(x, y, 0) = v.x;
    image.at(x, y, 1) = v.y;
    image.at(x, y, 2) = v.z;
}

void forRows(int height, const std::function<void(int)>& row) {
    parallelFor(std::size_t(height), [&](std::size_t begin, std::size_t end) {
        for (std::size_t y = begin; y < end; ++y) row(int(y));
    });
}

} // namespace

void GtaoTemporalSettings::validate() const {
    auto check = [](bool ok, const char* field, const char* range) {
        if (!ok) fail(std::string("gtao-") + field, std::string("must be in ") + range);
    };
    check(depthSigma > 0.0f && depthSigma <= 1.0f, "depth-sigma", "(0, 1]");
    check(rejectDepth > 0.0f && rejectDepth <= 1.0f, "reject-depth", "(0, 1]");
    check(rejectNormalCos >= -1.0f && rejectNormalCos <= 1.0f, "reject-normal-cos", "[-1, 1]");
    check(maxHistory >= 1 && maxHistory <= 1024, "max-history", "[1, 1024]");
    if (gridHistory && !halfResolution) fail("gtao-grid-history", "needs half resolution (the grid it keeps)");
    if (alternatingWindow && !temporal)
        fail("gtao-alternating-window", "needs the history (temporal), which averages its 4 windows");
    if (alternatingWindowSize != 4 && alternatingWindowSize != 2)
        fail("gtao-alternating-window-size", "must be 4 (4x4 windows) or 2 (2x2 windows)");
}

int reconstructWindowPhase(const GtaoTemporalSettings& settings, int frameIndex) {
    // Phases 0, 1, 3, 2 in turn: the window's x half (bit 0) then changes with frames 1 and 3 of each 4, not
    // with the frame's parity, which the 6 rotations share, so every rotation meets both halves of x and of y
    // over 12 frames; taken in the order 0..3, column -2 only ever saw the even rotations.
    if (!settings.alternatingWindow) return -1;
    const int phase = (frameIndex & 3) ^ ((frameIndex >> 1) & 1);
    return settings.alternatingWindowSize == 2 ? 4 + phase : phase;
}

void checkReconstructWindowPhase(int windowPhase) {
    if (windowPhase < -1 || windowPhase > 7)
        fail("reconstruct interleaved", "window phase must be -1 (5x5), 0..3 (4x4) or 4..7 (2x2), not " +
                                            std::to_string(windowPhase));
}

void checkReconstructInterleavedInputs(const Image& values, const Image& depth, const Image& normal,
                                       int windowPhase) {
    // The gather sums at most 3 channels, and reads depth and normal at every pixel of the values.
    if (values.channels != 1 && values.channels != 3)
        fail("reconstruct interleaved", "values must have 1 or 3 channels, not " + std::to_string(values.channels));
    if (depth.width != values.width || depth.height != values.height || depth.channels != 1 ||
        normal.width != values.width || normal.height != values.height || normal.channels != 3)
        fail("reconstruct interleaved", "depth (1 channel) and normal (3 channels) must match the " +
                                            std::to_string(values.width) + "x" + std::to_string(values.height) +
                                            " values, not " + imageShape(depth) + " and " + imageShape(normal));
    checkReconstructWindowPhase(windowPhase);
}

Image reconstructInterleaved(const Image& values, const Image& depth, const Image& normal, float depthSigma,
                             int windowPhase) {
    checkReconstructInterleavedInputs(values, depth, normal, windowPhase);
    Image out = values;
    const int w = values.width, h = values.height, channels = values.channels;
    const int side = reconstructWindowSide(windowPhase);
    const int firstX = reconstructWindowFirst(windowPhase, 0), lastX = firstX + side - 1;
    const int firstY = reconstructWindowFirst(windowPhase, 1), lastY = firstY + side - 1;
    forRows(h, [&](int y) {
        for (int x = 0; x < w; ++x) {
            const float d = depth.at(x, y);
            if (!finiteDepth(d)) continue;
            const Vec3 n = vec3At(normal, x, y);
            const float sigma = depthSigma * d;
            const float invTwoSigma2 = 1.0f / (2.0f * sigma * sigma);
            float sum[3] = {0, 0, 0}, weightSum = 0.0f;
            for (int dy = firstY; dy <= lastY; ++dy) {
                const int yy = y + dy;
                if (yy < 0 || yy >= h) continue;
                for (int dx = firstX; dx <= lastX; ++dx) {
                    const int xx = x + dx;
                    if (xx < 0 || xx >= w) continue;
                    const float di = depth.at(xx, yy);
                    if (!finiteDepth(di)) continue;
                    const float spatial = reconstructWindowWeight(windowPhase, dx, dy);
                    const float wt = tapWeight(spatial, d, n, di, vec3At(normal, xx, yy), invTwoSigma2, true);
                    for (int c = 0; c < channels; ++c) sum[c] += wt * values.at(xx, yy, c);
                    weightSum += wt;
                }
            }
            if (!(weightSum > 0.0f)) continue;
            if (channels == 3) {
                const Vec3 v = normalize(Vec3{sum[0], sum[1], sum[2]});
                if (dot(v, v) > 0.0f) setVec3(out, x, y, v);
            } else {
                for (int c = 0; c < channels; ++c) out.at(x, y, c) = sum[c] / weightSum;
            }
        }
    });
    return out;
}

void checkUpsampleDepthAwareInputs(const Image& low, const Image& lowDepth, const GBuffer& full) {
    const int w = full.width(), h = full.height(), channels = low.channels;
    // The filter sums at most 3 channels; it reads the full depth (and, for vectors, the normal) at every pixel of
    // the camera's size, and the low-resolution depth and values at the grid pixels (x / 2, y / 2) and next to them.
    if (channels != 1 && channels != 3)
        fail("upsample depth-aware", "values must have 1 or 3 channels, not " + std::to_string(channels));
    if (low.width != (w + 1) / 2 || low.height != (h + 1) / 2)
        fail("upsample depth-aware", "values are " + imageShape(low) + " but the grid of a " + std::to_string(w) +
                                         "x" + std::to_string(h) + " G-buffer is " + std::to_string((w + 1) / 2) +
                                         "x" + std::to_string((h + 1) / 2));
    if (lowDepth.width != low.width || lowDepth.height != low.height || lowDepth.channels != 1)
        fail("upsample depth-aware", "low-resolution depth (1 channel) must match the " + std::to_string(low.width) +
                                         "x" + std::to_string(low.height) + " values, not " + imageShape(lowDepth));
    full.validateDepthNormalShape("upsample depth-aware");
}

Image upsampleDepthAware(const Image& low, const Image& lowDepth, const GBuffer& full, float depthSigma) {
    checkUpsampleDepthAwareInputs(low, lowDepth, full);
    const int w = full.width(), h = full.height(), channels = low.channels;
    Image out(w, h, channels, channels == 1 ? 1.0f : 0.0f);
    forRows(h, [&](int y) {
        for (int x = 0; x < w; ++x) {
            const float d = full.depth.at(x, y);
            if (!finiteDepth(d)) continue;
            const float gx = 0.5f * float(x), gy = 0.5f * float(y);
            const int x0 = std::min(int(gx), low.width - 1), y0 = std::min(int(gy), low.height - 1);
            const int x1 = std::min(x0 + 1, low.width - 1), y1 = std::min(y0 + 1, low.height - 1);
            const float fx = gx - float(x0), fy = gy - float(y0);
            const int tx[4] = {x0, x1, x0, x1}, ty[4] = {y0, y0, y1, y1};
            const float bilinear[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
            const float sigma = depthSigma * d;
            const float invTwoSigma2 = 1.0f / (2.0f * sigma * sigma);
            float sum[3] = {0, 0, 0}, weightSum = 0.0f, bestDiff = 1e30f;
            int best = -1;
            for (int t = 0; t < 4; ++t) {
                const float di = lowDepth.at(tx[t], ty[t]);
                if (!finiteDepth(di)) continue;
                if (std::fabs(di - d) < bestDiff) {
                    bestDiff = std::fabs(di - d);
                    best = t;
                }
                if (bilinear[t] <= 0.0f) continue;
                const float wt = tapWeight(bilinear[t], d, {}, di, {}, invTwoSigma2, false);
                for (int c = 0; c < channels; ++c) sum[c] += wt * low.at(tx[t], ty[t], c);
                weightSum += wt;
            }
            // No surface among the taps: a feature thinner than the grid's spacing, which the grid never saw, against
            // the sky. It gets what the full-resolution kernel gives such a lone pixel, an open surface's values:
            // visibility 1 (the image's fill) and its own normal as the bent normal, where (0, 0, 0) would read as
            // no direction at all (GTSO's beta from it is pi/2 whatever the view: S = 0.5 for 1).
            if (best < 0) {
                if (channels == 3) setVec3(out, x, y, normalize(full.viewNormal(x, y)));
                continue;
            }
            // No tap on this surface (a thin feature between the samples): take the closest in depth.
            if (!(weightSum > 1e-4f)) {
                for (int c = 0; c < channels; ++c) out.at(x, y, c) = low.at(tx[best], ty[best], c);
                continue;
            }
            for (int c = 0; c < channels; ++c) out.at(x, y, c) = sum[c] / weightSum;
            if (channels == 3) setVec3(out, x, y, normalize(vec3At(out, x, y)));
        }
    });
    return out;
}

GtaoTemporal::GtaoTemporal(const GtaoSettings& settings, const GtaoTemporalSettings& temporal)
    : settings_(settings), temporal_(temporal) {
    settings_.validate();
    temporal_.validate();
}

const GtaoResult& GtaoTemporal::frame(const GBuffer& g) {
    const int w = g.width(), h = g.height();
    g.validateDepthNormalShape("gtao temporal");
    g.validatePixels("gtao temporal");  // computeGtao's check of the depths and normals
    if (g.depth.pixelCount() > 0) g.camera.validate();  // as computeGtao: the constants' projection comes from it
    if (frame_ > 0 && (w != previousCamera_.width || h != previousCamera_.height))
        fail("gtao temporal", "frame size changed from " + std::to_string(previousCamera_.width) + "x" +
                                  std::to_string(previousCamera_.height) + " to " + std::to_string(w) + "x" +
                                  std::to_string(h));

    // 1. One interleaved evaluation per grid pixel (the full image, or every other pixel in x and y).
    const GtaoConstants constants = gtaoConstants(settings_, g.camera, frame_, true);
    const int step = temporal_.halfResolution ? 2 : 1;
    const int gw = (w + step - 1) / step, gh = (h + step - 1) / step;
    Image rawVisibility(gw, gh, 1, 1.0f), rawBent(gw, gh, 3, 0.0f), gridDepth(gw, gh, 1), gridNormal(gw, gh, 3);
    const GtaoDepthMips mips = buildGtaoDepthMips(g.depth, constants.mipLevels);
    forRows(gh, [&](int y) {
        for (int x = 0; x < gw; ++x) {
            const int fx = x * step, fy = y * step;
            GtaoPixel p = gtaoPixel(constants, g, &mips, fx, fy, interleaveIndex(x, y));
            rawVisibility.at(x, y) = p.visibility;
            setVec3(rawBent, x, y, p.bentNormal);
            gridDepth.at(x, y) = g.depth.at(fx, fy);
            setVec3(gridNormal, x, y, g.viewNormal(fx, fy));
        }
    });

    // 2. Spatial gather of the 16 pattern directions; 3. back to full resolution, unless the history is the
    // grid's (then after step 4).
    const bool gridHistory = step == 2 && temporal_.gridHistory;
    const int phase = reconstructWindowPhase(temporal_, frame_);
    Image visibility = reconstructInterleaved(rawVisibility, gridDepth, gridNormal, temporal_.depthSigma, phase);
    Image bent = reconstructInterleaved(rawBent, gridDepth, gridNormal, temporal_.depthSigma, phase);
    if (step == 2 && !gridHistory) {
        visibility = upsampleDepthAware(visibility, gridDepth, g, temporal_.depthSigma);
        bent = upsampleDepthAware(bent, gridDepth, g, temporal_.depthSigma);
    }

    // 4. Reprojection and exponential accumulation, in world space for the bent normals, over the history's
    // lattice: every pixel, or with the grid's history every grid pixel (x, y), which stands at pixel
    // (hs x, hs y) and whose neighbours in the previous frame are hs pixels apart.
    const int hs = gridHistory ? 2 : 1;
    const int lw = gridHistory ? gw : w, lh = gridHistory ? gh : h;
    const Mat4 worldFromView = g.camera.worldFromView();
    const Mat4 viewFromWorld = g.camera.viewFromWorld();
    const Mat4 previousViewFromWorld = previousCamera_.viewFromWorld();
    const bool useHistory = temporal_.temporal && frame_ > 0;
    // The accumulated visibility the previous frame left on the lattice: its result, or the grid's.
    const Image& previousVisibility = gridHistory ? accumulated_ : result_.visibility;
    Image newBentWorld(lw, lh, 3, 0.0f), newLength(lw, lh, 1, 1.0f), normalWorld(lw, lh, 3, 0.0f);
    forRows(lh, [&](int y) {
        for (int x = 0; x < lw; ++x) {
            const int px = hs * x, py = hs * y;
            if (g.isSky(px, py)) continue;
            const Vec3 nWorld = normalize(transformVector(worldFromView, g.viewNormal(px, py)));
            setVec3(normalWorld, x, y, nWorld);
            Vec3 currentBent = normalize(transformVector(worldFromView, vec3At(bent, x, y)));
            setVec3(newBentWorld, x, y, currentBent);
            if (!useHistory) continue;
            const Vec3 world = transformPoint(worldFromView, g.viewPosition(px, py));
            float expectedDepth = 0.0f;
            const Vec2 prev = previousCamera_.pixelFromView(transformPoint(previousViewFromWorld, world), &expectedDepth);
            if (!(expectedDepth > 0.0f)) continue;
            // Lattice pixel x' has its centre at pixel centre hs x' + 0.5; scaled by 1 or 1/2, exactly.
            const float toLattice = hs == 1 ? 1.0f : 0.5f;
            const float gx = (prev.x - 0.5f) * toLattice, gy = (prev.y - 0.5f) * toLattice;
            const int x0 = int(std::floor(gx)), y0 = int(std::floor(gy));
            const float fx = gx - float(x0), fy = gy - float(y0);
            float weightSum = 0.0f, historyVisibility = 0.0f, historyLength = 0.0f;
            Vec3 historyBent{};
            for (int t = 0; t < 4; ++t) {
                const int tx = x0 + (t & 1), ty = y0 + (t >> 1);
                const float bw = ((t & 1) ? fx : 1.0f - fx) * ((t >> 1) ? fy : 1.0f - fy);
                if (bw <= 0.0f || tx < 0 || ty < 0 || tx >= lw || ty >= lh) continue;
                const float pd = previousDepth_.at(tx, ty);
                // Disocclusion: the previous frame saw another surface there, or one facing elsewhere.
                if (!finiteDepth(pd) || std::fabs(pd - expectedDepth) > temporal_.rejectDepth * expectedDepth) continue;
                if (dot(vec3At(previousNormalWorld_, tx, ty), nWorld) < temporal_.rejectNormalCos) continue;
                weightSum += bw;
                historyVisibility += bw * previousVisibility.at(tx, ty);
                historyBent += vec3At(bentWorld_, tx, ty) * bw;
                historyLength += bw * historyLength_.at(tx, ty);
            }
            // Less than a quarter of the footprint confirmed: too little to trust.
            if (weightSum < 0.25f) continue;
            historyVisibility /= weightSum;
            historyLength /= weightSum;
            historyBent = historyBent / weightSum;
            const float alpha = 1.0f / std::min(historyLength + 1.0f, float(temporal_.maxHistory));
            visibility.at(x, y) = historyVisibility + (visibility.at(x, y) - historyVisibility) * alpha;
            Vec3 blended = normalize(historyBent + (currentBent - historyBent) * alpha);
            if (dot(blended, blended) > 0.0f) setVec3(newBentWorld, x, y, blended);
            newLength.at(x, y) = std::min(historyLength + 1.0f, float(temporal_.maxHistory));
        }
    });

    Image bentView(lw, lh, 3, 0.0f);
    forRows(lh, [&](int y) {
        for (int x = 0; x < lw; ++x)
            if (!g.isSky(hs * x, hs * y))
                setVec3(bentView, x, y, normalize(transformVector(viewFromWorld, vec3At(newBentWorld, x, y))));
    });
    if (temporal_.packedHistory) {
        // What the GPU's packed planes hold: the next frame reads these values, and the caller the visibility.
        forRows(lh, [&](int y) {
            for (int x = 0; x < lw; ++x) {
                const std::uint32_t word = packVisibilityLength(visibility.at(x, y), newLength.at(x, y));
                visibility.at(x, y) = unpackVisibility(word);
                newLength.at(x, y) = unpackLength(word);
                setVec3(normalWorld, x, y, unpackOctahedral(packOctahedral(vec3At(normalWorld, x, y))));
                setVec3(newBentWorld, x, y, unpackOctahedral(packOctahedral(vec3At(newBentWorld, x, y))));
            }
        });
    }
    if (gridHistory) {
        // 3., after the accumulation: the history stays on the grid, the result goes to full resolution.
        result_.visibility = upsampleDepthAware(visibility, gridDepth, g, temporal_.depthSigma);
        result_.bentNormal = upsampleDepthAware(bentView, gridDepth, g, temporal_.depthSigma);
        accumulated_ = std::move(visibility);
        previousDepth_ = std::move(gridDepth);
    } else {
        result_.visibility = std::move(visibility);
        result_.bentNormal = std::move(bentView);
        previousDepth_ = g.depth;
    }
    bentWorld_ = std::move(newBentWorld);
    historyLength_ = std::move(newLength);
    previousCamera_ = g.camera;
    previousNormalWorld_ = std::move(normalWorld);
    ++frame_;
    return result_;
}

} // namespace obscura::ssao
