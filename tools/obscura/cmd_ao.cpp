// `obscura ao`: screen-space AO of a user's own depth (and normal) buffers, with the camera they were
// rendered with. Conventions in docs/FORMATS.md.
#include "ao_options.h"
#include "cli_common.h"
#include "commands.h"
#include "gpu_flags.h"
#include "gtao_cli.h"

#include "obscura/alchemy.h"
#include "obscura/ao_methods.h"
#include "obscura/camera_io.h"
#include "obscura/error.h"
#include "obscura/gpu.h"
#include "obscura/image_io.h"
#include "obscura/parallel.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

namespace obscura::cli {

namespace {

struct AoOptions {
    std::string depth, normal, camera, output;
    std::string method = "alchemy";
    int threads = 0;
    GpuFlags gpu;
    AlchemyFlags alchemy;
    BlurFlags blur;
    GtaoSliceFlags gtao;
    float gtaoMipRatio = 0.0f;  // eval::MethodOptions::gtaoMipRatio
    // The Alchemy flags but --ao-radius, which every method takes: the GTAO methods ignore them, and say so.
    std::vector<const CLI::Option*> alchemyOnlyFlags;
};

// The whole image when it has exactly names.size() channels (three and an alpha for three), the channel named Z
// of a depth file without X or Y channels (a renderer's RGBA + Z, or depth + alpha), or the channels `names` of a
// combined G-buffer EXR (the one `obscura gbuffer -o g.exr` writes: Z, N.X, N.Y, N.Z, albedo.*); otherwise fails
// naming the file and its channels.
Image channels(const Image& img, const std::vector<std::string>& names, const std::string& path, const char* what) {
    const int n = int(names.size());
    const auto& cn = img.channelNames;
    const bool named = int(cn.size()) == img.channels;
    const auto has = [&](const std::string& name) { return std::find(cn.begin(), cn.end(), name) != cn.end(); };
    std::vector<int> index;
    // Engines dump their normal buffers as RGBA: the alpha (A, or a layer's .A) is left out, wherever readExr's
    // order puts it (after R, G, B; before X, Y, Z).
    int alpha = -1;
    for (int c = 0; named && c < img.channels; ++c) {
        const std::string& name = cn[std::size_t(c)];
        if (name == "A" || name == "a" || (name.size() > 2 && name.ends_with(".A"))) alpha = c;
    }
    if (img.channels == n || (n == 3 && img.channels == 4 && alpha >= 0)) {
        for (int c = 0; c < img.channels; ++c)
            if (img.channels == n || c != alpha) index.push_back(c);
    } else {
        // A depth file's Z: not a normal buffer's (X, Y, Z), which passed as --depth must be refused.
        const bool depthZ = n == 1 && names[0] == "Z" && has("Z") && !has("X") && !has("Y");
        const bool combined = has("N.X");
        for (const std::string& name : names)
            for (int c = 0; (combined || depthZ) && c < int(cn.size()); ++c)
                if (cn[std::size_t(c)] == name) index.push_back(c);
        if (int(index.size()) != n) {
            std::string list;
            for (const std::string& name : cn) list += (list.empty() ? "" : ", ") + name;
            fail(path, std::string(what) + " needs " + std::to_string(n) + " channel" + (n > 1 ? "s" : "") +
                           (n == 1 ? " or one named Z" : "") + ", has " + std::to_string(img.channels) +
                           (list.empty() ? "" : " (" + list + ")"));
        }
    }
    Image out(img.width, img.height, n);
    for (std::size_t i = 0; i < out.pixelCount(); ++i)
        for (int c = 0; c < n; ++c)
            out.pixels[i * std::size_t(n) + std::size_t(c)] =
                img.pixels[i * std::size_t(img.channels) + std::size_t(index[std::size_t(c)])];
    return out;
}

void checkSize(const Image& img, const Camera& camera, const std::string& path, const std::string& cameraPath) {
    if (img.width != camera.width || img.height != camera.height)
        fail(path, "is " + std::to_string(img.width) + "x" + std::to_string(img.height) + " but " + cameraPath + " says " +
                       std::to_string(camera.width) + "x" + std::to_string(camera.height));
}

// The estimators take the normals as unit vectors (docs/FORMATS.md): a normal of another length scales the
// obscurance or tilts the horizons without a word. Far from 1 it is most likely another buffer or an
// encoding: albedo, zeros, or n * 0.5 + 0.5 (whose camera-facing (0, 0, 1) is 1.22 long). Sky pixels are
// never read. 10% either way leaves room for half-float storage and for normals interpolated unnormalized.
void checkUnitNormals(const GBuffer& g, const std::string& path, const std::string& depthPath) {
    std::size_t bad = 0;
    int firstX = 0, firstY = 0;
    float firstLength = 0.0f;
    for (int y = 0; y < g.height(); ++y)
        for (int x = 0; x < g.width(); ++x) {
            // isSky, as the passes read it: a writer's finite "far" of 1e30 or more is sky too, and its normal
            // is never read (checking only +inf refused such a buffer's zero sky normals).
            if (g.isSky(x, y)) continue;
            if (!std::isfinite(g.normal.at(x, y, 0)) || !std::isfinite(g.normal.at(x, y, 1)) ||
                !std::isfinite(g.normal.at(x, y, 2)))
                fail(path, "normal at pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is not finite");
            // hypot: the squares of a finite 1e20 overflowed, and the message spoke of a length of inf.
            const float length = float(std::hypot(double(g.normal.at(x, y, 0)), double(g.normal.at(x, y, 1)),
                                                  double(g.normal.at(x, y, 2))));
            if (length >= 0.9f && length <= 1.1f) continue;
            if (bad++ == 0) firstX = x, firstY = y, firstLength = length;
        }
    // A zero normal under a finite depth is most often a sky written as the far plane (1e4, 65504): a surface to
    // the estimators (docs/FORMATS.md), and the normals were not the file at fault.
    if (bad > 0 && firstLength < 1e-3f)
        fail(path, "normal at pixel (" + std::to_string(firstX) + ", " + std::to_string(firstY) + ") is zero where " +
                       depthPath + " has depth " + numberText(g.depth.at(firstX, firstY)) + " (" + std::to_string(bad) +
                       " pixel" + (bad > 1 ? "s" : "") + " with normals outside [0.9, 1.1]): if that depth is the far "
                       "plane, write sky as +inf (or 1e30 and more)");
    if (bad > 0)
        fail(path, "normal at pixel (" + std::to_string(firstX) + ", " + std::to_string(firstY) + ") has length " +
                       numberText(firstLength) + " (" + std::to_string(bad) + " pixel" + (bad > 1 ? "s" : "") +
                       " outside [0.9, 1.1]): unit view-space normals expected, decoded if stored as n * 0.5 + 0.5");
}

// Normals turned away from the camera are another convention's (+Z forward, or world space), not a few
// back-facing pixels at grazing angles: Alchemy moved by 0.40 on average, GTAO by 0.58, without a word. The
// pixel's view ray points from the camera to p, so a normal facing the camera has n . p < 0.
void checkFacing(const GBuffer& g, const std::string& path) {
    std::size_t surface = 0, away = 0;
    for (int y = 0; y < g.height(); ++y)
        for (int x = 0; x < g.width(); ++x) {
            if (g.isSky(x, y)) continue;
            const Vec3 p = g.camera.viewFromPixel(float(x) + 0.5f, float(y) + 0.5f, g.depth.at(x, y));
            const Vec3 n{g.normal.at(x, y, 0), g.normal.at(x, y, 1), g.normal.at(x, y, 2)};
            ++surface;
            away += dot(n, p) > 0.0f;
        }
    if (surface > 0 && 2 * away > surface)
        fail(path, "normals face away from the camera at " + std::to_string(away) + " of " + std::to_string(surface) +
                       " surface pixels: view-space normals turned towards the camera expected (the camera looks "
                       "down -Z; a +Z-forward or world-space buffer needs converting)");
}

void run(const AoOptions& o) {
    auto start = std::chrono::steady_clock::now();
    checkOutputPath("-o", o.output, {".exr"}, {o.depth, o.normal, o.camera});
    const eval::AoMethod& method = eval::findAoMethod(o.method, "--method");
    o.blur.warnUnread();
    const ssao::BilateralSettings blur = o.blur.settings();
    ssao::AlchemySettings alchemy = o.alchemy.settings("");
    if (o.alchemy.formulationOption->count() > 0 && o.method.starts_with("alchemy")) {
        // --method alchemy-chapter is --ao-formulation chapter: a contradiction once ran the chapter's silently.
        const std::string implied = o.method == "alchemy-chapter" ? "chapter" : "paper";
        if (o.alchemy.formulation != implied)
            fail("--ao-formulation", o.alchemy.formulation + " contradicts --method " + o.method + " (whose formulation is " +
                                         implied + "); give one of the two");
    }
    // A preset calibrates the chapter's formulation and switched --method alchemy (the paper's) to it silently.
    if (o.method == "alchemy" && !o.alchemy.preset.empty())
        fail("--ao-preset", o.alchemy.preset + " calibrates the chapter's formulation, and --method alchemy is the "
                                               "paper's; give --method alchemy-chapter");
    if (o.method == "alchemy-chapter") alchemy.formulation = ssao::AlchemyFormulation::Chapter;
    const bool radiusGiven = o.alchemy.radiusOption->count() > 0;
    if (!o.method.starts_with("alchemy")) {
        // --ao-radius was checked with the Alchemy settings: the same range, (0, 1e4] m.
        warnIgnored(o.alchemyOnlyFlags, "applies to the alchemy methods, not " + o.method);
    }
    if (!o.method.starts_with("alchemy") && o.normal.empty())
        fail("--normal", "method " + o.method + " needs a normal buffer");
    // Only an EXR holds what these are: a PNG's 8-bit codes / 255 (a 16-bit depth PNG in millimeters is read as
    // 8 bits) are no depth in meters, and Radiance HDR stores no negative value, which normals have.
    checkInputFormat("--depth", o.depth, {".exr"}, "linear depth in meters");
    checkInputFormat("--normal", o.normal, {".exr"}, "a unit normal buffer");
    o.gpu.validate();
    o.gtao.validate();
    validateGtaoMipRatioOverride(o.gtaoMipRatio);
    if ((!o.gtao.value.empty() || o.gtaoMipRatio != 0.0f) && o.method.starts_with("alchemy"))
        fail(o.gtao.value.slices != 0  ? "--gtao-slices"
             : o.gtao.value.steps != 0 ? "--gtao-steps"
             : o.gtao.value.jitter     ? "--gtao-jitter"
             : o.gtao.value.interleave ? "--gtao-interleave"
                                       : "--gtao-mip-ratio",
             "applies to the gtao methods, not " + o.method);
    ThreadLimit limit(o.threads, "--threads");

    GBuffer g;
    g.camera = readCameraJson(o.camera);
    g.depth = channels(readExrFrame(o.depth), {"Z"}, o.depth, "depth");
    checkSize(g.depth, g.camera, o.depth, o.camera);
    if (o.method.starts_with("alchemy") && (g.width() <= 2 * alchemy.guardBand || g.height() <= 2 * alchemy.guardBand))
        fail("--ao-guard-band", std::to_string(alchemy.guardBand) + " px on every side leaves nothing of " + o.depth +
                                    "'s " + std::to_string(g.width()) + "x" + std::to_string(g.height()) + " pixels");
    for (int y = 0; y < g.height(); ++y)
        for (int x = 0; x < g.width(); ++x) {
            const float d = g.depth.at(x, y);
            if (std::isnan(d) || d <= 0.0f)
                fail(o.depth, "depth at pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is " +
                                  numberText(d) + " (linear view depth in m must be > 0, or +inf for sky)");
        }
    // Alchemy told to rebuild its normals reads none: the file went unused without a word, yet a bad one failed.
    const bool normalUnread = o.method.starts_with("alchemy") && alchemy.normalsFromDepth && !o.normal.empty();
    if (normalUnread)
        std::fprintf(stderr, "obscura: warning: --normal: --ao-normals-from-depth rebuilds the normals from depth; "
                             "ignored\n");
    if (o.normal.empty() || normalUnread) {
        alchemy.normalsFromDepth = true;
        g.normal = ssao::normalsFromDepth(g.depth, g.camera);
    } else {
        g.normal = channels(readExrFrame(o.normal), {"N.X", "N.Y", "N.Z"}, o.normal, "normal");
        checkSize(g.normal, g.camera, o.normal, o.camera);
        checkUnitNormals(g, o.normal, o.depth);  // surface pixels only: a sky pixel's normal is never read
        checkFacing(g, o.normal);
        // A G-buffer holds (0, 0, 0) under the sky (GBuffer::normal); whatever the file holds there goes. The
        // surface normals within the accepted lengths are made unit, as ssao::prepareGBuffer does: Alchemy's
        // v.n scales with the length (AO moved by up to 0.082 for normals 1.09 long, 0.090 for 0.91).
        for (int y = 0; y < g.height(); ++y)
            for (int x = 0; x < g.width(); ++x) {
                const Vec3 n = g.isSky(x, y) ? Vec3{} : normalize(g.viewNormal(x, y));
                for (int c = 0; c < 3; ++c) g.normal.at(x, y, c) = n[c];
            }
    }

    Image ao;
    const std::unique_ptr<gpu::Context> context = o.gpu.open();
    const std::string device = context ? context->device().name : "CPU";
    if (o.method.starts_with("alchemy")) {
        const int band = alchemy.guardBand;
        const GBuffer cropped = ssao::cropGuardBand(g, ssao::guardBandCamera(g.camera, -band), band);
        if (context)
            ao = gpu::bilateralFilter(*context, gpu::alchemyAO(*context, g, alchemy), cropped, blur);
        else
            ao = ssao::bilateralFilter(ssao::alchemyAO(g, alchemy), cropped, blur);
    } else {
        eval::MethodOptions mo;
        mo.blur = blur;
        mo.gtao = o.gtao.value;
        mo.gtaoMipRatio = o.gtaoMipRatio;
        warnGtaoMipRatioUnread(o.gtaoMipRatio, method.readsMipRatio, "method " + o.method + " does not read it");
        if (radiusGiven) mo.radius = alchemy.radius;  // else the method's own (1 m)
        mo.gpu = context.get();
        ao = method.compute(g, mo);
    }
    reportValidation(context.get());
    ao.channelNames = {"Y"};
    writeExr(o.output, ao);
    std::printf("wrote %s: %dx%d %s AO on %s, %.2f s\n", o.output.c_str(), ao.width, ao.height, o.method.c_str(),
                device.c_str(), secondsSince(start));
}

} // namespace

void addAoCommand(CLI::App& app) {
    auto o = std::make_shared<AoOptions>();
    CLI::App* cmd = app.add_subcommand(
        "ao", "Screen-space AO of your own depth (+ normal) buffers and camera (formats in docs/FORMATS.md)");
    cmd->add_option("--depth", o->depth,
                    "Linear view depth EXR: 1 channel, or a channel named Z (not beside X and Y: a normal buffer); "
                    "meters along -Z, +inf (or 1e30 and more) for sky")
        ->required();
    cmd->add_option("--normal", o->normal,
                    "View-space unit normal EXR: 3 channels (R G B A: the alpha is left out), or N.X N.Y N.Z. Required "
                    "by the gtao methods; the alchemy methods rebuild normals from depth without it");
    cmd->add_option("--camera", o->camera, "Camera JSON of the buffers (as `obscura gbuffer` writes it)")->required();
    cmd->add_option("-o,--output", o->output, "Output AO EXR (1 channel Y, 1 = unoccluded)")->required();
    cmd->add_option("--method", o->method, "AO method: " + eval::aoMethodNames() + " (see `obscura compare --help`)")->capture_default_str();
    cmd->add_option("--threads", o->threads, "Worker threads (0 = all cores)")->capture_default_str();
    o->gpu.add(*cmd, "the AO method and the blur");
    const std::vector<const CLI::Option*> alchemyFlags = optionsAddedBy(*cmd, [&] { o->alchemy.add(*cmd, true); });
    for (const CLI::Option* option : alchemyFlags)
        if (option != o->alchemy.radiusOption) o->alchemyOnlyFlags.push_back(option);
    o->blur.add(*cmd);
    o->gtao.add(*cmd, "GTAO methods");
    addGtaoMipRatioOverride(*cmd, o->gtaoMipRatio);
    cmd->callback([o] { run(*o); });
}

} // namespace obscura::cli
