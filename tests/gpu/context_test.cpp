// The Vulkan context and its resources: device choice and its errors, the block suballocator's free list,
// the SPIR-V reflection the passes check their layouts with, staged upload and download.
#include "gpu_test_util.h"
#include "scoped_env.h"
#include "spirv_edit.h"

#include "gpu/allocator.h"
#include "gpu/buffer.h"
#include "gpu/spirv.h"
#include "gpu/shaders/layouts.h"

#include "obscura/alchemy_constants.h"
#include "obscura/error.h"
#include "obscura/gpu.h"
#include "obscura/gpu_shaders.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <numeric>
#include <vector>

namespace obscura::gpu {
namespace {

// The free list alone: first fit with alignment, the alignment gap kept free, and neighbours merged on
// release in any order, so a block emptied in any order is one free range again.
TEST(GpuAllocator, FirstFitAlignsAndMerges) {
    RangeAllocator r(1024);
    EXPECT_EQ(r.allocate(100, 1), 0u);
    EXPECT_EQ(r.allocate(100, 256), 256u);  // [100, 256) stays free
    EXPECT_EQ(r.allocate(50, 4), 100u);     // first fit: into the gap
    EXPECT_EQ(r.freeBytes(), 1024u - 250u);
    EXPECT_FALSE(r.allocate(1024, 1).has_value());
    EXPECT_EQ(r.allocate(668, 1), 356u);  // exactly the tail
    EXPECT_EQ(r.freeRanges(), 1u);        // [150, 256)
    r.release(100, 50);
    r.release(356, 668);
    r.release(0, 100);
    EXPECT_EQ(r.freeRanges(), 2u);  // [0, 256) and [356, 1024) around the block at 256
    r.release(256, 100);
    EXPECT_TRUE(r.empty());
    EXPECT_EQ(r.allocate(1024, 1024), 0u);
}

// The embedded shaders declare what src/gpu/shaders/layouts.h says they do.
TEST(GpuShaders, ReflectionReadsTheLayouts) {
    const SpirvLayout l = reflect(shaders::alchemy);
    EXPECT_EQ(l.bindings, kAlchemyBindingCount);
    EXPECT_EQ(l.pushConstantBytes, std::uint32_t(kAlchemyPushConstantBytes));
    EXPECT_EQ(l.localSize[0], std::uint32_t(ssao::kAlchemyWorkgroupX));
    EXPECT_EQ(l.localSize[1], std::uint32_t(ssao::kAlchemyWorkgroupY));
    EXPECT_EQ(l.localSize[2], 1u);
    const SpirvLayout b = reflect(shaders::bilateral_separable);
    EXPECT_EQ(b.bindings, kBilateralBindingCount);
    EXPECT_EQ(b.pushConstantBytes, std::uint32_t(kBilateralPushConstantBytes));
    const std::uint32_t junk[6] = {1, 2, 3, 4, 5, 6};
    EXPECT_THROW(reflect(Spirv{junk, 6}), Error);
}

// The host binds one descriptor set 0 of bindings 0..n-1, each a single storage buffer or combined image sampler.
// The reflection counted decorated bindings only, so a module with a binding in set 1, a gap, a duplicate or a
// uniform block passed the count check, and the driver crashed or the shader wrote into another buffer; each is
// now named (ComputePipeline refuses it). Every embedded shader reads as bindable.
TEST(GpuShaders, ReflectionNamesLayoutsTheHostCannotBind) {
    for (const std::string& name : shaderNames()) {
        const ShaderCode code = shaderCode(name);
        EXPECT_EQ(reflect({code.words, code.wordCount}).unsupported, "") << name;
    }
    const std::vector<std::uint32_t> embedded(shaders::gtao.words, shaders::gtao.words + shaders::gtao.count);
    const auto unsupported = [](const std::vector<std::uint32_t>& words) {
        return reflect({words.data(), words.size()}).unsupported;
    };
    const std::vector<std::size_t> sets = testing::decorations(embedded, spirv::DecorationDescriptorSet);
    const std::vector<std::size_t> bindings = testing::decorations(embedded, spirv::DecorationBinding);
    ASSERT_GE(bindings.size(), 3u);
    ASSERT_EQ(sets.size(), bindings.size());
    std::vector<std::uint32_t> words = embedded;
    words[sets[0] + 3] = 1;
    EXPECT_NE(unsupported(words).find("is in descriptor set 1, the host binds set 0 only"), std::string::npos)
        << unsupported(words);
    words = embedded;
    std::size_t highest = bindings[0];
    for (std::size_t i : bindings)
        if (words[i + 3] > words[highest + 3]) highest = i;
    words[highest + 3] += 1;
    EXPECT_NE(unsupported(words).find("bindings are not numbered 0 to"), std::string::npos) << unsupported(words);
    words = embedded;
    for (std::size_t i : bindings) words[i + 3] = words[i + 3] == 1 ? 0 : words[i + 3];
    EXPECT_NE(unsupported(words).find("binding 0 is declared twice"), std::string::npos) << unsupported(words);
    // A storage buffer's pointer type moved to the Uniform class: with its Block decoration, a uniform block.
    words = embedded;
    bool moved = false;
    for (std::size_t i = 5; i < words.size() && (words[i] >> 16) != 0; i += words[i] >> 16)
        if ((words[i] & 0xffffu) == spirv::OpTypePointer && words[i + 2] == spirv::StorageClassStorageBuffer) {
            words[i + 2] = spirv::StorageClassUniform;
            moved = true;
        }
    ASSERT_TRUE(moved) << "gtao.comp declares no StorageBuffer pointer";
    EXPECT_NE(unsupported(words).find("neither a storage buffer nor a combined image sampler"), std::string::npos)
        << unsupported(words);
}

// A malformed module is an obscura::Error, whatever is wrong with it: a type instruction too short for its
// operands once threw std::length_error from a reversed range, and read past its end.
TEST(GpuShaders, ReflectionRefusesShortTypeInstructions) {
    for (const std::uint32_t op : {spirv::OpTypeInt, spirv::OpTypeVector, spirv::OpTypePointer, spirv::OpTypeStruct}) {
        std::vector<std::uint32_t> words(shaders::alchemy.words, shaders::alchemy.words + shaders::alchemy.count);
        words.insert(words.begin() + 5, (1u << 16) | op);  // a type instruction of one word: no result id
        try {
            reflect({words.data(), words.size()});
            ADD_FAILURE() << "no error for a one-word type " << op;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("type instruction of 1 words"), std::string::npos) << e.what();
        }
    }
}

// The workgroup size a module declares: glslang writes it twice, as the LocalSize execution mode and as a
// constant decorated BuiltIn WorkgroupSize, and where the two differ the built-in is what a device runs
// (SPIR-V 1.5, "BuiltIn"), so the reflection reads it; a module rewritten in both places reads as rewritten.
// A size given by specialization constants (gtao.comp's, local_size_x_id) reads as their defaults, which the
// host leaves alone, and their constant_ids are not among those the host sets.
TEST(GpuShaders, ReflectionReadsTheWorkgroupSizeADeviceRuns) {
    const std::vector<std::uint32_t> embedded(shaders::alchemy.words, shaders::alchemy.words + shaders::alchemy.count);
    const auto size = [](const std::vector<std::uint32_t>& words) {
        const SpirvLayout l = reflect({words.data(), words.size()});
        return std::vector<std::uint32_t>(l.localSize, l.localSize + 3);
    };
    const std::vector<std::uint32_t> declared = {std::uint32_t(ssao::kAlchemyWorkgroupX),
                                                 std::uint32_t(ssao::kAlchemyWorkgroupY), 1u};
    EXPECT_EQ(size(embedded), declared);
    EXPECT_TRUE(reflect(shaders::alchemy).sizeSpecIds.empty());
    // Only the built-in rewritten: it wins over the execution mode, which still says the embedded size.
    const std::vector<std::uint32_t> builtinOnly = testing::withWorkgroupSize(embedded, 24, 3, false);
    ASSERT_NE(builtinOnly, embedded) << "the module has no WorkgroupSize built-in to rewrite";
    EXPECT_EQ(size(builtinOnly), (std::vector<std::uint32_t>{24, 3, 1}));
    EXPECT_EQ(size(testing::withWorkgroupSize(embedded, 32, 2)), (std::vector<std::uint32_t>{32, 2, 1}));
    // The built-in's composite made a specialization composite of those constants: the same size, fixed.
    std::vector<std::uint32_t> spec = builtinOnly;
    const std::size_t composite = testing::workgroupSizeComposite(spec);
    ASSERT_NE(composite, 0u);
    spec[composite] = (spec[composite] & 0xffff0000u) | spirv::OpSpecConstantComposite;
    EXPECT_EQ(size(spec), (std::vector<std::uint32_t>{24, 3, 1}));
    EXPECT_TRUE(reflect({spec.data(), spec.size()}).sizeSpecIds.empty());
    // A component that is no constant at all (the composite's own id) is refused.
    spec[composite + 3] = spec[composite + 2];
    EXPECT_NE(testing::errorMessage([&] { reflect({spec.data(), spec.size()}); }).find("WorkgroupSize has a component"),
              std::string::npos);

    // gtao.comp's size: two specialization constants, whose defaults are layouts.h's size.
    const SpirvLayout gtao = reflect(shaders::gtao);
    EXPECT_EQ(std::vector<std::uint32_t>(gtao.localSize, gtao.localSize + 3),
              (std::vector<std::uint32_t>{std::uint32_t(kGtaoWorkgroupX), std::uint32_t(kGtaoWorkgroupY), 1u}));
    EXPECT_EQ(gtao.sizeSpecIds,
              (std::vector<std::uint32_t>{std::uint32_t(kSpecWorkgroupSizeX), std::uint32_t(kSpecWorkgroupSizeY)}));
    EXPECT_EQ(gtao.specConstants, kGtaoSpecPackedNormals + 1);  // the variants' constant_ids 0..6, not the size's
    // Rewritten, it reads as rewritten through the constants' defaults; the execution mode alone does not count.
    const std::vector<std::uint32_t> gtaoWords(shaders::gtao.words, shaders::gtao.words + shaders::gtao.count);
    EXPECT_EQ(size(testing::withWorkgroupSize(gtaoWords, 24, 3, false)), (std::vector<std::uint32_t>{24, 3, 1}));
    EXPECT_EQ(size(testing::withWorkgroupSize(gtaoWords, 24, 3)), (std::vector<std::uint32_t>{24, 3, 1}));
}

// A counter of fewer than 64 valid bits (36 on some GPUs) wraps: the plain 64-bit difference of ticks
// 2^36 - 500 and 500 read 9.6e14 ms; modulo the counter it is 1000 ticks, 0.052083 ms at 52.083 ns a tick.
TEST(GpuContext, TimestampsWrapAtTheCounterWidth) {
    const double periodNs = 52.083;
    const std::uint64_t before = (std::uint64_t(1) << 36) - 500, after = 500;
    EXPECT_NEAR(timestampDeltaMs(before, after, timestampMask(36), periodNs), 1000 * periodNs * 1e-6, 1e-12);
    EXPECT_NEAR(timestampDeltaMs(10, 1010, timestampMask(64), periodNs), 1000 * periodNs * 1e-6, 1e-12);
    EXPECT_EQ(timestampMask(64), ~std::uint64_t(0));
    EXPECT_EQ(timestampMask(1), 1u);
}

TEST(GpuContext, DeviceInfo) {
    OBSCURA_GPU_CONTEXT(context);
    EXPECT_FALSE(context.device().name.empty());
    EXPECT_GE(context.device().apiVersion, std::uint32_t(VK_API_VERSION_1_2));
    EXPECT_TRUE(context.validation());
    std::printf("[ measured ] device %d: %s, timestamp period %g ns\n", context.device().index,
                context.device().name.c_str(), context.device().timestampPeriodNs);
}

// The messenger records what the layer reports (so the tests' "no message" checks mean something): a
// buffer of size 0 breaks VUID-VkBufferCreateInfo-size-00912. A context of its own, so the shared one stays
// clean.
TEST(GpuContext, ValidationRecordsMessages) {
    if (deviceCount() == 0) GTEST_SKIP() << "no Vulkan device (install mesa-vulkan-drivers for lavapipe)";
    ContextSettings settings;
    settings.validation = true;
    Context context(settings);
    EXPECT_EQ(testing::validationReport(context), "");
    Context::Impl& c = context.impl();
    VkBufferCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    info.size = 0;
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    VkBuffer buffer = VK_NULL_HANDLE;
    if (vkCreateBuffer(c.device, &info, nullptr, &buffer) == VK_SUCCESS) vkDestroyBuffer(c.device, buffer, nullptr);
    const std::string report = testing::validationReport(context);
    EXPECT_NE(report.find("VUID-VkBufferCreateInfo-size-00912"), std::string::npos) << report;
}

// A device index beyond the devices there are is an error naming the setting, from the settings and from
// the environment alike.
TEST(GpuContext, RejectsAMissingDevice) {
    if (deviceCount() == 0) GTEST_SKIP() << "no Vulkan device (install mesa-vulkan-drivers for lavapipe)";
    ContextSettings settings;
    settings.deviceIndex = deviceCount();
    try {
        Context c(settings);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("deviceIndex"), std::string::npos) << e.what();
    }
    testutil::ScopedEnv device("OBSCURA_GPU_DEVICE", "x");
    EXPECT_THROW(Context{}, Error);
    // The whole value, digits only: strtol took " 0" and "+0" but refused "0 ".
    for (const char* bad : {" 0", "+0", "0 ", "1x", "-2"}) {
        device.set(bad);
        EXPECT_THROW(Context{}, Error) << "'" << bad << "'";
    }
    device.set("0");
    EXPECT_EQ(Context{}.device().index, 0);
    device.set("-1");  // the default device, as --gpu-device -1 asks
    EXPECT_GE(Context{}.device().index, 0);
}

// Upload and download through staging buffers, in sizes that straddle the allocator's 64 MiB block (a
// larger buffer gets a block of its own, released with it), and suballocated buffers share blocks.
TEST(GpuContext, UploadAndDownloadRoundTrip) {
    OBSCURA_GPU_CONTEXT(context);
    Context::Impl& c = context.impl();
    for (std::size_t count : {std::size_t(1), std::size_t(1000), std::size_t(17) << 20}) {
        std::vector<float> data(count);
        std::iota(data.begin(), data.end(), 0.5f);
        const Buffer b = upload(c, data.data(), count * sizeof(float));
        std::vector<float> back(count, -1.0f);
        download(c, b, back.data(), count * sizeof(float));
        EXPECT_EQ(back, data) << count;
    }
    const std::size_t blocks = c.allocator->blockCount();
    {
        std::vector<Buffer> many;
        for (int i = 0; i < 50; ++i) many.emplace_back(c, 4096 + 256 * i, MemoryUse::Device);
        EXPECT_LE(c.allocator->blockCount(), blocks + 1);
    }
    EXPECT_LE(c.allocator->blockCount(), blocks + 1);
    EXPECT_EQ(testing::validationReport(context), "");
}

} // namespace
} // namespace obscura::gpu
