// Flags of the screen-space AO settings shared by `render --ao alchemy`, `ao` and `compare`: the Alchemy
// parameters with the chapter's presets, and the cross-bilateral blur.
#pragma once

#include "obscura/alchemy.h"
#include "obscura/bilateral.h"

#include <string>

namespace CLI {
class App;
class Option;
} // namespace CLI

namespace obscura::cli {

// "auto", "on" or "off" (the CLI checks the spelling) -> the blur's normal weight.
ssao::NormalWeight normalWeightFromFlag(const std::string& value);
// The help text of --blur-normal-weight, shared by every command that has it.
extern const char* const kNormalWeightHelp;

struct BlurFlags {
    std::string mode = "separable";
    int radius = 6;
    float depthSigma = 0.05f;
    std::string normalWeight = "auto";
    std::vector<const CLI::Option*> detailFlags;  // --blur-radius, --blur-depth-sigma, --blur-normal-weight
    void add(CLI::App& app);
    // Warns of the detail flags given with --blur none, which ignores them.
    void warnUnread() const;
    // Validated; errors name the flag.
    ssao::BilateralSettings settings() const;
};

struct AlchemyFlags {
    std::string preset;
    std::string formulation = "paper";
    float intensity = 1.0f, contrast = 1.0f, bias = 1e-4f;
    int samples = 12;
    int guardBand = 0;
    float maxRadiusPixels = 256.0f, lodRadiusPixels = 0.0f;
    bool normalsFromDepth = false;
    unsigned seed = 0;
    // Registers --ao-preset, --ao-formulation, --ao-intensity, --ao-contrast, --ao-bias, --ao-samples,
    // --ao-guard-band, --ao-max-radius-px, --ao-lod-radius-px, --ao-normals-from-depth; and --ao-radius when `withRadius` (render has its own).
    void add(CLI::App& app, bool withRadius);
    // Preset first, then every flag given explicitly. `radiusText` is the --ao-radius value when the
    // command registered it itself (empty: not given). Validated; errors name the flag.
    ssao::AlchemySettings settings(const std::string& radiusText) const;

    float radius = 0.5f;
    CLI::Option *radiusOption = nullptr, *formulationOption = nullptr, *intensityOption = nullptr,
                *contrastOption = nullptr, *biasOption = nullptr, *samplesOption = nullptr;
};

} // namespace obscura::cli
