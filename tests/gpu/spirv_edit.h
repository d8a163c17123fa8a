// A compiled module with another workgroup size, for the tests of the passes that dispatch by the size their
// module declares (ComputePipeline::kShadersOwnSize) and of the reflection that reads it (SPIR-V 1.5,
// section 2.3 "Physical Layout" and 3 "Binary Form").
#pragma once

#include <cstdint>
#include <vector>

namespace obscura::gpu::testing {

// The module `words` with its workgroup x by y by 1: the LocalSize execution mode rewritten (where
// `executionMode`), and the constant decorated BuiltIn WorkgroupSize, which glslang emits beside it, pointed at
// two new constants inserted before it (the old ones may have other uses). Returns the words unchanged where
// the module has neither.
inline std::vector<std::uint32_t> withWorkgroupSize(std::vector<std::uint32_t> words, std::uint32_t x,
                                                    std::uint32_t y, bool executionMode = true) {
    enum : std::uint32_t { OpExecutionMode = 16, OpConstant = 43, OpConstantComposite = 44, OpDecorate = 71 };
    std::uint32_t builtin = 0;
    for (std::size_t i = 5; i < words.size(); i += words[i] >> 16) {
        const std::uint32_t op = words[i] & 0xffffu, length = words[i] >> 16;
        if (length == 0) return words;
        if (op == OpExecutionMode && length >= 6 && words[i + 2] == 17 && executionMode) {  // LocalSize
            words[i + 3] = x;
            words[i + 4] = y;
        }
        if (op == OpDecorate && length >= 4 && words[i + 2] == 11 && words[i + 3] == 25) builtin = words[i + 1];
        if (op == OpConstantComposite && length == 6 && words[i + 2] == builtin && builtin != 0) {
            // The scalar type of the old constituents: that of the OpConstant defining the first.
            std::uint32_t scalarType = 0;
            for (std::size_t j = 5; j < i; j += words[j] >> 16)
                if ((words[j] & 0xffffu) == OpConstant && words[j + 2] == words[i + 3]) scalarType = words[j + 1];
            if (scalarType == 0) return words;
            const std::uint32_t idX = words[3], idY = words[3] + 1;
            words[3] += 2;  // the id bound
            words[i + 3] = idX;
            words[i + 4] = idY;
            const std::vector<std::uint32_t> constants = {(4u << 16) | OpConstant, scalarType, idX, x,
                                                          (4u << 16) | OpConstant, scalarType, idY, y};
            words.insert(words.begin() + std::ptrdiff_t(i), constants.begin(), constants.end());
            break;  // the execution mode precedes the constants
        }
    }
    return words;
}

} // namespace obscura::gpu::testing
