// gpu::shaderNames / gpu::shaderCode: every shader of src/gpu/shaders is listed and is the module the
// library's own passes use; an unknown name is an error that lists the known ones.
#include "gpu/spirv.h"

#include "obscura/error.h"
#include "obscura/gpu_shaders.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

namespace obscura::gpu {
namespace {

TEST(GpuShaderCode, EveryShaderByName) {
    std::vector<std::string> expected;
    for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(OBSCURA_TEST_DATA) / ".." / ".." /
                                                                 "src" / "gpu" / "shaders"))
        if (entry.path().extension() == ".comp") expected.push_back(entry.path().stem().string());
    std::sort(expected.begin(), expected.end());
    ASSERT_FALSE(expected.empty());
    EXPECT_EQ(shaderNames(), expected);
    const ShaderCode gtao = shaderCode("gtao");
    EXPECT_EQ(gtao.words, shaders::gtao.words);
    EXPECT_EQ(gtao.wordCount, shaders::gtao.count);
    EXPECT_EQ(gtao.words[0], 0x07230203u);  // the SPIR-V magic number
    try {
        shaderCode("ssao");
        FAIL() << "no error for an unknown shader";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("shader 'ssao': no such shader (there are: alchemy, "), std::string::npos)
            << e.what();
    }
}

} // namespace
} // namespace obscura::gpu
