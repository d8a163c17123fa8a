// Reading VK_KHR_pipeline_executable_properties; see pipeline_executables.h.
#include "gpu/pipeline_executables.h"

#include <algorithm>
#include <cstring>

namespace obscura::gpu {

namespace {

// A fixed-size name or description field, up to its null (the spec requires one; a driver that forgets it
// still gives a bounded string).
template <std::size_t N>
std::string text(const char (&field)[N]) {
    return std::string(field, strnlen(field, N));
}

// VK_INCOMPLETE cannot happen with the count just read, but is taken as success with what came.
bool ok(VkResult r) { return r == VK_SUCCESS || r == VK_INCOMPLETE; }

// The spec's two-call idiom for each of the three queries, query(device, info, &n, items): the count, then
// the items, each item's sType set first. Returns the first result that is not ok, else the last.
template <class T, class Info>
VkResult enumerate(VkResult (*query)(VkDevice, const Info*, std::uint32_t*, T*), VkDevice device, const Info* info,
                   VkStructureType type, std::vector<T>& items) {
    std::uint32_t n = 0;
    if (VkResult r = query(device, info, &n, nullptr); !ok(r)) return r;
    items.assign(n, T{});
    for (T& item : items) item.sType = type;
    const VkResult r = query(device, info, &n, items.data());
    items.resize(std::min<std::size_t>(n, items.size()));
    return r;
}

} // namespace

std::vector<PipelineExecutable> describeExecutables(VkDevice device, VkPipeline pipeline, const ExecutableQueries& q,
                                                    bool withInternals, std::string* error) {
    std::vector<PipelineExecutable> out;
    error->clear();
    const auto failed = [&](const char* query, VkResult r) {
        *error = std::string(query) + " returned " + resultName(r);
        return out;
    };
    VkPipelineInfoKHR info{};
    info.sType = VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR;
    info.pipeline = pipeline;
    std::vector<VkPipelineExecutablePropertiesKHR> properties;
    if (VkResult r = enumerate(q.properties, device, &info, VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_PROPERTIES_KHR, properties);
        !ok(r))
        return failed("vkGetPipelineExecutablePropertiesKHR", r);
    for (std::uint32_t e = 0; e < properties.size(); ++e) {
        PipelineExecutable x;
        x.name = text(properties[e].name);
        x.description = text(properties[e].description);
        x.subgroupSize = properties[e].subgroupSize;
        VkPipelineExecutableInfoKHR executable{};
        executable.sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR;
        executable.pipeline = pipeline;
        executable.executableIndex = e;
        std::vector<VkPipelineExecutableStatisticKHR> statistics;
        if (VkResult r = enumerate(q.statistics, device, &executable, VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR,
                                   statistics);
            !ok(r))
            return failed("vkGetPipelineExecutableStatisticsKHR", r);
        for (const VkPipelineExecutableStatisticKHR& s : statistics) {
            double v = 0;
            switch (s.format) {
            case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR: v = s.value.b32 ? 1 : 0; break;
            case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR: v = double(s.value.i64); break;
            case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR: v = double(s.value.u64); break;
            case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_FLOAT64_KHR: v = s.value.f64; break;
            default: continue;  // a format newer than this code: left out rather than misread
            }
            x.statistics.push_back({text(s.name), text(s.description), v});
        }
        if (withInternals) {
            // Three calls: the count, the sizes, then the data into buffers of those sizes.
            std::vector<VkPipelineExecutableInternalRepresentationKHR> reps;
            if (VkResult r = enumerate(q.internals, device, &executable,
                                       VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INTERNAL_REPRESENTATION_KHR, reps);
                !ok(r))
                return failed("vkGetPipelineExecutableInternalRepresentationsKHR", r);
            std::uint32_t count = std::uint32_t(reps.size());
            std::vector<std::string> data(count);
            for (std::uint32_t i = 0; i < count; ++i) {
                data[i].assign(reps[i].dataSize, '\0');
                reps[i].pData = data[i].data();
            }
            if (VkResult r = q.internals(device, &executable, &count, reps.data()); !ok(r))
                return failed("vkGetPipelineExecutableInternalRepresentationsKHR", r);
            for (std::uint32_t i = 0; i < count && i < reps.size(); ++i) {
                std::string d = data[i].substr(0, std::min<std::size_t>(reps[i].dataSize, data[i].size()));
                const bool isText = reps[i].isText == VK_TRUE;
                if (isText) d.resize(strnlen(d.data(), d.size()));  // up to the terminating null
                x.internals.push_back({text(reps[i].name), text(reps[i].description), isText, std::move(d)});
            }
        }
        out.push_back(std::move(x));
    }
    return out;
}

} // namespace obscura::gpu
