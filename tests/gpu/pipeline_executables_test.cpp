// Reading what a driver says of a pipeline (VK_KHR_pipeline_executable_properties), against queries that
// behave as the spec says a driver's must: the two-call idiom, VK_INCOMPLETE when the caller's array is short,
// names in fixed-size fields, text representations null-terminated. Lavapipe (Mesa 22.3) lacks the extension,
// so these fakes are what CI can hold the reading to; the NVIDIA driver offers it.
#include "gpu/pipeline_executables.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

namespace obscura::gpu {
namespace {

VkResult failStatistics = VK_SUCCESS;  // what the fake statistics query returns instead of its data

template <std::size_t N>
void put(char (&field)[N], const std::string& s) {
    std::memset(field, 0, N);
    std::memcpy(field, s.data(), std::min(s.size(), N - 1));
}

VKAPI_ATTR VkResult VKAPI_CALL fakeProperties(VkDevice, const VkPipelineInfoKHR* info, std::uint32_t* n,
                                              VkPipelineExecutablePropertiesKHR* out) {
    EXPECT_EQ(info->sType, VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR);
    if (!out) {
        *n = 1;
        return VK_SUCCESS;
    }
    if (*n < 1) return VK_INCOMPLETE;
    EXPECT_EQ(out[0].sType, VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR);
    out[0].stages = VK_SHADER_STAGE_COMPUTE_BIT;
    put(out[0].name, "Compute Shader");
    put(out[0].description, std::string(300, 'd'));  // longer than the field: cut, still terminated
    out[0].subgroupSize = 32;
    *n = 1;
    return VK_SUCCESS;
}

VKAPI_ATTR VkResult VKAPI_CALL fakeStatistics(VkDevice, const VkPipelineExecutableInfoKHR* info, std::uint32_t* n,
                                              VkPipelineExecutableStatisticKHR* out) {
    EXPECT_EQ(info->executableIndex, 0u);
    if (failStatistics != VK_SUCCESS) return failStatistics;
    constexpr std::uint32_t kCount = 5;
    if (!out) {
        *n = kCount;
        return VK_SUCCESS;
    }
    const std::uint32_t written = std::min(*n, kCount);
    for (std::uint32_t i = 0; i < written; ++i) {
        EXPECT_EQ(out[i].sType, VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR);
        put(out[i].description, "what it counts");
    }
    const auto set = [&](std::uint32_t i, const char* name, VkPipelineExecutableStatisticFormatKHR format) {
        if (i >= written) return false;
        put(out[i].name, name);
        out[i].format = format;
        return true;
    };
    if (set(0, "Register Count", VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR)) out[0].value.u64 = 40;
    if (set(1, "Spills", VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR)) out[1].value.b32 = VK_TRUE;
    if (set(2, "Offset", VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR)) out[2].value.i64 = -3;
    if (set(3, "Occupancy", VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_FLOAT64_KHR)) out[3].value.f64 = 0.75;
    if (set(4, "Future", VkPipelineExecutableStatisticFormatKHR(77))) out[4].value.u64 = 1;
    *n = written;
    return written < kCount ? VK_INCOMPLETE : VK_SUCCESS;
}

// Two representations: a text one (the null inside its size ends it) and a binary one with a zero byte.
const std::string kText = std::string("FFMA R0, R1, R2, R3 ;\n") + '\0' + "garbage";
const std::string kBinary = std::string("\x01\x00\x02", 3);

VKAPI_ATTR VkResult VKAPI_CALL fakeInternals(VkDevice, const VkPipelineExecutableInfoKHR*, std::uint32_t* n,
                                             VkPipelineExecutableInternalRepresentationKHR* out) {
    if (!out) {
        *n = 2;
        return VK_SUCCESS;
    }
    const std::string* data[2] = {&kText, &kBinary};
    VkResult r = VK_SUCCESS;
    for (std::uint32_t i = 0; i < std::min(*n, 2u); ++i) {
        put(out[i].name, i == 0 ? "SASS" : "Binary");
        put(out[i].description, "the machine code");
        out[i].isText = i == 0 ? VK_TRUE : VK_FALSE;
        if (!out[i].pData) {
            out[i].dataSize = data[i]->size();
            continue;
        }
        const std::size_t copied = std::min(out[i].dataSize, data[i]->size());
        std::memcpy(out[i].pData, data[i]->data(), copied);
        if (copied < data[i]->size()) r = VK_INCOMPLETE;
        out[i].dataSize = copied;
    }
    return r;
}

const ExecutableQueries kFakes{fakeProperties, fakeStatistics, fakeInternals};

TEST(GpuPipelineExecutables, ReadsEveryFormatAndSkipsUnknownOnes) {
    failStatistics = VK_SUCCESS;
    std::string error = "stale";
    const std::vector<PipelineExecutable> x = describeExecutables(VK_NULL_HANDLE, VK_NULL_HANDLE, kFakes, false, &error);
    EXPECT_EQ(error, "");
    ASSERT_EQ(x.size(), 1u);
    EXPECT_EQ(x[0].name, "Compute Shader");
    EXPECT_EQ(x[0].description, std::string(VK_MAX_DESCRIPTION_SIZE - 1, 'd'));
    EXPECT_EQ(x[0].subgroupSize, 32u);
    ASSERT_EQ(x[0].statistics.size(), 4u);  // the fifth has a format this code does not know
    EXPECT_EQ(x[0].statistics[0].name, "Register Count");
    EXPECT_EQ(x[0].statistics[0].value, 40.0);
    EXPECT_EQ(x[0].statistics[0].description, "what it counts");
    EXPECT_EQ(x[0].statistics[1].value, 1.0);
    EXPECT_EQ(x[0].statistics[2].value, -3.0);
    EXPECT_EQ(x[0].statistics[3].value, 0.75);
    EXPECT_TRUE(x[0].internals.empty()) << "not asked for";
}

TEST(GpuPipelineExecutables, ReadsTextAndBinaryRepresentations) {
    failStatistics = VK_SUCCESS;
    std::string error;
    const std::vector<PipelineExecutable> x = describeExecutables(VK_NULL_HANDLE, VK_NULL_HANDLE, kFakes, true, &error);
    EXPECT_EQ(error, "");
    ASSERT_EQ(x.size(), 1u);
    ASSERT_EQ(x[0].internals.size(), 2u);
    EXPECT_EQ(x[0].internals[0].name, "SASS");
    EXPECT_TRUE(x[0].internals[0].text);
    EXPECT_EQ(x[0].internals[0].data, "FFMA R0, R1, R2, R3 ;\n");
    EXPECT_EQ(x[0].internals[1].name, "Binary");
    EXPECT_FALSE(x[0].internals[1].text);
    EXPECT_EQ(x[0].internals[1].data, kBinary);
}

TEST(GpuPipelineExecutables, ARefusedQueryIsReportedNotThrown) {
    failStatistics = VK_ERROR_OUT_OF_HOST_MEMORY;
    std::string error;
    std::vector<PipelineExecutable> x;
    EXPECT_NO_THROW(x = describeExecutables(VK_NULL_HANDLE, VK_NULL_HANDLE, kFakes, true, &error));
    failStatistics = VK_SUCCESS;
    EXPECT_TRUE(x.empty());
    EXPECT_EQ(error, "vkGetPipelineExecutableStatisticsKHR returned VK_ERROR_OUT_OF_HOST_MEMORY");
}

} // namespace
} // namespace obscura::gpu
