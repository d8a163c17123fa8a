// SPIR-V of the compute shaders (src/gpu/shaders/*.comp), compiled by glslc at build time and embedded as
// word arrays (cmake/embed_spirv.cmake writes one source per shader), and the little reflection the host
// needs to check that what it binds is what a shader declares.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace obscura::gpu {

// The numbers of the SPIR-V binary form that the reflection below reads, and the tests that rewrite a
// module (tests/gpu/spirv_edit.h) write (SPIR-V 1.5 specification, section 3).
namespace spirv {
enum : std::uint32_t {
    kMagic = 0x07230203,
    OpExecutionMode = 16,
    OpTypeInt = 21,
    OpTypeFloat = 22,
    OpTypeVector = 23,
    OpTypeSampledImage = 27,
    OpTypeArray = 28,
    OpTypeStruct = 30,
    OpTypePointer = 32,
    OpConstant = 43,
    OpConstantComposite = 44,
    OpSpecConstant = 50,
    OpSpecConstantComposite = 51,
    OpVariable = 59,
    OpDecorate = 71,
    OpMemberDecorate = 72,
    ExecutionModeLocalSize = 17,
    DecorationSpecId = 1,
    DecorationBuiltIn = 11,
    DecorationArrayStride = 6,
    DecorationBinding = 33,
    DecorationDescriptorSet = 34,
    DecorationBlock = 2,
    DecorationBufferBlock = 3,
    StorageClassUniformConstant = 0,
    StorageClassUniform = 2,
    StorageClassStorageBuffer = 12,
    DecorationOffset = 35,
    BuiltInWorkgroupSize = 25,
    StorageClassPushConstant = 9,
};
} // namespace spirv

struct Spirv {
    const std::uint32_t* words;
    std::size_t count;
};

namespace shaders {
extern const Spirv alchemy;              // alchemy.comp
extern const Spirv bilateral_separable;  // bilateral_separable.comp
extern const Spirv gtao;                 // gtao.comp
extern const Spirv normals_from_depth;   // normals_from_depth.comp
extern const Spirv prepare_depth;        // prepare_depth.comp
extern const Spirv bilateral_2d;         // bilateral_2d.comp
extern const Spirv multibounce;          // multibounce.comp
extern const Spirv shade;                // shade.comp
extern const Spirv specular_occlusion;   // specular_occlusion.comp
extern const Spirv reconstruct_interleaved;  // reconstruct_interleaved.comp
extern const Spirv upsample_depth_aware;     // upsample_depth_aware.comp
extern const Spirv gtao_temporal;            // gtao_temporal.comp
extern const Spirv gtao_temporal_fused;      // gtao_temporal_fused.comp
extern const Spirv gtao_mips;                // gtao_mips.comp
extern const Spirv alchemy_blur_row;         // alchemy_blur_row.comp
extern const Spirv bilateral_tiled;          // bilateral_tiled.comp
} // namespace shaders

// The descriptor type of a binding: a storage buffer (std430 block) or a combined image sampler
// (sampler2D, sampler3D).
enum class BindingKind : int { StorageBuffer, SampledImage };

// The binding kinds of a shader whose `count` bindings are all storage buffers.
inline std::vector<BindingKind> storageBuffers(int count) {
    return std::vector<BindingKind>(std::size_t(count), BindingKind::StorageBuffer);
}

// What a compute shader declares: its resources and workgroup size.
struct SpirvLayout {
    int bindings = 0;                    // descriptor bindings (all in set 0 here)
    std::vector<BindingKind> kinds;      // kinds[b]: the type of binding b (b < bindings when they are 0..n-1)
    int specConstants = 0;               // specialization constants the host sets (constant_id decorations,
                                         // less those of the workgroup size below)
    std::uint32_t pushConstantBytes = 0; // size of the push-constant block, 0 if none
    // The BuiltIn WorkgroupSize constant where the module declares one (it wins), else the LocalSize mode. A
    // size given by specialization constants (local_size_x_id) is their defaults, which the host leaves as they
    // are: their constant_ids are sizeSpecIds, and a host that would set one is refused (ComputePipeline).
    std::uint32_t localSize[3] = {0, 0, 0};
    std::vector<std::uint32_t> sizeSpecIds;
    std::vector<std::uint32_t> specIds;  // the constant_ids the host sets, ascending (sizeSpecIds left out)
    // Why the host cannot bind this layout as it binds every shader (one set 0 of bindings 0..n-1, each a single
    // storage buffer or combined image sampler), or empty. ComputePipeline refuses a module that says something:
    // a binding in set 1, a gap, a uniform block or a storage image once passed the count check and crashed the
    // driver or wrote to the wrong buffer.
    std::string unsupported;
};
// Reads the layout from the module's decorations and types. Throws obscura::Error for a malformed module or
// a type it cannot size (only scalars, vectors, arrays with strides and structs occur in push constants).
SpirvLayout reflect(const Spirv& code);

} // namespace obscura::gpu
