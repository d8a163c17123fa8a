// Minimal SPIR-V reflection (SPIR-V 1.5 specification, section 2.3 "Physical Layout" and 3 "Binary Form"):
// enough to count a compute shader's descriptor bindings (telling combined image samplers from storage
// buffers) and specialization constants and size its push-constant block, as niagara's
// shaders.cpp does, so a pass cannot bind a layout its shader does not declare.
#include "gpu/spirv.h"

#include "obscura/error.h"

#include <algorithm>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace obscura::gpu {

namespace {

using namespace spirv;

[[noreturn]] void malformed(const std::string& why) { fail("SPIR-V", why); }

} // namespace

SpirvLayout reflect(const Spirv& code) {
    if (code.count < 5 || code.words[0] != kMagic) malformed("not a SPIR-V module");
    SpirvLayout layout;
    std::map<std::uint32_t, std::vector<std::uint32_t>> types;  // id -> opcode followed by operands
    std::map<std::uint32_t, std::uint32_t> constants, strides;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> memberOffsets;
    std::map<std::uint32_t, std::uint32_t> bound;  // variable id -> binding
    std::map<std::uint32_t, std::uint32_t> variableTypes;  // variable id -> its pointer type
    std::map<std::uint32_t, std::uint32_t> setOf, blockKind;  // variable -> descriptor set; struct -> (Buffer)Block
    std::set<std::uint32_t> specIds;
    // A specialization constant's result id -> its constant_id, and -> its default value.
    std::map<std::uint32_t, std::uint32_t> specIdOf, specDefaults;
    std::uint32_t pushType = 0;
    // The constant decorated BuiltIn WorkgroupSize, which glslang emits beside the LocalSize execution mode and
    // which wins over it where the two differ (SPIR-V 1.5, section 3.21 "BuiltIn": WorkgroupSize).
    std::uint32_t workgroupSizeId = 0;
    std::map<std::uint32_t, std::vector<std::uint32_t>> composites;  // id -> constituent ids
    std::set<std::uint32_t> specComposites;                          // those that are specialization constants
    for (std::size_t i = 5; i < code.count;) {
        const std::uint32_t words = code.words[i] >> 16, op = code.words[i] & 0xffffu;
        if (words == 0 || i + words > code.count) malformed("truncated instruction");
        const std::uint32_t* a = code.words + i + 1;  // operands
        switch (op) {
        case OpExecutionMode:
            if (words >= 6 && a[1] == ExecutionModeLocalSize) std::copy(a + 2, a + 5, layout.localSize);
            break;
        case OpTypeInt:
        case OpTypeFloat:
        case OpTypeSampledImage:
        case OpTypeVector:
        case OpTypeArray:
        case OpTypeStruct:
        case OpTypePointer: {
            // The fewest words each form has (result id and its operands), so no operand is read past its end.
            const std::uint32_t least = op == OpTypeStruct ? 2 : op == OpTypeVector || op == OpTypeArray || op == OpTypePointer ? 4 : 3;
            if (words < least) malformed("type instruction of " + std::to_string(words) + " words");
            std::vector<std::uint32_t>& t = types[a[0]];
            if (!t.empty()) malformed("type id " + std::to_string(a[0]) + " defined twice");
            t.push_back(op);
            t.insert(t.end(), a + 1, a + words - 1);
            break;
        }
        case OpConstant:
            if (words >= 4) constants[a[1]] = a[2];
            break;
        case OpSpecConstant:
            if (words >= 4) specDefaults[a[1]] = a[2];
            break;
        case OpConstantComposite:
        case OpSpecConstantComposite:
            if (words >= 3) composites[a[1]].assign(a + 2, a + words - 1);
            if (words >= 3 && op == OpSpecConstantComposite) specComposites.insert(a[1]);
            break;
        case OpVariable:
            if (words >= 4 && a[2] == StorageClassPushConstant) pushType = a[0];
            if (words >= 4) variableTypes[a[1]] = a[0];
            break;
        case OpDecorate:
            if (words >= 3 && (a[1] == DecorationBlock || a[1] == DecorationBufferBlock)) blockKind[a[0]] = a[1];
            if (words >= 4 && a[1] == DecorationDescriptorSet) setOf[a[0]] = a[2];
            if (words >= 4 && a[1] == DecorationBinding) bound[a[0]] = a[2];
            if (words >= 4 && a[1] == DecorationSpecId) {
                specIds.insert(a[2]);
                specIdOf[a[0]] = a[2];
            }
            if (words >= 4 && a[1] == DecorationArrayStride) strides[a[0]] = a[2];
            if (words >= 4 && a[1] == DecorationBuiltIn && a[2] == BuiltInWorkgroupSize) workgroupSizeId = a[0];
            break;
        case OpMemberDecorate:
            if (words >= 5 && a[2] == DecorationOffset) memberOffsets[{a[0], a[1]}] = a[3];
            break;
        default: break;
        }
        i += words;
    }
    if (workgroupSizeId != 0) {
        const auto size = composites.find(workgroupSizeId);
        if (size == composites.end() || size->second.size() != 3)
            malformed("WorkgroupSize is not a constant 3-component vector");
        // A component of a specialization composite may be a specialization constant (local_size_x_id): the
        // device runs its default, since the host sets only its variants' constant_ids (ComputePipeline).
        const bool specialized = specComposites.count(workgroupSizeId) != 0;
        for (int c = 0; c < 3; ++c) {
            const std::uint32_t id = size->second[std::size_t(c)];
            const auto value = constants.find(id);
            const auto byDefault = specDefaults.find(id);
            if (value != constants.end()) {
                layout.localSize[c] = value->second;
            } else if (specialized && byDefault != specDefaults.end() && specIdOf.count(id)) {
                layout.localSize[c] = byDefault->second;
                layout.sizeSpecIds.push_back(specIdOf[id]);
            } else {
                malformed("WorkgroupSize has a component that is neither a constant nor a specialization constant's "
                          "default");
            }
        }
    }
    const auto unsupported = [&](const std::string& why) {
        if (layout.unsupported.empty()) layout.unsupported = why;
    };
    layout.bindings = int(bound.size());
    for (const std::uint32_t id : std::set<std::uint32_t>(layout.sizeSpecIds.begin(), layout.sizeSpecIds.end()))
        specIds.erase(id);
    layout.specConstants = int(specIds.size());
    layout.specIds.assign(specIds.begin(), specIds.end());
    // Each binding's kind from what its variable points to: a storage buffer is a block in the StorageBuffer
    // class (or, in SPIR-V before 1.3, a BufferBlock in the Uniform class); a combined image sampler is a
    // UniformConstant OpTypeSampledImage. Anything else (a uniform block, a storage image, an array of either)
    // is a descriptor the host never writes.
    std::set<std::uint32_t> numbers;
    for (const auto& [variable, binding] : bound) {
        const std::string which = "binding " + std::to_string(binding);
        const auto set = setOf.find(variable);
        if (set != setOf.end() && set->second != 0)
            unsupported(which + " is in descriptor set " + std::to_string(set->second) + ", the host binds set 0 only");
        if (!numbers.insert(binding).second) unsupported(which + " is declared twice");
        if (binding >= (1u << 16)) {
            unsupported(which + " is out of the host's range");
            continue;
        }
        if (binding >= layout.kinds.size()) layout.kinds.resize(binding + 1, BindingKind::StorageBuffer);
        const auto pointer = types.find(variableTypes[variable]);
        if (pointer == types.end() || pointer->second.size() < 3 || pointer->second[0] != OpTypePointer) {
            unsupported(which + " is not a variable of pointer type");
            continue;
        }
        const std::uint32_t storage = pointer->second[1];
        const auto pointee = types.find(pointer->second[2]);
        const std::uint32_t pointeeOp = pointee == types.end() || pointee->second.empty() ? 0 : pointee->second[0];
        const auto block = blockKind.find(pointer->second[2]);
        const std::uint32_t decoration = block == blockKind.end() ? 0 : block->second;
        if (storage == StorageClassUniformConstant && pointeeOp == OpTypeSampledImage)
            layout.kinds[binding] = BindingKind::SampledImage;
        else if (pointeeOp == OpTypeStruct && ((storage == StorageClassStorageBuffer && decoration == DecorationBlock) ||
                                               (storage == StorageClassUniform && decoration == DecorationBufferBlock)))
            layout.kinds[binding] = BindingKind::StorageBuffer;
        else
            unsupported(which + " is neither a storage buffer nor a combined image sampler (a uniform block, a "
                                "storage image or an array?)");
    }
    if (!numbers.empty() && *numbers.rbegin() + 1 != numbers.size())
        unsupported("bindings are not numbered 0 to " + std::to_string(numbers.size() - 1) + " (the highest is " +
                    std::to_string(*numbers.rbegin()) + ")");
    // In 64-bit arithmetic and at most 16 types deep: a struct that contains itself once recursed until the stack
    // overflowed, and sizes past the 32-bit range are no push-constant block.
    std::function<std::uint64_t(std::uint32_t, int)> sizeOf = [&](std::uint32_t id, int depth) -> std::uint64_t {
        if (depth > 16) malformed("push-constant type nested more than 16 deep (or containing itself)");
        const auto it = types.find(id);
        if (it == types.end() || it->second.empty()) malformed("push constant of unknown type");
        const std::vector<std::uint32_t>& t = it->second;
        switch (t[0]) {
        case OpTypeInt:
        case OpTypeFloat: return t[1] / 8;
        case OpTypeVector: return std::uint64_t(t[2]) * sizeOf(t[1], depth + 1);
        case OpTypeArray:
            if (!strides.count(id) || !constants.count(t[2])) malformed("push-constant array without a stride");
            return std::uint64_t(strides[id]) * constants[t[2]];
        case OpTypeStruct: {
            std::uint64_t end = 0;
            for (std::uint32_t m = 0; m + 1 < t.size(); ++m) {
                const auto offset = memberOffsets.find({id, m});
                if (offset == memberOffsets.end()) malformed("push-constant member without an offset");
                end = std::max(end, offset->second + sizeOf(t[m + 1], depth + 1));
            }
            return end;
        }
        default: malformed("push constant of a type that has no size here");
        }
    };
    if (pushType) {
        const auto it = types.find(pushType);
        if (it == types.end() || it->second.size() < 3 || it->second[0] != OpTypePointer)
            malformed("push-constant variable is not a pointer");
        const std::uint64_t bytes = sizeOf(it->second[2], 0);
        if (bytes > 0xffffffffu) malformed("push-constant block of " + std::to_string(bytes) + " bytes");
        layout.pushConstantBytes = std::uint32_t(bytes);
    }
    return layout;
}

} // namespace obscura::gpu
