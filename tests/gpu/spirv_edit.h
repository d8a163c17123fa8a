// A compiled module with another workgroup size, for the tests of the passes that dispatch by the size their
// module declares (ComputePipeline::kShadersOwnSize) and of the reflection that reads it (SPIR-V 1.5,
// section 2.3 "Physical Layout" and 3 "Binary Form").
#pragma once

#include "gpu/spirv.h"
#include "obscura/gpu.h"
#include "scoped_env.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

namespace obscura::gpu::testing {

// The word index of the (specialization) constant composite decorated BuiltIn WorkgroupSize, which glslang
// emits beside the LocalSize execution mode; 0 where the module has none.
inline std::size_t workgroupSizeComposite(const std::vector<std::uint32_t>& words) {
    std::uint32_t builtin = 0;
    for (std::size_t i = 5; i < words.size() && (words[i] >> 16) != 0; i += words[i] >> 16) {
        const std::uint32_t op = words[i] & 0xffffu, length = words[i] >> 16;
        if (op == spirv::OpDecorate && length >= 4 && words[i + 2] == spirv::DecorationBuiltIn &&
            words[i + 3] == spirv::BuiltInWorkgroupSize)
            builtin = words[i + 1];
        if ((op == spirv::OpConstantComposite || op == spirv::OpSpecConstantComposite) && length == 6 &&
            words[i + 2] == builtin && builtin != 0)
            return i;
    }
    return 0;
}

// The word index of the instruction that defines result id `id` with opcode `op`; 0 where none does.
inline std::size_t definition(const std::vector<std::uint32_t>& words, std::uint32_t op, std::uint32_t id) {
    for (std::size_t i = 5; i < words.size() && (words[i] >> 16) != 0; i += words[i] >> 16)
        if ((words[i] & 0xffffu) == op && (words[i] >> 16) >= 4 && words[i + 2] == id) return i;
    return 0;
}

// The word indices of the OpDecorate instructions with `decoration` and one literal (Binding, DescriptorSet,
// SpecId: the literal is at index + 3), in module order.
inline std::vector<std::size_t> decorations(const std::vector<std::uint32_t>& words, std::uint32_t decoration) {
    std::vector<std::size_t> found;
    for (std::size_t i = 5; i < words.size() && (words[i] >> 16) != 0; i += words[i] >> 16)
        if ((words[i] & 0xffffu) == spirv::OpDecorate && (words[i] >> 16) == 4 && words[i + 2] == decoration)
            found.push_back(i);
    return found;
}

// The module `words` with its workgroup x by y by 1: the LocalSize execution mode rewritten (where
// `executionMode`), and the WorkgroupSize composite given the new size: where its x and y are specialization
// constants (local_size_x_id), their defaults rewritten, as a module compiled with that size would hold them;
// else the composite pointed at two new constants inserted before it (the old ones may have other uses).
// Returns the words unchanged where the module has neither.
inline std::vector<std::uint32_t> withWorkgroupSize(std::vector<std::uint32_t> words, std::uint32_t x,
                                                    std::uint32_t y, bool executionMode = true) {
    // The execution mode precedes the constants, so rewriting it leaves the composite's index as it was.
    for (std::size_t i = 5; executionMode && i < words.size() && (words[i] >> 16) != 0; i += words[i] >> 16)
        if ((words[i] & 0xffffu) == spirv::OpExecutionMode && (words[i] >> 16) >= 6 &&
            words[i + 2] == spirv::ExecutionModeLocalSize) {
            words[i + 3] = x;
            words[i + 4] = y;
        }
    const std::size_t i = workgroupSizeComposite(words);
    if (i == 0) return words;
    const std::size_t specX = definition(words, spirv::OpSpecConstant, words[i + 3]),
                      specY = definition(words, spirv::OpSpecConstant, words[i + 4]);
    if (specX != 0 && specY != 0) {
        words[specX + 3] = x;
        words[specY + 3] = y;
        return words;
    }
    // The scalar type of the old constituents: that of the OpConstant defining the first.
    const std::size_t first = definition(words, spirv::OpConstant, words[i + 3]);
    if (first == 0 || first > i) return words;
    const std::uint32_t scalarType = words[first + 1];
    const std::uint32_t idX = words[3], idY = words[3] + 1;
    words[3] += 2;  // the id bound
    words[i + 3] = idX;
    words[i + 4] = idY;
    const std::vector<std::uint32_t> constants = {(4u << 16) | spirv::OpConstant, scalarType, idX, x,
                                                  (4u << 16) | spirv::OpConstant, scalarType, idY, y};
    words.insert(words.begin() + std::ptrdiff_t(i), constants.begin(), constants.end());
    return words;
}

// Writes a module's words to `file`, as glslc writes a .spv (host byte order, which SPIR-V's magic number
// tells a reader); fails the calling test on a write error.
inline void writeModule(const std::filesystem::path& file, const std::uint32_t* words, std::size_t count) {
    std::ofstream out(file, std::ios::binary);
    out.write(reinterpret_cast<const char*>(words), std::streamsize(count * sizeof(std::uint32_t)));
    out.close();
    EXPECT_TRUE(out.good()) << file;
}

// A validated context of its own whose shader `name` is `words` instead of the embedded module, loaded as a
// user would, through OBSCURA_SHADER_DIR: a folder of this object's own under the test's temporary directory,
// removed with it (the context reads the module when it first makes the pipeline, so the folder lives as long
// as the context). Fails the calling test on a write error.
class ContextWithModule {
public:
    ContextWithModule(const std::string& name, const std::vector<std::uint32_t>& words)
        : dir_(std::filesystem::path(::testing::TempDir()) /
               ("obscura-module-" + name + "-" + std::to_string(::getpid()) + "-" + std::to_string(next()++))) {
        std::filesystem::create_directories(dir_);
        writeModule(dir_ / (name + ".spv"), words.data(), words.size());
        const testutil::ScopedEnv shaderDir("OBSCURA_SHADER_DIR", dir_.string());
        ContextSettings settings;
        settings.validation = true;
        context_ = std::make_unique<Context>(settings);
    }
    ~ContextWithModule() {
        context_.reset();
        std::error_code ignored;
        std::filesystem::remove_all(dir_, ignored);
    }
    ContextWithModule(const ContextWithModule&) = delete;
    ContextWithModule& operator=(const ContextWithModule&) = delete;
    Context& context() { return *context_; }

private:
    static int& next() {
        static int n = 0;
        return n;
    }
    std::filesystem::path dir_;
    std::unique_ptr<Context> context_;
};

} // namespace obscura::gpu::testing
