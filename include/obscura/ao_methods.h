// The screen-space AO methods by name, for the commands that run any of them (`obscura compare`,
// `obscura ao`): each entry computes AO on a G-buffer and names the ray-traced settings of the integral it
// estimates, so it can be measured against ground truth. A new method is one entry in src/eval/methods.cpp.
//
// Errors: findAoMethod()/parseMethodList() throw obscura::Error for an unknown name; compute() throws for
// bad settings or buffers.
#pragma once

#include "obscura/bilateral.h"
#include "obscura/gbuffer.h"
#include "obscura/gpu.h"
#include "obscura/image.h"
#include "obscura/trace.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace obscura::eval {

// Knobs every method understands; 0 keeps the method's own default.
struct MethodOptions {
    int samples = 0;                      // samples (or directions x steps) per pixel
    ssao::GtaoSliceOverride gtao;         // GTAO methods: slice and step counts, jitter; slices over samples'
    float gtaoMipRatio = 0.0f;            // GTAO methods: GtaoSettings::mipDistanceRatio, [2, 64]; 0: its
                                          // default. Only the mip and planar-nearest samplings read it
    float radius = 0.0f;                  // world-space radius, m
    ssao::BilateralSettings blur{ssao::BlurMode::None};  // filter applied after the raw estimate
    std::uint32_t seed = 0;
    gpu::Context* gpu = nullptr;          // set: the estimator and the filter run as Vulkan compute passes
};

struct AoMethod {
    std::string name;
    std::string description;  // one line
    // Obscurance in [0, 1], one channel of the G-buffer's size; sky 1.
    std::function<Image(const GBuffer&, const MethodOptions&)> compute;
    // The ray-traced settings (falloff, radius) of the integral the method estimates, with `rays` rays.
    std::function<trace::ObscuranceSettings(const MethodOptions&, int rays)> reference;
    // The samples per pixel it takes with these options (per grid pixel at half resolution): Alchemy's disc
    // samples, GTAO's 2 x slices x steps per side, whose slice count `samples` sets only in whole slices.
    std::function<int(const MethodOptions&)> samplesPerPixel;
    // Whether MethodOptions::gtaoMipRatio changes it: its samples switch on distance (mip, planar-mip and
    // planar-nearest sampling).
    bool readsMipRatio = false;
};

const std::vector<AoMethod>& aoMethods();
// Their names in order, comma-separated: "alchemy, alchemy-chapter, gtao, ...".
std::string aoMethodNames();
// `flag` names the option the name came from in the error (ao's --method, compare's --methods).
const AoMethod& findAoMethod(const std::string& name, const std::string& flag = "--methods");
// "alchemy,gtao" -> the methods, in order, without duplicates.
std::vector<const AoMethod*> parseMethodList(const std::string& commaSeparated);

} // namespace obscura::eval
